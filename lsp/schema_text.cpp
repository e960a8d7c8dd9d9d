#include "lsp/schema_text.h"

#include <fmt/format.h>

namespace tranche::lsp {

std::string type_text(schema::Type type, schema::Unit unit, schema::EnumType e) {
  switch (type) {
    case schema::Type::Int:
      return "integer";
    case schema::Type::Bool:
      return "boolean";
    case schema::Type::Enum:
      return fmt::format("`{}` (one of: {})", schema::enum_info(e).name,
                         fmt::join(schema::enum_info(e).values, ", "));
    case schema::Type::Text:
      return "name (compared with quoted text: `== \"lid\"`)";
    case schema::Type::Number:
      break;
  }
  if (unit == schema::Unit::Ratio) return "ratio (write `50%` or `0.5`)";
  if (unit == schema::Unit::None) return "plain number";
  return fmt::format("number in `{}`", schema::unit_name(unit));
}

std::string quantity(double v, schema::Unit unit) {
  if (unit == schema::Unit::Ratio) return fmt::format("{:g}%", v * 100);
  if (unit == schema::Unit::None) return fmt::format("{:g}", v);
  return fmt::format("{:g} {}", v, schema::unit_name(unit));
}

std::string value_text(double v, const ast::Type& type) {
  if (type.kind == ast::Kind::Bool) return v != 0 ? "true" : "false";
  if (type.kind == ast::Kind::Int || type.unit.plain()) return fmt::format("{:g}", v);
  return fmt::format("{:g} {}", v, type.unit.name());
}

std::string property_text(const schema::PropInfo& p) {
  std::string s = fmt::format("**`{}`** — property, {}\n\ndecided at the *{}* stage", p.name,
                              type_text(p.type, p.unit, p.enum_type), schema::stage_name(p.stage));
  if (schema::finest_stage(p.id) != p.stage)
    s += fmt::format(" (and again per {} by a rule that reads `{}.*`)", schema::stage_name(schema::finest_stage(p.id)),
                     schema::level_name(schema::stage_level(schema::finest_stage(p.id))));
  if (p.type == schema::Type::Number || p.type == schema::Type::Int)
    s += fmt::format("; physical range {} – {}", quantity(p.min, p.unit), quantity(p.max, p.unit));
  std::string def = p.type == schema::Type::Enum   ? std::string(schema::enum_value_name(p.enum_type, static_cast<int>(p.default_value)))
                    : p.type == schema::Type::Bool ? (p.default_value != 0 ? "true" : "false")
                                                   : quantity(p.default_value, p.unit);
  return s + fmt::format("; default {}\n\n{}", def, p.doc);
}

const std::vector<FunctionDoc>& functions() {
  static const std::vector<FunctionDoc> all = {
      {"min", "min(a, b, ...)", "the smallest of two or more values of one unit"},
      {"max", "max(a, b, ...)", "the largest of two or more values of one unit"},
      {"clamp", "clamp(x, lo, hi)", "x kept between lo and hi"},
      {"abs", "abs(x)", "the absolute value"},
      {"round", "round(x)", "the nearest integer (halves away from zero); an integer for a plain number"},
      {"floor", "floor(x)", "rounded down"},
      {"ceil", "ceil(x)", "rounded up"},
      {"sqrt", "sqrt(x)", "the square root: `sqrt(island.area)` is in mm"},
      {"sin", "sin(angle)", "sine of an angle in deg (or of a plain number in radians)"},
      {"cos", "cos(angle)", "cosine of an angle in deg (or of a plain number in radians)"},
      {"tan", "tan(angle)", "tangent of an angle in deg (or of a plain number in radians)"},
      {"atan2", "atan2(y, x)", "the angle of (x, y), in deg"},
      {"lerp", "lerp(a, b, t)", "a + (b - a) * t"},
      {"any", "any(i in LO..HI: CONDITION)", "true when the condition holds for one integer i of the constant range"},
      {"all", "all(i in LO..HI: CONDITION)", "true when the condition holds for every integer i of the constant range"},
  };
  return all;
}

std::string function_text(std::string_view name) {
  for (const auto& f : functions())
    if (f.name == name) return fmt::format("**`{}`** — {}", f.signature, f.doc);
  return {};
}

std::string hook_text(const ast::Stmt& s) {
  if (s.kind == ast::StmtKind::Replace)
    return fmt::format("**`replace {0}`** — generates each matching {0}'s G-code instead of the default "
                       "(`default` emits the default)",
                       s.name);
  return fmt::format("**`{} {}`** — G-code emitted {} each matching {}{}", s.when == ast::When::Before ? "before" : "after",
                     s.name, s.when == ast::When::Before ? "before" : "after", s.name,
                     s.append ? "; `append` adds it to the hook instead of replacing it" : "");
}

}  // namespace tranche::lsp
