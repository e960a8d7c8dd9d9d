#include "grammar/errors.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "RulesLexer.h"
#include "grammar/tokens.h"

namespace tranche::grammar {

using L = RulesLexer;

namespace {

// Expected token sets are summarised the way a user thinks of them.
std::string describe_expected(const antlr4::dfa::Vocabulary& vocab, const antlr4::misc::IntervalSet& set) {
  std::set<size_t> types;
  for (ssize_t t : set.toList())
    if (t >= 0 || t == -1) types.insert(static_cast<size_t>(t));
  types.erase(L::UNTERMINATED_STRING);
  types.erase(L::ERROR_CHAR);
  types.erase(L::WS);
  types.erase(L::LINE_COMMENT);

  std::vector<std::string> names;
  auto take = [&](std::initializer_list<size_t> group, size_t needed, const char* name) {
    size_t have = 0;
    for (size_t g : group) have += types.count(g);
    if (have < needed) return;
    for (size_t g : group) types.erase(g);
    names.emplace_back(name);
  };
  take({L::NUMBER, L::IDENT, L::LPAREN, L::MINUS, L::NOT, L::IF, L::TRUE, L::FALSE, L::STRING,
        L::TRIPLE_STRING},
       3, "an expression");
  take({L::GCODE, L::COMMENT, L::LET, L::FOR, L::MOVE, L::DEFAULT, L::OFFSET, L::REVERSE, L::BEFORE, L::AFTER,
        L::REPLACE, L::IDENT, L::IF},
       4, "a statement");
  take({L::USE, L::RULE, L::ON}, 3, "`rule`, `on` or `use`");
  take({L::EQ, L::NE, L::LT, L::LE, L::GT, L::GE, L::PLUS, L::STAR, L::SLASH, L::MOD, L::AND, L::OR, L::IN},
       4, "an operator");
  take({L::UNIT, L::DEGREE, L::PERCENT}, 2, "a unit");
  bool separator = types.count(L::NL) || types.count(L::SEMI);
  types.erase(L::NL);
  types.erase(L::SEMI);
  for (size_t t : types)
    names.push_back(t == static_cast<size_t>(-1) ? "end of file" : token_kind_name(vocab, t));
  if (separator) names.emplace_back("a newline");
  if (names.empty()) return {};
  if (names.size() > 6) names.resize(6);
  if (names.size() == 1) return names[0];
  std::string s;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i) s += i + 1 == names.size() ? " or " : ", ";
    s += names[i];
  }
  return s;
}

}  // namespace

void ReportingStrategy::report(antlr4::Parser* parser, antlr4::Token* found,
                               const antlr4::misc::IntervalSet& expected) {
  if (reported_ >= budget_) throw TooManyErrors{};
  ++reported_;
  std::string want = describe_expected(parser->getVocabulary(), expected);
  std::string got = found_name(found);
  std::string message =
      want.empty() ? fmt::format("unexpected {}", got) : fmt::format("expected {}, found {}", want, got);
  std::string label = want.empty() ? "not expected here" : fmt::format("expected {}", want);
  auto& d = sink_.error("E0004", input_.span(found), std::move(message), std::move(label));
  size_t type = found ? found->getType() : antlr4::Token::EOF;
  if (type == L::ASSIGN && !expected.contains(static_cast<size_t>(L::ASSIGN)))
    d.help("to compare two values, write `==`").fix(input_.span(found), "==");
  if (type == antlr4::Token::EOF && !unclosed_.empty())
    d.label(unclosed_.back(),
            fmt::format("this `{}` is never closed", input_.sources().text(unclosed_.back())));
  // The tokens around the one found (found is null only at the end of the input).
  antlr4::TokenStream* stream = parser->getTokenStream();
  size_t index = found ? found->getTokenIndex() : 0;
  antlr4::Token* prev = found && index > 0 ? stream->get(index - 1) : nullptr;
  antlr4::Token* next = found && index + 1 < stream->size() ? stream->get(index + 1) : nullptr;
  size_t before = prev ? prev->getType() : antlr4::Token::EOF;
  size_t after = next ? next->getType() : antlr4::Token::EOF;
  bool statement_end = expected.contains(static_cast<size_t>(L::NL)) || expected.contains(static_cast<size_t>(L::RBRACE));
  if (type == L::IDENT && expected.contains(static_cast<size_t>(L::WHEN))) {
    d.help("a rule's condition follows `when`: `rule \"name\" when CONDITION { ... }`")
        .fix(input_.span(found), "when " + found->getText());
  } else if (type == L::IF && expected.contains(static_cast<size_t>(L::WHEN))) {
    d.help("a rule's condition follows `when`, not `if`").fix(input_.span(found), "when");
  } else if (type == L::IDENT && expected.contains(static_cast<size_t>(L::LBRACE)) &&
             !expected.contains(static_cast<size_t>(L::IDENT))) {
    d.help("a rule's actions go inside `{ ... }`");
  } else if (type == L::LBRACE && expected.contains(static_cast<size_t>(L::DOT))) {
    d.help("an event is `LEVEL.start` or `LEVEL.end`: `on layer.start { ... }`");
  } else if (type == L::COLON) {
    d.help("set a property with `=` (`speed = 20 mm/s`); a `:` follows the range of `any(i in 1..3: ...)` and "
           "comes before the format of a template value: `{layer.z:.2}`")
        .fix(input_.span(found), " =");
  } else if (type == L::PERCENT) {
    d.help("the remainder of a division is written `mod`: `layer.index mod 2 == 0`; `%` follows a number: `50%`")
        .fix(input_.span(found), "mod");
  } else if (type == L::COMMA && statement_end) {
    d.help("statements are separated by a newline or `;`, not `,`").fix(input_.span(found), ";");
  } else if (type == L::LBRACK && (before == L::EQ || before == L::IN || before == L::NE)) {
    d.help("a list of values is written in parentheses after `in`: `layer.index in (1, 2, 3)`");
  } else if (after == L::ASSIGN && (type == L::STAR || type == L::PLUS || type == L::MINUS || type == L::SLASH)) {
    d.help(fmt::format("there is no `{0}=`: write `speed = speed {0} 50%`", found->getText()));
  } else if ((type == L::RULE || type == L::ON || type == L::USE || type == L::PARAM) && prev) {
    // A rule, `on`, `use` or `param` inside a block: the block before it was never closed.
    std::vector<antlr4::Token*> open;
    for (size_t k = 0; k < index; ++k) {
      antlr4::Token* t = stream->get(k);
      if (t->getType() == L::LBRACE) open.push_back(t);
      if (t->getType() == L::RBRACE && !open.empty()) open.pop_back();
    }
    if (!open.empty()) {
      d.label(input_.span(open.front()), "this `{` is not closed before the next item");
      d.help(fmt::format("close the block with `}}` before `{}`", found->getText()));
    }
  }
  if (reported_ == budget_) d.note(fmt::format("stopping after {} syntax errors in this file", budget_));
}

void ReportingStrategy::reportNoViableAlternative(antlr4::Parser* parser,
                                                  const antlr4::NoViableAltException& e) {
  report(parser, e.getOffendingToken(), parser->getExpectedTokens());
}

void ReportingStrategy::reportInputMismatch(antlr4::Parser* parser, const antlr4::InputMismatchException& e) {
  report(parser, e.getOffendingToken(), e.getExpectedTokens());
}

void ReportingStrategy::reportFailedPredicate(antlr4::Parser* parser,
                                              const antlr4::FailedPredicateException& e) {
  report(parser, e.getOffendingToken(), parser->getExpectedTokens());
}

void ReportingStrategy::reportUnwantedToken(antlr4::Parser* parser) {
  if (inErrorRecoveryMode(parser)) return;
  beginErrorCondition(parser);
  report(parser, parser->getCurrentToken(), getExpectedTokens(parser));
}

void ReportingStrategy::reportMissingToken(antlr4::Parser* parser) {
  if (inErrorRecoveryMode(parser)) return;
  beginErrorCondition(parser);
  report(parser, parser->getCurrentToken(), getExpectedTokens(parser));
}

}  // namespace tranche::grammar
