// Quantifiers: `any(i in LO..HI: C)` and `all(...)`.
#include <fmt/format.h>

#include "compiler/checker.h"

namespace tranche::compiler {

using ast::Expr;
using ast::Kind;
using ast::Type;

// `any(i in LO..HI: C)` / `all(...)`: C for each integer i of a constant range, at most
// kMaxQuantifierSteps of them, so that a filter stays a bounded computation.
Type Checker::quantifier(Expr& e, ExprContext& ctx) {
  constexpr int64_t kMaxQuantifierSteps = 1000;
  Type lo = expr(*e.args[0], ctx);
  Type hi = expr(*e.args[1], ctx);
  bool ok = !lo.is_error() && !hi.is_error();
  for (const Expr* bound : {e.args[0].get(), e.args[1].get()}) {
    if (ok && (bound->type.kind != Kind::Int || !bound->constant)) {
      sink_
          .error("E0405", bound->span,
                 fmt::format("the bounds of `{}` must be integers known before slicing", e.text),
                 bound->type.kind != Kind::Int ? "not an integer" : "not a constant")
          .help(fmt::format("`{}` looks at a fixed number of values: `{}({} in 1..3: ...)`", e.text, e.text, e.member));
      ok = false;
    }
  }
  if (ok) {
    double n = *e.args[1]->constant - *e.args[0]->constant + 1;
    ast::Span range = join(e.args[0]->span, e.args[1]->span);
    if (n > static_cast<double>(kMaxQuantifierSteps)) {
      sink_.error("E0405", range,
                  fmt::format("this range has {:.0f} steps; `{}` takes at most {}", n, e.text, kMaxQuantifierSteps),
                  "too many steps");
      ok = false;
    } else if (n <= 0 && user_file(sources_, range)) {
      sink_
          .warning("W210", range, fmt::format("the range `{}` is empty: `{}` is always {}", sources_.text(range),
                                              e.text, e.text == "any" ? "false" : "true"),
                   "no steps")
          .help("ranges count up and include both ends: `1..3` is 1, 2, 3");
    }
  }
  // The variable is a name like a `let`'s: not a property, param, level or enum value.
  std::string clash;
  if (schema::find_property(e.member)) clash = "is a property";
  else if (params_.count(e.member)) clash = "is a param";
  else if (level_named(e.member) || e.member == "below" || e.member == "above" || e.member == "layers")
    clash = "names a level";
  for (const auto& en : schema::enums())
    if (clash.empty() && en.id != schema::EnumType::None && schema::find_enum_value(en.id, e.member))
      clash = fmt::format("is a `{}` value", en.name);
  if (!clash.empty()) {
    sink_.error("E0108", e.member_span, fmt::format("`{}` {}", e.member, clash), "choose another name");
    return Type::error();
  }
  bound_.push_back({e.member, e.member_span, false});
  Type body = expr(*e.args[2], ctx);
  bool used = bound_.back().used;
  bound_.pop_back();
  if (!used && !e.member.starts_with('_') && user_file(sources_, e.member_span))
    sink_.warning("W209", e.member_span, fmt::format("the variable `{}` is never used", e.member), "unused")
        .help(fmt::format("`{}` tests the same condition at every step: read `{}` in it, or drop the `{}`", e.text,
                          e.member, e.text));
  if (!ok || body.is_error()) return Type::error();
  if (body.kind != Kind::Bool) {
    sink_.error("E0201", e.args[2]->span,
                fmt::format("the condition of `{}` must be true or false, found {}", e.text, body.describe()),
                "not true or false");
    return Type::error();
  }
  return Type::boolean();
}

}  // namespace tranche::compiler
