// Internal to grammar/: the visitor that turns an error-free parse tree into our AST. Values
// travel through antlrcpp::Any as raw owning pointers that are wrapped at once.
#pragma once

#include "RulesBaseVisitor.h"
#include "grammar/ast/ast.h"
#include "grammar/ast/diagnostic.h"
#include "grammar/input.h"
#include "grammar/parse.h"

namespace tranche::grammar {

class AstBuilder : public RulesBaseVisitor {
 public:
  AstBuilder(const Input& input, diag::Sink& sink, const ParseOptions& options)
      : in_(input), sink_(sink), options_(options) {}

  ast::File file(RulesParser::FileContext* ctx);
  ast::ExprPtr expression(RulesParser::ExprContext* ctx) { return expr(ctx); }
  // True once the builder reported an error (a bad number, template, event or an expression
  // over the depth limit): the caller discards the result.
  bool failed() const { return failed_; }

  antlrcpp::Any visitPrimaryExpr(RulesParser::PrimaryExprContext* ctx) override;
  antlrcpp::Any visitNegExpr(RulesParser::NegExprContext* ctx) override;
  antlrcpp::Any visitNotExpr(RulesParser::NotExprContext* ctx) override;
  antlrcpp::Any visitMulExpr(RulesParser::MulExprContext* ctx) override { return binary_chain(ctx); }
  antlrcpp::Any visitAddExpr(RulesParser::AddExprContext* ctx) override { return binary_chain(ctx); }
  antlrcpp::Any visitCmpExpr(RulesParser::CmpExprContext* ctx) override { return binary_chain(ctx); }
  antlrcpp::Any visitAndExpr(RulesParser::AndExprContext* ctx) override { return binary_chain(ctx); }
  antlrcpp::Any visitOrExpr(RulesParser::OrExprContext* ctx) override { return binary_chain(ctx); }
  antlrcpp::Any visitInRangeExpr(RulesParser::InRangeExprContext* ctx) override { return binary_chain(ctx); }
  antlrcpp::Any visitInSetExpr(RulesParser::InSetExprContext* ctx) override { return binary_chain(ctx); }
  antlrcpp::Any visitIfExpr(RulesParser::IfExprContext* ctx) override;
  antlrcpp::Any visitNumberLit(RulesParser::NumberLitContext* ctx) override;
  antlrcpp::Any visitBoolLit(RulesParser::BoolLitContext* ctx) override;
  antlrcpp::Any visitStringLit(RulesParser::StringLitContext* ctx) override;
  antlrcpp::Any visitCallExpr(RulesParser::CallExprContext* ctx) override;
  antlrcpp::Any visitQuantifierExpr(RulesParser::QuantifierExprContext* ctx) override;
  antlrcpp::Any visitLayerAccess(RulesParser::LayerAccessContext* ctx) override;
  antlrcpp::Any visitNameRef(RulesParser::NameRefContext* ctx) override;
  antlrcpp::Any visitParenExpr(RulesParser::ParenExprContext* ctx) override;

 private:
  ast::ExprPtr expr(antlr4::tree::ParseTree* ctx);
  antlrcpp::Any binary_chain(RulesParser::ExprContext* top);
  ast::ExprPtr make(ast::ExprKind kind, antlr4::ParserRuleContext* ctx);
  bool check_depth(ast::Expr& e, const std::vector<ast::ExprPtr>& args);
  static antlrcpp::Any give(ast::ExprPtr e) { return antlrcpp::Any(e.release()); }

  ast::RulePtr rule(RulesParser::RuleItemContext* ctx);
  ast::RulePtr on(RulesParser::OnItemContext* ctx);
  std::unique_ptr<ast::Use> use(RulesParser::UseItemContext* ctx);
  ast::ParamPtr param(RulesParser::ParamItemContext* ctx);
  bool block(RulesParser::BlockContext* ctx, std::vector<ast::StmtPtr>& out);
  ast::StmtPtr stmt(RulesParser::StmtContext* ctx);
  ast::StmtPtr if_stmt(RulesParser::IfStmtContext* ctx);
  ast::StmtPtr move(RulesParser::MoveStmtContext* ctx);
  bool text(antlr4::Token* token, ast::Template& out);
  bool template_part(uint32_t open, uint32_t close, ast::Template& out);
  bool template_error(uint32_t from, uint32_t to, std::string message, std::string label, std::string help);
  std::string name(RulesParser::NameContext* ctx, ast::Span* span);
  std::string string_value(antlr4::Token* token);

  const Input& in_;
  diag::Sink& sink_;
  const ParseOptions& options_;
  bool failed_ = false;
  bool depth_reported_ = false;
};

}  // namespace tranche::grammar
