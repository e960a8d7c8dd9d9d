// The Tranche rule language. docs/language.md is the user-facing reference; this grammar is
// only the syntax: names, types, units, stages and statement placement are checked by
// compiler/, which gives better messages than a parser can.
//
// Newlines end statements. grammar/tokens.cpp drops the newlines that cannot end one (inside
// brackets, after an operator, before `{`, `else`, `and`...) and adds one after a `}` that is
// followed by more code on the same line, so the parser only ever sees `sep` between statements.
grammar Rules;

file : sep* (item (sep+ item)* sep*)? EOF ;

// Entry point for a `{expr}` inside a template string and for a `--set` value.
exprOnly : expr EOF ;

item
  : USE STRING                                                     # useItem
  | RULE STRING? (WHEN expr)? block                                # ruleItem
  | ON name DOT name (WHEN expr)? APPEND? block                    # onItem
  | PARAM name ASSIGN expr                                         # paramItem
  ;

block : LBRACE sep* (stmt (sep+ stmt)* sep*)? RBRACE ;

stmt
  : name ASSIGN expr                                               # assignStmt
  | hook=(BEFORE | AFTER) name APPEND? block                       # hookStmt
  | REPLACE name block                                             # replaceStmt
  | GCODE text=(STRING | TRIPLE_STRING)                            # gcodeStmt
  | COMMENT text=(STRING | TRIPLE_STRING)                          # commentStmt
  | LET name ASSIGN expr                                           # letStmt
  | ifStmt                                                         # ifStatement
  | FOR name IN expr (DOTDOT expr)? block                          # forStmt
  | MOVE TO LPAREN expr COMMA expr RPAREN kind=(TRAVEL | EXTRUDE)?
      (WITH moveOption (COMMA moveOption)*)?                       # moveStmt
  | DEFAULT                                                        # defaultStmt
  | OFFSET expr                                                    # offsetStmt
  | REVERSE                                                        # reverseStmt
  | RETRACT                                                        # retractStmt
  ;

ifStmt : IF expr block (ELSE (block | ifStmt))? ;

moveOption : name ASSIGN expr ;

// Alternatives from the tightest to the loosest binding (ANTLR's order of precedence).
expr
  : primary                                                        # primaryExpr
  | MINUS expr                                                     # negExpr
  | expr op=(STAR | SLASH | MOD) expr                              # mulExpr
  | expr op=(PLUS | MINUS) expr                                    # addExpr
  | expr IN expr DOTDOT expr                                       # inRangeExpr
  | expr IN LPAREN expr (COMMA expr)* RPAREN                        # inSetExpr
  | expr op=(EQ | NE | LT | LE | GT | GE) expr                     # cmpExpr
  | NOT expr                                                       # notExpr
  | expr AND expr                                                  # andExpr
  | expr OR expr                                                   # orExpr
  | IF expr THEN expr ELSE expr                                    # ifExpr
  ;

primary
  : NUMBER unit?                                                   # numberLit
  | value=(TRUE | FALSE)                                           # boolLit
  | text=(STRING | TRIPLE_STRING)                                  # stringLit
  | name LPAREN name IN expr DOTDOT expr COLON expr RPAREN          # quantifierExpr
  | name LPAREN (expr (COMMA expr)*)? RPAREN                       # callExpr
  | name LBRACK expr RBRACK DOT name                               # layerAccess
  | name (DOT name)?                                               # nameRef
  | LPAREN expr RPAREN                                             # parenExpr
  ;

// A unit directly after a number: `mm`, `mm2`, `mm/s`, `°C`, `%`... (checked by compiler/).
unit : UNIT | DEGREE | PERCENT | IDENT ;

name : IDENT ;

sep : NL | SEMI ;

USE : 'use' ;
PARAM : 'param' ;
RULE : 'rule' ;
WHEN : 'when' ;
ON : 'on' ;
APPEND : 'append' ;
BEFORE : 'before' ;
AFTER : 'after' ;
REPLACE : 'replace' ;
GCODE : 'gcode' ;
COMMENT : 'comment' ;
LET : 'let' ;
IF : 'if' ;
THEN : 'then' ;
ELSE : 'else' ;
FOR : 'for' ;
IN : 'in' ;
MOVE : 'move' ;
TO : 'to' ;
TRAVEL : 'travel' ;
EXTRUDE : 'extrude' ;
WITH : 'with' ;
DEFAULT : 'default' ;
OFFSET : 'offset' ;
REVERSE : 'reverse' ;
RETRACT : 'retract' ;
AND : 'and' ;
OR : 'or' ;
NOT : 'not' ;
MOD : 'mod' ;
TRUE : 'true' ;
FALSE : 'false' ;

// Units that contain a slash or a symbol are single tokens, so `0.2 mm / layer.height` is a
// division while `20 mm/s` is a speed. Plain units (`mm`, `deg`, `s`, `C`) are identifiers.
UNIT : 'mm/s2' | 'mm/s²' | 'mm/s' | 'mm3/s' | 'mm³/s' | '°C' ;
DEGREE : '°' ;
PERCENT : '%' ;

NUMBER : DIGITS ('.' DIGITS)? EXPONENT? | '.' DIGITS EXPONENT? ;
fragment DIGITS : [0-9]+ ;
fragment EXPONENT : [eE] [+-]? [0-9]+ ;

IDENT : [\p{L}_] [\p{L}\p{N}_]* ;

TRIPLE_STRING : '"""' .*? '"""' ;
STRING : '"' ('\\' ~[\r\n] | ~["\\\r\n])* '"' ;
// A string that reaches the end of its line: reported by grammar/tokens.cpp, never parsed.
UNTERMINATED_STRING : '"' ('\\' ~[\r\n] | ~["\\\r\n])* ;

EQ : '==' ;
NE : '!=' ;
LE : '<=' ;
GE : '>=' ;
LT : '<' ;
GT : '>' ;
ASSIGN : '=' ;
PLUS : '+' ;
MINUS : '-' ;
STAR : '*' ;
SLASH : '/' ;
LPAREN : '(' ;
RPAREN : ')' ;
LBRACK : '[' ;
RBRACK : ']' ;
LBRACE : '{' ;
RBRACE : '}' ;
COMMA : ',' ;
DOTDOT : '..' ;
DOT : '.' ;
COLON : ':' ;
SEMI : ';' ;

NL : '\r\n' | '\n' | '\r' ;
WS : [ \t\f\u000B\u00A0\uFEFF]+ -> skip ;
LINE_COMMENT : '#' ~[\r\n]* -> skip ;

// Anything else becomes one token that grammar/tokens.cpp reports, so the lexer never fails.
ERROR_CHAR : . ;
