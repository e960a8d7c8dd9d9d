// Internal to grammar/: turns ANTLR's syntax errors into our diagnostics (E0004) with human
// token names ("expected `{`, found a newline"), and stops after a fixed number of them.
#pragma once

#include <antlr4-runtime.h>

#include <vector>

#include "grammar/ast/diagnostic.h"
#include "grammar/input.h"

namespace tranche::grammar {

// Thrown (and caught in parse.cpp) to stop parsing once the error budget is spent.
struct TooManyErrors {};

class ReportingStrategy : public antlr4::DefaultErrorStrategy {
 public:
  ReportingStrategy(const Input& input, diag::Sink& sink, std::vector<ast::Span> unclosed, int budget)
      : input_(input), sink_(sink), unclosed_(std::move(unclosed)), budget_(budget) {}

  int reported() const { return reported_; }

 protected:
  void reportNoViableAlternative(antlr4::Parser* parser, const antlr4::NoViableAltException& e) override;
  void reportInputMismatch(antlr4::Parser* parser, const antlr4::InputMismatchException& e) override;
  void reportFailedPredicate(antlr4::Parser* parser, const antlr4::FailedPredicateException& e) override;
  void reportUnwantedToken(antlr4::Parser* parser) override;
  void reportMissingToken(antlr4::Parser* parser) override;

 private:
  void report(antlr4::Parser* parser, antlr4::Token* found, const antlr4::misc::IntervalSet& expected);

  const Input& input_;
  diag::Sink& sink_;
  std::vector<ast::Span> unclosed_;
  int budget_;
  int reported_ = 0;
};

}  // namespace tranche::grammar
