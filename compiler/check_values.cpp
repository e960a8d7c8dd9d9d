// What a value and a template may hold: constants in the physical range (E0212), no other
// slicer's placeholder syntax in a template (E0008).
#include <fmt/format.h>

#include <regex>

#include "compiler/checker.h"
#include "compiler/names.h"

namespace tranche::compiler {

using ast::Expr;

namespace {
// The constant values an expression can take: itself, or both branches of an `if`.
void constant_leaves(const Expr& e, std::vector<const Expr*>& out) {
  if (e.kind == ast::ExprKind::If && !e.args[0]->constant) {
    constant_leaves(*e.args[1], out);
    constant_leaves(*e.args[2], out);
  } else if (e.constant) {
    out.push_back(&e);
  }
}
}  // namespace

// E0212: a constant outside the property's physical range stops the slice whenever it is set.
// (Directions are brought into [0°, 360°) instead: W206 warns about them.)
void Checker::range(const Expr& value, schema::PropId prop) {
  const auto& p = schema::property(prop);
  if ((p.type != schema::Type::Number && p.type != schema::Type::Int) || p.wraps()) return;
  std::vector<const Expr*> leaves;
  constant_leaves(value, leaves);
  for (const Expr* e : leaves) {
    double v = *e->constant;
    if (v >= p.min && v <= p.max) continue;
    auto& d = sink_.error(
        "E0212", e->span,
        fmt::format("`{}` = {} is outside its physical range", p.name, format_quantity(v, p.unit)),
        fmt::format("expected {} to {}", format_quantity(p.min, p.unit), format_quantity(p.max, p.unit)));
    d.note("a value outside the range stops the slice wherever the rule applies");
    bool plain_literal = e->kind == ast::ExprKind::Number && e->unit_text.empty();
    if (p.id == schema::PropId::Fan && v > 100 && v <= 255 && plain_literal) {
      std::string fixed = fmt::format("{:.0f}%", v / 255 * 100);
      d.help(fmt::format("`fan` is a fraction of full speed, not M106's 0-255: {:g} is `{}`", v, fixed)).fix(e->span, fixed);
    } else if (p.unit == schema::Unit::Ratio && v > 1 && v <= 100 && plain_literal) {
      d.help(fmt::format("for a percentage, write `{:g}%`", v)).fix(e->span, fmt::format("{:g}%", v));
    } else {
      d.help(fmt::format("give `{}` a value from {} to {}, or `clamp(...)` a computed one", p.name,
                         format_quantity(p.min, p.unit), format_quantity(p.max, p.unit)));
    }
  }
}

// E0008: placeholders of other slicers in a template's text would be printed as they are.
void Checker::placeholders(const ast::Template& t) {
  static const std::regex foreign(R"(\[([A-Za-z_][A-Za-z0-9_]*)\]|%([A-Za-z_][A-Za-z0-9_]*)%|\{\{\s*([A-Za-z_][A-Za-z0-9_.]*)\s*\}\})");
  for (size_t k = 0; k < t.parts.size(); ++k) {
    const ast::TemplatePart& p = t.parts[k];
    if (p.expr) continue;
    std::string raw(sources_.text(p.span));
    if (raw.find_first_of("[%{$") == std::string::npos) continue;  // most text: nothing to look at
    // `${layer.z}`: the `$` of a shell or JavaScript template is printed.
    if (!raw.empty() && raw.back() == '$' && k + 1 < t.parts.size() && t.parts[k + 1].expr) {
      ast::Span dollar = sources_.span(p.span.file, p.span.end() - 1, p.span.end());
      sink_.error("E0008", dollar, "`${...}`: the `$` would be printed before the value", "printed as it is")
          .help("a template's values are written `{...}` without `$`")
          .fix(dollar, "");
    }
    for (std::sregex_iterator it(raw.begin(), raw.end(), foreign), end; it != end; ++it) {
      const std::smatch& m = *it;
      int group = m[1].matched ? 1 : m[2].matched ? 2 : 3;
      std::string name = m[group];
      std::string ours;
      std::string_view whose = group == 3 ? "Jinja's (Klipper's)" : group == 1 ? "PrusaSlicer's" : "another slicer's";
      if (auto f = foreign_value(name)) {
        ours = std::string(f->ours);
        if (group == 1 && !f->whose.empty()) whose = f->whose;
      } else if (schema::find_property(name) || schema::find_field(name) || params_.count(name)) {
        ours = name;
      }
      if (ours.empty()) continue;  // `[done]`, `{{x}}`: text the user means
      uint32_t at = p.span.offset + static_cast<uint32_t>(m.position(0));
      ast::Span span = sources_.span(p.span.file, at, at + static_cast<uint32_t>(m.length(0)));
      std::string fixed = "{" + ours + "}";
      sink_
          .error("E0008", span,
                 fmt::format("`{}` is {} placeholder syntax: it would be printed as it is", m.str(0), whose),
                 "printed as it is")
          .help(fmt::format("a template prints a value written in braces: `{}`", fixed))
          .fix(span, fixed);
    }
  }
}

}  // namespace tranche::compiler
