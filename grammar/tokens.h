// Internal to grammar/: lexing and the newline filter between the lexer and the parser.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "grammar/ast/diagnostic.h"
#include "grammar/input.h"
#include "grammar/parse.h"

namespace tranche::grammar {

struct Tokens {
  std::unique_ptr<antlr4::Lexer> lexer;              // the tokens' source: it must outlive the parse
  std::vector<std::unique_ptr<antlr4::Token>> list;  // ends with EOF
  std::vector<ast::Span> unclosed;  // brackets still open at the end of the input, outermost first
  int errors = 0;                   // lexical errors reported
  bool fatal = false;               // the input cannot be parsed (nesting limit, unterminated `"""`)
};

// Lexes `input`. Newlines that cannot end a statement are dropped (inside `()`/`[]`, after an
// operator, before `{`, `else`, `and`...); a newline is added after a `}` followed by more
// code on its line. With `expression_only`, every newline is dropped (a template's `{...}`).
Tokens lex(Input& input, diag::Sink& sink, const ParseOptions& options, bool expression_only);

// Whether a token of this type ends an operand (so that a `-` after it is binary).
bool ends_operand(size_t type);

// How a token type reads in a message: "`{`", "a name", "a newline", "end of file".
std::string token_kind_name(const antlr4::dfa::Vocabulary& vocabulary, size_t type);
// How a token reads as what was found: its text for names and symbols.
std::string found_name(const antlr4::Token* token);

}  // namespace tranche::grammar
