#include "grammar/tokens.h"

#include <fmt/format.h>

#include "RulesLexer.h"

namespace tranche::grammar {

using L = RulesLexer;

namespace {

// After these a newline continues the statement (`speed = 20 mm/s *` ⏎ `2`).
bool continues_after(size_t t) {
  switch (t) {
    case L::PLUS:
    case L::MINUS:
    case L::STAR:
    case L::SLASH:
    case L::MOD:
    case L::EQ:
    case L::NE:
    case L::LT:
    case L::LE:
    case L::GT:
    case L::GE:
    case L::AND:
    case L::OR:
    case L::NOT:
    case L::IN:
    case L::DOTDOT:
    case L::ASSIGN:
    case L::COMMA:
    case L::DOT:
    case L::COLON:
    case L::LPAREN:
    case L::LBRACK:
    case L::LBRACE:
    case L::THEN:
    case L::ELSE:
    case L::IF:
    case L::WHEN:
    case L::USE:
    case L::PARAM:
    case L::RULE:
    case L::ON:
    case L::BEFORE:
    case L::AFTER:
    case L::REPLACE:
    case L::GCODE:
    case L::COMMENT:
    case L::LET:
    case L::FOR:
    case L::MOVE:
    case L::TO:
    case L::WITH:
    case L::OFFSET:
    case L::NL:
    case L::SEMI:
      return true;
    default:
      return false;
  }
}

// A newline is a separator only if the next line starts like a statement or an item.
bool starts_statement(size_t t) {
  switch (t) {
    case L::IDENT:
    case L::USE:
    case L::PARAM:
    case L::RULE:
    case L::ON:
    case L::BEFORE:
    case L::AFTER:
    case L::REPLACE:
    case L::GCODE:
    case L::COMMENT:
    case L::LET:
    case L::IF:
    case L::FOR:
    case L::MOVE:
    case L::DEFAULT:
    case L::OFFSET:
    case L::REVERSE:
    case L::RETRACT:
    case L::RBRACE:
    case L::SEMI:
    case L::NUMBER:
    case L::STRING:
    case L::TRIPLE_STRING:
    case L::TRUE:
    case L::FALSE:
    case antlr4::Token::EOF:
      return true;
    default:
      return false;
  }
}

}  // namespace

bool ends_operand(size_t t) {
  switch (t) {
    case L::IDENT:
    case L::NUMBER:
    case L::RPAREN:
    case L::RBRACK:
    case L::TRUE:
    case L::FALSE:
    case L::STRING:
    case L::TRIPLE_STRING:
    case L::UNIT:
    case L::DEGREE:
    case L::PERCENT:
      return true;
    default:
      return false;
  }
}

namespace {

std::string char_help(std::string_view c) {
  if (c == "'") return "strings are written in double quotes: \"...\"";
  if (c == "&") return "write `and`";
  if (c == "|") return "write `or`";
  if (c == "!") return "write `not`, or `!=` for \"not equal\"";
  if (c == "≤") return "write `<=`";
  if (c == "≥") return "write `>=`";
  if (c == "≠") return "write `!=`";
  if (c == "×") return "write `*`";
  if (c == ":")
    return "set a property with `=` (`speed = 20 mm/s`); a `:` is only used for the format of a template value: "
           "`{layer.z:.2}`";
  if (c == "$") return "values are written as they are, without `$`: `layer.z`, and `{layer.z}` in a template";
  if (c == "?") return "a choice is written `if C then A else B`";
  if (c == "^") return "there is no power operator: write `x * x`";
  return {};
}

std::unique_ptr<antlr4::CommonToken> synthetic_newline(const antlr4::Token& after) {
  auto t = std::make_unique<antlr4::CommonToken>(
      std::make_pair(after.getTokenSource(), after.getInputStream()), static_cast<size_t>(L::NL),
      antlr4::Token::DEFAULT_CHANNEL, after.getStartIndex(), after.getStopIndex());
  t->setLine(after.getLine());
  t->setCharPositionInLine(after.getCharPositionInLine());
  t->setText("\n");
  return t;
}

// Every token of the input, in `raw`: a run of bad characters is one diagnostic (E0002), an
// unterminated string one more (E0003); a `"""` never closed makes the rest unreadable (fatal).
void read_tokens(antlr4::Lexer& lexer, Input& input, diag::Sink& sink, const ParseOptions& options,
                 Tokens& out, std::vector<std::unique_ptr<antlr4::Token>>& raw) {
  for (;;) {
    std::unique_ptr<antlr4::Token> t = lexer.nextToken();
    size_t type = t->getType();
    if (type == L::ERROR_CHAR) {
      // One diagnostic for a run of adjacent bad characters.
      size_t start = t->getStartIndex(), stop = t->getStopIndex();
      std::string text = t->getText();
      for (;;) {
        auto next = lexer.nextToken();
        if (next->getType() == L::ERROR_CHAR && next->getStartIndex() == stop + 1) {
          stop = next->getStopIndex();
          continue;
        }
        t = std::move(next);
        break;
      }
      if (++out.errors <= options.max_errors) {
        std::string shown = stop > start ? input.getText(antlr4::misc::Interval(start, stop)) : text;
        auto& d = sink.error("E0002", input.span(start, stop),
                             fmt::format("unexpected character{} `{}`", stop > start ? "s" : "", shown),
                             "not part of the rule language");
        if (std::string h = char_help(text); !h.empty()) d.help(h);
      }
      type = t->getType();
      if (type == L::ERROR_CHAR) continue;  // cannot happen: the loop above consumed the run
    }
    if (type == L::STRING && t->getText() == "\"\"" && input.char_at(t->getStopIndex() + 1) == '"') {
      // `"""` that never closes: TRIPLE_STRING did not match, so the lexer fell back to `""`.
      ++out.errors;
      sink.error("E0003", input.span(t->getStartIndex(), t->getStartIndex() + 2), "unterminated string",
                 "this `\"\"\"` is never closed")
          .help("end the text with `\"\"\"`");
      out.fatal = true;  // the rest of the file is inside the string
      return;
    }
    if (type == L::UNTERMINATED_STRING) {
      if (++out.errors <= options.max_errors) {
        sink.error("E0003", input.span(t.get()), "unterminated string", "this string has no closing `\"`")
            .help("close it on the same line, or use `\"\"\"` for text on several lines");
      }
      continue;
    }
    raw.push_back(std::move(t));
    if (type == antlr4::Token::EOF) break;
  }
}

// The tokens the parser sees, in `out.list`: newlines only where a statement ends (a `}` not
// followed by one gets one), and the nesting of brackets and prefix operators checked (E0005).
void layout_tokens(std::vector<std::unique_ptr<antlr4::Token>>& raw, Input& input, diag::Sink& sink,
                   const ParseOptions& options, bool expression_only, Tokens& out) {
  // The newline filter and the nesting check, in one pass with one token of lookahead.
  struct Open {
    size_t type;
    ast::Span span;
    int prefixes;
  };
  std::vector<Open> open;
  int prefixes = 0, total_prefixes = 0, parens = 0;
  size_t prev = L::NL;  // the start of input behaves like the start of a line
  for (size_t i = 0; i < raw.size(); ++i) {
    auto& t = raw[i];
    size_t type = t->getType();
    size_t next = i + 1 < raw.size() ? raw[i + 1]->getType() : antlr4::Token::EOF;
    if (type == L::NL) {
      if (expression_only || parens > 0 || continues_after(prev)) continue;
      size_t k = i + 1;
      while (k < raw.size() && raw[k]->getType() == L::NL) ++k;
      if (!starts_statement(k < raw.size() ? raw[k]->getType() : antlr4::Token::EOF)) continue;
      total_prefixes -= prefixes;  // a statement ends: its prefix operators are closed
      prefixes = 0;
      out.list.push_back(std::move(t));
      prev = type;
      continue;
    }

    bool deeper = false;
    if (type == L::LPAREN || type == L::LBRACK || type == L::LBRACE) {
      open.push_back(Open{type, input.span(t.get()), prefixes});
      prefixes = 0;
      if (type != L::LBRACE) ++parens;
      deeper = true;
    } else if (type == L::RPAREN || type == L::RBRACK || type == L::RBRACE) {
      size_t want = type == L::RPAREN ? L::LPAREN : type == L::RBRACK ? L::LBRACK : L::LBRACE;
      if (!open.empty() && open.back().type == want) {
        total_prefixes -= prefixes;
        prefixes = open.back().prefixes;
        if (want != L::LBRACE) --parens;
        open.pop_back();
      }
    } else if (type == L::SEMI || type == L::COMMA) {
      total_prefixes -= prefixes;
      prefixes = 0;
    } else if ((type == L::MINUS && !ends_operand(prev)) || type == L::NOT ||
               (type == L::IF && prev != L::NL && prev != L::SEMI && prev != L::LBRACE)) {
      // Each nests the parser one level deeper until the statement ends (`else if` chains too).
      ++prefixes;
      ++total_prefixes;
      deeper = true;
    }
    if (deeper && static_cast<int>(open.size()) + total_prefixes > options.max_nesting) {
      ++out.errors;
      sink.error("E0005", input.span(t.get()),
                 fmt::format("nesting is too deep: more than {} brackets and prefix operators open at once",
                             options.max_nesting),
                 "the limit is reached here")
          .help("split the expression into several rules or `let` steps");
      out.fatal = true;
      return;
    }

    out.list.push_back(std::move(t));
    prev = type;
    if (type == L::RBRACE && !expression_only && next != L::NL && next != L::SEMI && next != L::RBRACE &&
        next != L::ELSE && next != antlr4::Token::EOF) {
      out.list.push_back(synthetic_newline(*out.list.back()));
      prev = L::NL;
    }
  }
  for (const auto& o : open) out.unclosed.push_back(o.span);
}

}  // namespace

Tokens lex(Input& input, diag::Sink& sink, const ParseOptions& options, bool expression_only) {
  Tokens out;
  out.lexer = std::make_unique<RulesLexer>(&input);
  antlr4::Lexer& lexer = *out.lexer;
  lexer.removeErrorListeners();  // ERROR_CHAR catches every character no other rule does
  std::vector<std::unique_ptr<antlr4::Token>> raw;
  read_tokens(lexer, input, sink, options, out, raw);
  if (out.fatal) return out;
  layout_tokens(raw, input, sink, options, expression_only, out);
  return out;
}

std::string token_kind_name(const antlr4::dfa::Vocabulary& vocabulary, size_t type) {
  switch (type) {
    case antlr4::Token::EOF:
      return "end of file";
    case L::NL:
      return "a newline";
    case L::IDENT:
      return "a name";
    case L::NUMBER:
      return "a number";
    case L::STRING:
    case L::TRIPLE_STRING:
    case L::UNTERMINATED_STRING:
      return "a string";
    case L::UNIT:
    case L::DEGREE:
    case L::PERCENT:
      return "a unit";
    default:
      break;
  }
  std::string lit = vocabulary.getLiteralName(type);
  if (lit.size() >= 2 && lit.front() == '\'') return fmt::format("`{}`", lit.substr(1, lit.size() - 2));
  return "a token";
}

std::string found_name(const antlr4::Token* token) {
  if (token == nullptr) return "end of file";
  size_t type = token->getType();
  switch (type) {
    case antlr4::Token::EOF:
    case L::NL:
    case L::STRING:
    case L::TRIPLE_STRING:
    case L::UNTERMINATED_STRING:
      return type == antlr4::Token::EOF ? "end of file" : type == L::NL ? "a newline" : "a string";
    default:
      break;
  }
  std::string text = token->getText();
  if (text.size() > 24) text = text.substr(0, 21) + "...";
  return fmt::format("`{}`", text);
}

}  // namespace tranche::grammar
