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
  if (type == L::ASSIGN && expected.contains(static_cast<size_t>(L::EQ)))
    d.help("to compare two values, write `==`").fix(input_.span(found), "==");
  if (type == antlr4::Token::EOF && !unclosed_.empty())
    d.label(unclosed_.back(),
            fmt::format("this `{}` is never closed", input_.sources().text(unclosed_.back())));
  if (type == L::IDENT && expected.contains(static_cast<size_t>(L::LBRACE)) &&
      !expected.contains(static_cast<size_t>(L::IDENT)))
    d.help("a rule's actions go inside `{ ... }`");
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
