// Names (object.name): compared with quoted text, and only so. The quoted text is typed as a name
// here and interned by codegen into the program's strings (docs/language.md, "Names").
#include <fmt/format.h>

#include "compiler/checker.h"

namespace tranche::compiler {

using ast::Expr;
using ast::ExprKind;
using ast::Kind;
using ast::Op;
using ast::Type;

// `object.name == "lid"`: quoted text is compared with a name, and a name only with quoted text.
// Decides comparisons with quoted text on one side; nothing for the others.
std::optional<Type> Checker::text_compare(Expr& e, ExprContext& ctx) {
  const bool quoted[2] = {e.args[0]->kind == ExprKind::String, e.args[1]->kind == ExprKind::String};
  if (quoted[0] == quoted[1]) return std::nullopt;  // none (typed as usual) or both (each an E0206)
  Expr& text = *e.args[quoted[0] ? 0 : 1];
  Expr& other = *e.args[quoted[0] ? 1 : 0];
  Type t = expr(other, ctx);
  if (t.is_error()) return Type::error();
  if (t.kind != Kind::Text) {
    expr(text, ctx);  // E0206
    return Type::error();
  }
  if (e.op != Op::Eq && e.op != Op::Ne) {
    const char* op = e.op == Op::Lt ? "<" : e.op == Op::Le ? "<=" : e.op == Op::Gt ? ">" : ">=";
    sink_.error("E0213", e.text_span, "names have no order", fmt::format("`{}` cannot compare them", op))
        .help("compare a name with `==`, `!=` or `in (\"a\", \"b\")`");
    return Type::error();
  }
  text_operand(text, other);
  return Type::boolean();
}

// `text` compared with the name `name`: quoted text is typed as a name (codegen interns it into
// the program's strings); anything else is an error (E0213).
bool Checker::text_operand(Expr& text, const Expr& name) {
  if (text.kind == ExprKind::String) {
    text.type = Type::text();
    return true;
  }
  const std::string written(sources_.text(text.span));
  auto& d = sink_.error("E0213", text.span,
                        fmt::format("a name is compared with quoted text, not {}",
                                    text.type.kind == Kind::Error ? fmt::format("`{}`", written) : text.type.describe()),
                        "not quoted text");
  d.label(name.span, "a name");
  if (text.kind == ExprKind::Name || text.kind == ExprKind::Number)
    d.help(fmt::format("write it in quotes: `\"{}\"`", written)).fix(text.span, fmt::format("\"{}\"", written));
  return false;
}

// Whether the bare word `e` names a value (a local, a loop variable, a property or a param).
bool Checker::names_value(const Expr& e, ExprContext& ctx) {
  for (const auto& b : bound_)
    if (b.name == e.text) return true;
  return find_local(ctx, e.text) || schema::find_property(e.text) || params_.count(e.text);
}

}  // namespace tranche::compiler
