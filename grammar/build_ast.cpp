#include "grammar/build_ast.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

namespace tranche::grammar {

using ast::Expr;
using ast::ExprKind;
using ast::ExprPtr;
using ast::Op;
using ast::Stmt;
using ast::StmtKind;
using ast::StmtPtr;

ExprPtr AstBuilder::expr(antlr4::tree::ParseTree* ctx) {
  if (ctx == nullptr) return nullptr;
  antlrcpp::Any any = visit(ctx);
  if (!any.is<Expr*>()) return nullptr;
  return ExprPtr(any.as<Expr*>());
}

ExprPtr AstBuilder::make(ExprKind kind, antlr4::ParserRuleContext* ctx) {
  auto e = std::make_unique<Expr>();
  e->kind = kind;
  e->span = in_.span(ctx);
  return e;
}

bool AstBuilder::check_depth(Expr& e, const std::vector<ExprPtr>& args) {
  int depth = 1;
  for (const auto& a : args) depth = std::max(depth, 1 + a->depth);
  e.depth = static_cast<uint16_t>(std::min(depth, 65535));
  if (depth <= options_.max_expr_depth) return true;
  failed_ = true;
  if (!depth_reported_) {
    depth_reported_ = true;
    sink_
        .error("E0005", e.span,
               fmt::format("expression is too deeply nested: more than {} operations inside each other",
                           options_.max_expr_depth),
               "this expression")
        .help("split it into several rules or `let` steps");
  }
  return false;
}

antlrcpp::Any AstBuilder::visitPrimaryExpr(RulesParser::PrimaryExprContext* ctx) {
  return give(expr(ctx->primary()));
}

antlrcpp::Any AstBuilder::visitNegExpr(RulesParser::NegExprContext* ctx) {
  ExprPtr operand = expr(ctx->expr());
  if (!operand) return {};
  auto e = make(ExprKind::Unary, ctx);
  e->op = Op::Neg;
  e->text_span = in_.span(ctx->MINUS()->getSymbol());
  e->args.push_back(std::move(operand));
  if (!check_depth(*e, e->args)) return {};
  return give(std::move(e));
}

antlrcpp::Any AstBuilder::visitNotExpr(RulesParser::NotExprContext* ctx) {
  ExprPtr operand = expr(ctx->expr());
  if (!operand) return {};
  auto e = make(ExprKind::Unary, ctx);
  e->op = Op::Not;
  e->text_span = in_.span(ctx->NOT()->getSymbol());
  e->args.push_back(std::move(operand));
  if (!check_depth(*e, e->args)) return {};
  return give(std::move(e));
}

namespace {
// The left operand of a left-recursive alternative (binary, `in`), or null for other contexts:
// only those alternatives start with an expression (prefix ones start with a token, `primary`
// with a primary).
RulesParser::ExprContext* left_operand(RulesParser::ExprContext* ctx) {
  if (ctx->children.size() < 3) return nullptr;
  return dynamic_cast<RulesParser::ExprContext*>(ctx->children[0]);
}

Op op_of(antlr4::Token* t) {
  switch (t->getType()) {
    case RulesParser::STAR:
      return Op::Mul;
    case RulesParser::SLASH:
      return Op::Div;
    case RulesParser::MOD:
      return Op::Mod;
    case RulesParser::PLUS:
      return Op::Add;
    case RulesParser::MINUS:
      return Op::Sub;
    case RulesParser::EQ:
      return Op::Eq;
    case RulesParser::NE:
      return Op::Ne;
    case RulesParser::LT:
      return Op::Lt;
    case RulesParser::LE:
      return Op::Le;
    case RulesParser::GT:
      return Op::Gt;
    case RulesParser::GE:
      return Op::Ge;
    default:
      return Op::None;
  }
}
}  // namespace

// `a + b + c + ...` is a left-deep tree: walk its left spine with a loop, not recursion, so
// a long chain cannot exhaust the stack; only its depth limit applies.
antlrcpp::Any AstBuilder::binary_chain(RulesParser::ExprContext* top) {
  std::vector<RulesParser::ExprContext*> spine;
  RulesParser::ExprContext* cur = top;
  while (RulesParser::ExprContext* left = left_operand(cur)) {
    spine.push_back(cur);
    cur = left;
  }
  ExprPtr acc = expr(cur);
  if (!acc) return {};
  for (auto it = spine.rbegin(); it != spine.rend(); ++it) {
    RulesParser::ExprContext* ctx = *it;
    auto e = make(ExprKind::Binary, ctx);
    e->args.push_back(std::move(acc));
    antlr4::Token* op_token = nullptr;
    if (auto* c8 = dynamic_cast<RulesParser::MulExprContext*>(ctx)) {
      op_token = c8->op;
      e->args.push_back(expr(c8->expr(1)));
    } else if (auto* c9 = dynamic_cast<RulesParser::AddExprContext*>(ctx)) {
      op_token = c9->op;
      e->args.push_back(expr(c9->expr(1)));
    } else if (auto* c10 = dynamic_cast<RulesParser::CmpExprContext*>(ctx)) {
      op_token = c10->op;
      e->args.push_back(expr(c10->expr(1)));
    } else if (auto* c11 = dynamic_cast<RulesParser::AndExprContext*>(ctx)) {
      e->op = Op::And;
      e->text_span = in_.span(c11->AND()->getSymbol());
      e->args.push_back(expr(c11->expr(1)));
    } else if (auto* c12 = dynamic_cast<RulesParser::OrExprContext*>(ctx)) {
      e->op = Op::Or;
      e->text_span = in_.span(c12->OR()->getSymbol());
      e->args.push_back(expr(c12->expr(1)));
    } else if (auto* c13 = dynamic_cast<RulesParser::InRangeExprContext*>(ctx)) {
      e->kind = ExprKind::InRange;
      e->text_span = in_.span(c13->IN()->getSymbol());
      e->args.push_back(expr(c13->expr(1)));
      e->args.push_back(expr(c13->expr(2)));
    } else if (auto* c14 = dynamic_cast<RulesParser::InSetExprContext*>(ctx)) {
      e->kind = ExprKind::InSet;
      e->text_span = in_.span(c14->IN()->getSymbol());
      for (size_t i = 1; i < c14->expr().size(); ++i) e->args.push_back(expr(c14->expr(i)));
    }
    if (op_token != nullptr) {
      e->op = op_of(op_token);
      e->text_span = in_.span(op_token);
    }
    for (const auto& a : e->args)
      if (!a) return {};
    if (!check_depth(*e, e->args)) return {};
    acc = std::move(e);
  }
  return give(std::move(acc));
}

antlrcpp::Any AstBuilder::visitIfExpr(RulesParser::IfExprContext* ctx) {
  auto e = make(ExprKind::If, ctx);
  for (auto* c : ctx->expr()) {
    ExprPtr a = expr(c);
    if (!a) return {};
    e->args.push_back(std::move(a));
  }
  if (e->args.size() != 3 || !check_depth(*e, e->args)) return {};
  return give(std::move(e));
}

antlrcpp::Any AstBuilder::visitNumberLit(RulesParser::NumberLitContext* ctx) {
  auto e = make(ExprKind::Number, ctx);
  std::string text = ctx->NUMBER()->getText();
  double value = 0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  ast::Span number_span = in_.span(ctx->NUMBER()->getSymbol());
  if (ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(value)) {
    failed_ = true;
    sink_
        .error("E0006", number_span, fmt::format("number `{}` is out of range", text),
               "too large or too small to represent")
        .help("numbers must lie between about 1e-300 and 1e300");
    return {};
  }
  e->number = value;
  e->integer_literal = text.find_first_of(".eE") == std::string::npos;
  if (e->integer_literal && value > 9007199254740992.0) {
    failed_ = true;
    sink_
        .error("E0006", number_span, fmt::format("integer `{}` is too large", text),
               "integers are exact only up to 2^53")
        .help("write it as a decimal number if an approximation is fine");
    return {};
  }
  if (auto* u = ctx->unit()) {
    e->unit_text = u->getText();
    e->unit_span = in_.span(u);
    e->integer_literal = false;
  }
  e->text_span = number_span;
  return give(std::move(e));
}

antlrcpp::Any AstBuilder::visitBoolLit(RulesParser::BoolLitContext* ctx) {
  auto e = make(ExprKind::Bool, ctx);
  e->boolean = ctx->value->getType() == RulesParser::TRUE;
  return give(std::move(e));
}

antlrcpp::Any AstBuilder::visitStringLit(RulesParser::StringLitContext* ctx) {
  auto e = make(ExprKind::String, ctx);
  e->text = ctx->text->getText();
  e->str = string_value(ctx->text);
  return give(std::move(e));
}

antlrcpp::Any AstBuilder::visitCallExpr(RulesParser::CallExprContext* ctx) {
  auto e = make(ExprKind::Call, ctx);
  e->text = name(ctx->name(), &e->text_span);
  for (auto* c : ctx->expr()) {
    ExprPtr a = expr(c);
    if (!a) return {};
    e->args.push_back(std::move(a));
  }
  if (!check_depth(*e, e->args)) return {};
  return give(std::move(e));
}

// `any(i in LO..HI: BODY)`: text any|all, member the variable, args LO, HI, BODY.
antlrcpp::Any AstBuilder::visitQuantifierExpr(RulesParser::QuantifierExprContext* ctx) {
  auto e = make(ExprKind::Quantifier, ctx);
  e->text = name(ctx->name(0), &e->text_span);
  e->member = name(ctx->name(1), &e->member_span);
  for (auto* c : ctx->expr()) {
    ExprPtr a = expr(c);
    if (!a) return {};
    e->args.push_back(std::move(a));
  }
  if (e->text != "any" && e->text != "all") {
    failed_ = true;
    sink_
        .error("E0105", e->text_span, fmt::format("unknown quantifier `{}`", e->text),
                "`any` or `all`")
        .help(fmt::format("`any({0} in ...: C)` is true when C holds for one `{0}`, `all(...)` when for every one",
                          e->member));
    return {};
  }
  if (e->args.size() != 3 || !check_depth(*e, e->args)) return {};
  return give(std::move(e));
}

antlrcpp::Any AstBuilder::visitLayerAccess(RulesParser::LayerAccessContext* ctx) {
  auto e = make(ExprKind::LayerAccess, ctx);
  e->text = name(ctx->name(0), &e->text_span);
  e->member = name(ctx->name(1), &e->member_span);
  ExprPtr index = expr(ctx->expr());
  if (!index) return {};
  e->args.push_back(std::move(index));
  if (!check_depth(*e, e->args)) return {};
  return give(std::move(e));
}

antlrcpp::Any AstBuilder::visitNameRef(RulesParser::NameRefContext* ctx) {
  auto e = make(ctx->name().size() > 1 ? ExprKind::Member : ExprKind::Name, ctx);
  e->text = name(ctx->name(0), &e->text_span);
  if (ctx->name().size() > 1) e->member = name(ctx->name(1), &e->member_span);
  return give(std::move(e));
}

antlrcpp::Any AstBuilder::visitParenExpr(RulesParser::ParenExprContext* ctx) {
  ExprPtr inner = expr(ctx->expr());
  if (!inner) return {};
  inner->span = in_.span(ctx);  // diagnostics on a parenthesised value underline the brackets too
  return give(std::move(inner));
}

std::string AstBuilder::name(RulesParser::NameContext* ctx, ast::Span* span) {
  if (ctx == nullptr) return {};
  if (span) *span = in_.span(ctx);
  return ctx->getText();
}

}  // namespace tranche::grammar
