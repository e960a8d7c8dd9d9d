// Hover: what the name under the cursor is, from the schema and the checked program.
#include <fmt/format.h>

#include <filesystem>

#include "lsp/features.h"
#include "lsp/schema_text.h"

namespace tranche::lsp {

namespace {

std::string field_text(const schema::FieldInfo& f, bool other_layer) {
  return fmt::format("**`{}`** — field of each `{}`, {}\n\nknown from the *{}* stage{}\n\n{}", f.name,
                     schema::level_name(f.level), type_text(f.type, f.unit, f.enum_type),
                     schema::stage_name(f.stage), other_layer ? " (here read for another layer)" : "", f.doc);
}

std::string param_text(const Document& doc, const std::string& name) {
  auto defs = param_definitions(*doc.analysis.program, name);
  if (defs.empty()) return {};
  const ast::Param* last = defs.back();
  std::string value = last->constant ? value_text(*last->constant, last->type) : "(not a constant)";
  std::string s = fmt::format("**`{}`** — param = `{}`\n\n", name, value);
  const ast::SourceMap& sources = doc.analysis.program->sources;
  for (const ast::Param* p : defs) {
    std::string where = p->from_set ? std::string("`--set`")
                                    : fmt::format("{}:{}", sources.file(p->span.file).path, p->span.line);
    s += fmt::format("- `{}` at {}{}\n", p->constant ? value_text(*p->constant, p->type) : "?", where,
                     p == last ? " (in effect)" : "");
  }
  return s + "\nChange it with `--set " + name + "=VALUE` or a later `param " + name + " = ...` line.";
}

std::string expr_text(const Document& doc, const ast::Expr& e) {
  switch (e.ref) {
    case ast::RefKind::Field:
    case ast::RefKind::OtherLayer:
      if (e.type.is_error()) break;
      return field_text(schema::field(e.field), e.ref == ast::RefKind::OtherLayer);
    case ast::RefKind::Property:
    case ast::RefKind::Inherited:
      return property_text(schema::property(e.prop)) +
             (e.ref == ast::RefKind::Inherited ? "\n\nHere: the value the earlier rules give it." : "");
    case ast::RefKind::EnumValue:
      return fmt::format("**`{}`** — a `{}` value", e.text, schema::enum_info(e.type.enum_type).name);
    case ast::RefKind::Local:
      return fmt::format("**`{}`** — {}", e.text, e.type.describe());
    case ast::RefKind::Bound:
      return fmt::format("**`{}`** — an integer: each step of the range of the `any`/`all` around it", e.text);
    default:
      break;
  }
  if (e.kind == ast::ExprKind::Name && e.from_param) return param_text(doc, e.text);
  if (e.kind == ast::ExprKind::Call || e.kind == ast::ExprKind::Quantifier) return function_text(e.text);
  if (e.kind == ast::ExprKind::Number && !e.unit_text.empty() && !e.type.is_error())
    return fmt::format("`{}`: {}", doc.analysis.program->sources.text(e.span), e.type.describe());
  return {};
}

}  // namespace

json hover(const Document& doc, const json& position) {
  if (!doc.analysis.program) return nullptr;
  uint32_t at = doc.offset(position);
  Found f = find_at(doc.analysis, at);
  std::string text;
  ast::Span span;
  auto in = [&](const ast::Span& s) { return s.valid() && s.offset <= at && at <= s.end(); };
  if (f.use) {
    span = f.use->target_span;
    const ast::SourceMap& sources = doc.analysis.program->sources;
    text = f.use->file >= 0 ? fmt::format("**`use \"{}\"`** → `{}`", f.use->target,
                                          std::filesystem::absolute(sources.file(f.use->file).path).string())
                            : fmt::format("**`use \"{}\"`**: not found", f.use->target);
  } else if (f.expr) {
    span = f.expr->span;
    text = expr_text(doc, *f.expr);
  } else if (f.param && in(f.param->name_span)) {
    span = f.param->name_span;
    text = param_text(doc, f.param->name);
  } else if (f.stmt && f.stmt->kind == ast::StmtKind::Assign && in(f.stmt->name_span)) {
    span = f.stmt->name_span;
    if (auto p = schema::find_property(f.stmt->name)) text = property_text(schema::property(*p));
  } else if (f.stmt && (f.stmt->kind == ast::StmtKind::Hook || f.stmt->kind == ast::StmtKind::Replace) &&
             in(f.stmt->name_span)) {
    span = f.stmt->name_span;
    text = hook_text(*f.stmt);
  }
  if (text.empty()) return nullptr;
  return {{"contents", {{"kind", "markdown"}, {"value", text}}}, {"range", doc.range(span)}};
}

}  // namespace tranche::lsp
