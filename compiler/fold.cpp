// Constant folding: the value of an expression whose operands are all known before slicing,
// and the operations that have none (E0209).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "compiler/checker.h"

namespace tranche::compiler {

using ast::Expr;
using ast::ExprKind;
using ast::Kind;
using ast::Op;

namespace {

// a OP b for an arithmetic, comparison or logical operator (b != 0 for / and mod).
std::optional<double> fold_binary(Op op, double a, double b) {
  switch (op) {
    case Op::Add:
      return a + b;
    case Op::Sub:
      return a - b;
    case Op::Mul:
      return a * b;
    case Op::Div:
      return a / b;
    case Op::Mod:
      return a - b * std::floor(a / b);
    case Op::Eq:
      return a == b;
    case Op::Ne:
      return a != b;
    case Op::Lt:
      return a < b;
    case Op::Le:
      return a <= b;
    case Op::Gt:
      return a > b;
    case Op::Ge:
      return a >= b;
    case Op::And:
      return (a != 0 && b != 0);
    case Op::Or:
      return (a != 0 || b != 0);
    default:
      return std::nullopt;
  }
}

// A built-in function of constant arguments `c` (sqrt of a non-negative number); trigonometric
// arguments in degrees when `deg(i)`.
template <typename Arg, typename Deg>
double fold_call(ast::Func func, size_t n, Arg c, Deg deg) {
  auto rad = [&](size_t i) { return deg(i) ? c(i) * std::numbers::pi / 180 : c(i); };
  switch (func) {
    case ast::Func::Min:
    case ast::Func::Max: {
      double r = c(0);
      for (size_t i = 1; i < n; ++i) r = func == ast::Func::Min ? std::min(r, c(i)) : std::max(r, c(i));
      return r;
    }
    case ast::Func::Clamp:
      return std::min(std::max(c(0), c(1)), c(2));
    case ast::Func::Abs:
      return std::abs(c(0));
    case ast::Func::Round:
      return std::round(c(0));
    case ast::Func::Floor:
      return std::floor(c(0));
    case ast::Func::Ceil:
      return std::ceil(c(0));
    case ast::Func::Sqrt:
      return std::sqrt(c(0));
    case ast::Func::Sin:
      return std::sin(rad(0));
    case ast::Func::Cos:
      return std::cos(rad(0));
    case ast::Func::Tan:
      return std::tan(rad(0));
    case ast::Func::Atan2:
      return std::atan2(c(0), c(1)) * 180 / std::numbers::pi;
    case ast::Func::Lerp:
      return c(0) + (c(1) - c(0)) * c(2);
  }
  return 0;
}

}  // namespace

// Folds constants, reporting operations that have no value (E0209).
void Checker::fold(Expr& e) {
  auto c = [&](size_t i) { return e.args[i]->constant; };
  auto all = [&] {
    for (const auto& a : e.args)
      if (!a->constant) return false;
    return true;
  };
  auto no_value = [&](const ast::Span& at, const char* what, const char* label) {
    sink_.error("E0209", at, what, label);
    e.type = ast::Type::error();
  };
  std::optional<double> v;
  switch (e.kind) {
    case ExprKind::Number:
      v = e.number;
      break;
    case ExprKind::Bool:
      v = e.boolean ? 1 : 0;
      break;
    case ExprKind::Name:
      if (e.ref == ast::RefKind::EnumValue) v = e.enum_value;
      break;
    case ExprKind::Unary:
      if (c(0)) v = e.op == Op::Neg ? -*c(0) : (*c(0) == 0 ? 1 : 0);
      break;
    case ExprKind::Binary:
      // A constant zero divisor is an error even when the dividend is not constant.
      if ((e.op == Op::Div || e.op == Op::Mod) && c(1) == 0.0)
        return no_value(e.args[1]->span,
                        e.op == Op::Div ? "division by zero" : "remainder of a division by zero",
                        "this is zero");
      if (all()) v = fold_binary(e.op, *c(0), *c(1));
      break;
    case ExprKind::InRange:
      if (all()) v = *c(0) >= *c(1) && *c(0) <= *c(2);
      break;
    case ExprKind::InSet:
      if (all()) {
        bool in = false;
        for (size_t i = 1; i < e.args.size(); ++i) in = in || *c(i) == *c(0);
        v = in;
      }
      break;
    case ExprKind::If:
      if (c(0)) v = *c(0) != 0 ? c(1) : c(2);
      break;
    case ExprKind::Call:
      if (!all()) break;
      if (e.func == ast::Func::Sqrt && *c(0) < 0)
        return no_value(e.args[0]->span, "square root of a negative number", "this is negative");
      v = fold_call(
          e.func, e.args.size(), [&](size_t i) { return *c(i); },
          [&](size_t i) {
            const ast::Type& t = e.args[i]->type;
            return (t.kind == Kind::Number ? t.unit : ast::Unit{}).deg == 1;
          });
      break;
    default:
      break;
  }
  if (!v) return;
  if (!std::isfinite(*v) || (e.type.kind == Kind::Int && std::abs(*v) > 9007199254740992.0))
    return no_value(e.span, "this value is out of range", "the result is too large");
  e.constant = v;
}

}  // namespace tranche::compiler
