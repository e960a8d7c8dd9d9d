// Expression typing: operators, units, literals and constant folding.
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "compiler/checker.h"
#include "compiler/names.h"

namespace tranche::compiler {

using ast::Expr;
using ast::ExprKind;
using ast::Kind;
using ast::Op;
using ast::Type;
using ast::Unit;

namespace {

const char* op_text(Op op) {
  static const char* names[] = {"?",  "-",  "not", "+",  "-", "*",  "/",   "mod",
                                "==", "!=", "<",   "<=", ">", ">=", "and", "or"};
  return names[static_cast<size_t>(op)];
}

Unit unit_of(const Type& t) { return t.kind == Kind::Number ? t.unit : Unit{}; }

// A plain constant zero takes any unit: `island.area > 0`, `x + 0`.
bool is_zero(const Expr& e) { return e.constant && *e.constant == 0 && unit_of(e.type).plain(); }

bool is_bare_name(const Expr& e) { return e.kind == ExprKind::Name; }

}  // namespace

Type Checker::expr(Expr& e, ExprContext& ctx, schema::EnumType hint) {
  Type t;
  switch (e.kind) {
    case ExprKind::Number:
      t = number(e);
      break;
    case ExprKind::Bool:
      t = Type::boolean();
      break;
    case ExprKind::String: {
      // Quoted text compared with a name is typed by text_compare; anywhere else it is no value.
      auto& d = sink_.error("E0206", e.span, "a string is not a value here",
                            "quoted text is a `gcode` or `comment` template, or a name compared with `object.name`");
      d.help("to compare with an enum value, write the name without quotes: `path.kind == infill`");
      // `"infill"` where a name is meant: the name without its quotes.
      if (e.text.size() > 2 && e.text.find_first_of(" \\{}") == std::string::npos && e.text[0] == '"' &&
          e.text[1] != '"')
        d.fix(e.span, e.text.substr(1, e.text.size() - 2));
      break;
    }
    case ExprKind::Name:
      t = name(e, ctx, hint);
      break;
    case ExprKind::Member:
      t = member(e, ctx);
      break;
    case ExprKind::LayerAccess:
      t = layer_access(e, ctx);
      break;
    case ExprKind::Call:
      t = call(e, ctx);
      break;
    case ExprKind::Unary: {
      Type a = expr(*e.args[0], ctx);
      if (a.is_error()) break;
      if (e.op == Op::Neg) {
        if (a.numeric())
          t = a;
        else
          sink_.error("E0201", e.args[0]->span, fmt::format("`-` needs a number, found {}", a.describe()),
                      "not a number");
      } else {
        if (a.kind == Kind::Bool)
          t = a;
        else
          sink_.error("E0201", e.args[0]->span, fmt::format("`not` needs a boolean, found {}", a.describe()),
                      "not true or false");
      }
      break;
    }
    case ExprKind::Binary:
      t = binary(e, ctx);
      break;
    case ExprKind::InRange:
      t = in_range(e, ctx);
      break;
    case ExprKind::InSet:
      t = in_set(e, ctx);
      break;
    case ExprKind::If:
      t = if_expr(e, ctx, hint);
      break;
    case ExprKind::Quantifier:
      t = quantifier(e, ctx);
      break;
  }
  if (t.kind == Kind::Number && !t.unit.in_range()) {
    sink_.error("E0208", e.span, fmt::format("the unit of this value, `{}`, is out of range", t.unit.name()),
                "too many units multiplied together");
    t = Type::error();
  }
  e.type = t;
  for (const auto& a : e.args) {
    e.stage = std::max(e.stage, a->stage);
    e.level = std::max(e.level, a->level);
    e.from_param = e.from_param || a->from_param;
  }
  if (!t.is_error()) fold(e);
  return e.type;
}

Type Checker::number(Expr& e) {
  if (e.unit_text.empty()) return e.integer_literal ? Type::integer() : Type::number();
  auto spelling = ast::parse_unit(e.unit_text);
  if (!spelling) {
    std::vector<std::string> all;
    for (auto s : ast::unit_spellings()) all.emplace_back(s);
    auto& d = sink_.error("E0106", e.unit_span, fmt::format("unknown unit `{}`", e.unit_text), "not a unit");
    const std::string& u = e.unit_text;
    std::string lower = u;
    for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    std::optional<std::string> best;
    if (expected_unit_) {
      // The spellings of the unit the value needs come first: a temperature never gets `deg`.
      int best_d = 1 << 20;
      for (auto s : ast::unit_spellings()) {
        auto sp = ast::parse_unit(s);
        if (!sp || sp->unit != *expected_unit_) continue;
        int dist = edit_distance(u, s);
        if (dist < best_d) best_d = dist, best = std::string(s);
      }
      if (best_d > std::max<int>(2, static_cast<int>(u.size()))) best.reset();
    }
    if (u == "min" || u == "h" || u == "ms" || lower.starts_with("sec")) {
      d.help("times are written in seconds: `s`");
    } else if (u == "cm" || u == "m" || u == "um" || u == "in" || u == "inch") {
      d.help("lengths are written in millimetres: `mm`");
    } else if (u == "K" || u == "F") {
      d.help("temperatures are written in degrees Celsius: `°C` or `C`");
    } else if (u.find('C') != std::string::npos || lower.find("cel") != std::string::npos) {
      d.did_you_mean(e.unit_span, "°C");  // `degC`, `celsius`: never `deg`, an angle
    } else if (best || (best = suggest(u, all))) {
      // `mms`, `mmps`: a speed is more likely than a length.
      if (*best == "mm" && u.size() > 2 && u.find('s', 2) != std::string::npos) *best = "mm/s";
      d.did_you_mean(e.unit_span, *best);
    }
    d.note("units: mm, mm2, mm3, mm/s, mm/s2, mm3/s, deg (or °), s, °C (or C), %");
    return Type::error();
  }
  e.number *= spelling->scale;
  return Type::number(spelling->unit);
}

bool Checker::same_units(const Expr& a, const Expr& b, const ast::Span& op, std::string_view verb) {
  Unit ua = unit_of(a.type), ub = unit_of(b.type);
  if (ua == ub || is_zero(a) || is_zero(b)) return true;
  auto& d = sink_.error("E0200", op, fmt::format("cannot {} {} and {}", verb, ua.quoted(), ub.quoted()),
                        "the units differ");
  d.label(a.span, ua.plain() ? "this has no unit" : fmt::format("this is in `{}`", ua.name()));
  d.label(b.span, ub.plain() ? "this has no unit" : fmt::format("this is in `{}`", ub.name()));
  const Expr& plain = ua.plain() ? a : b;
  const Unit& other = ua.plain() ? ub : ua;
  if ((ua.plain() || ub.plain()) && plain.kind == ExprKind::Number && plain.unit_text.empty())
    d.help(fmt::format("give the number a unit: `{} {}`", sources_.text(plain.span), other.name()));
  return false;
}

Type Checker::binary(Expr& e, ExprContext& ctx) {
  switch (e.op) {
    case Op::Eq:
    case Op::Ne:
    case Op::Lt:
    case Op::Le:
    case Op::Gt:
    case Op::Ge:
      return compare(e, ctx);
    default:
      break;
  }
  // `1200 mm/min`: a speed in another slicer's unit, read as a division by the name `min`.
  if (const Expr& l = *e.args[0], &r = *e.args[1]; e.op == Op::Div && l.kind == ExprKind::Number &&
                                                     l.unit_text == "mm" && r.kind == ExprKind::Name &&
                                                     (r.text == "min" || r.text == "h")) {
    double per_s = l.number / (r.text == "min" ? 60 : 3600);
    std::string fixed = fmt::format("{:g} mm/s", per_s);
    sink_.error("E0106", join(l.unit_span, r.span), fmt::format("unknown unit `mm/{}`", r.text), "not a unit")
        .help(fmt::format("speeds are written in mm/s: `{}` is `{}`", sources_.text(e.span), fixed))
        .fix(e.span, fixed);
    return Type::error();
  }
  Type a = expr(*e.args[0], ctx);
  Type b = expr(*e.args[1], ctx);
  if (a.is_error() || b.is_error()) return Type::error();
  if (e.op == Op::And || e.op == Op::Or) {
    for (int i = 0; i < 2; ++i) {
      const Type& t = i == 0 ? a : b;
      if (t.kind != Kind::Bool) {
        sink_.error("E0201", e.args[static_cast<size_t>(i)]->span,
                    fmt::format("`{}` needs a boolean on each side, found {}", op_text(e.op), t.describe()),
                    "not true or false");
        return Type::error();
      }
    }
    return Type::boolean();
  }
  for (int i = 0; i < 2; ++i) {
    const Type& t = i == 0 ? a : b;
    if (!t.numeric()) {
      sink_.error("E0201", e.args[static_cast<size_t>(i)]->span,
                  fmt::format("`{}` needs numbers, found {}", op_text(e.op), t.describe()), "not a number");
      return Type::error();
    }
  }
  bool both_int = a.kind == Kind::Int && b.kind == Kind::Int;
  switch (e.op) {
    case Op::Add:
    case Op::Sub:
      if (!same_units(*e.args[0], *e.args[1], e.text_span, e.op == Op::Add ? "add" : "subtract"))
        return Type::error();
      if (both_int) return Type::integer();
      return Type::number(is_zero(*e.args[0]) ? unit_of(b) : unit_of(a));
    case Op::Mod:
      if (!same_units(*e.args[0], *e.args[1], e.text_span, "take the remainder of")) return Type::error();
      if (both_int) return Type::integer();
      return Type::number(is_zero(*e.args[0]) ? unit_of(b) : unit_of(a));
    case Op::Mul:
      return both_int ? Type::integer() : Type::number(unit_of(a) * unit_of(b));
    case Op::Div:
      return Type::number(unit_of(a) / unit_of(b));
    default:
      return Type::error();
  }
}

Type Checker::compare(Expr& e, ExprContext& ctx) {
  if (auto t = text_compare(e, ctx)) return *t;
  // A bare enum value is resolved against the other side: `infill == path.kind` works too.
  size_t first = is_bare_name(*e.args[0]) && !is_bare_name(*e.args[1]) ? 1 : 0;
  Type t[2];
  t[first] = expr(*e.args[first], ctx);
  // `path.knd == infill`: the enum value cannot be judged once the field is unknown.
  if (t[first].is_error() && is_bare_name(*e.args[1 - first])) return Type::error();
  if (t[first].kind == Kind::Text && is_bare_name(*e.args[1 - first]) && !names_value(*e.args[1 - first], ctx)) {
    text_operand(*e.args[1 - first], *e.args[first]);  // `object.name == lid`: the word is meant quoted
    return Type::error();
  }
  t[1 - first] = expr(*e.args[1 - first], ctx,
                      t[first].kind == Kind::Enum ? t[first].enum_type : schema::EnumType::None);
  if (t[0].is_error() || t[1].is_error()) return Type::error();
  if (t[0].kind == Kind::Text || t[1].kind == Kind::Text) {
    const size_t name = t[0].kind == Kind::Text ? 0 : 1;
    text_operand(*e.args[1 - name], *e.args[name]);
    return Type::error();
  }
  bool equality = e.op == Op::Eq || e.op == Op::Ne;
  if (t[0].numeric() && t[1].numeric()) {
    if (!same_units(*e.args[0], *e.args[1], e.text_span, "compare")) return Type::error();
    return Type::boolean();
  }
  if (t[0].kind == Kind::Enum || t[1].kind == Kind::Enum) {
    const Type& en = t[0].kind == Kind::Enum ? t[0] : t[1];
    const Type& other = t[0].kind == Kind::Enum ? t[1] : t[0];
    const auto& info = schema::enum_info(en.enum_type);
    std::vector<std::string> values(info.values.begin(), info.values.end());
    if (other != en) {
      sink_
          .error("E0204", e.text_span,
                 fmt::format("cannot compare {} with {}", en.describe(), other.describe()),
                 "different kinds of value")
          .note(fmt::format("`{}` values are {}", info.name, quoted_list(values, 12)));
      return Type::error();
    }
    if (!equality) {
      sink_
          .error("E0204", e.text_span, fmt::format("`{}` values have no order", info.name),
                 fmt::format("`{}` cannot compare them", op_text(e.op)))
          .help("compare with `==`, `!=` or `in (a, b)`");
      return Type::error();
    }
    return Type::boolean();
  }
  if (t[0].kind == Kind::Bool && t[1].kind == Kind::Bool && equality) return Type::boolean();
  sink_.error("E0201", e.text_span,
              fmt::format("cannot compare {} with {}", t[0].describe(), t[1].describe()),
              "different kinds of value");
  return Type::error();
}

Type Checker::in_range(Expr& e, ExprContext& ctx) {
  Type x = expr(*e.args[0], ctx);
  Type lo = expr(*e.args[1], ctx);
  Type hi = expr(*e.args[2], ctx);
  if (x.is_error() || lo.is_error() || hi.is_error()) return Type::error();
  for (size_t i = 0; i < 3; ++i) {
    if (!e.args[i]->type.numeric()) {
      sink_
          .error("E0201", e.args[i]->span,
                 fmt::format("`in LO..HI` needs numbers, found {}", e.args[i]->type.describe()),
                 "not a number")
          .help("for enum values, list them: `path.kind in (infill, bridge)`");
      return Type::error();
    }
  }
  if (!same_units(*e.args[0], *e.args[1], e.text_span, "compare") ||
      !same_units(*e.args[0], *e.args[2], e.text_span, "compare"))
    return Type::error();
  return Type::boolean();
}

Type Checker::in_set(Expr& e, ExprContext& ctx) {
  Type x = expr(*e.args[0], ctx);
  bool ok = !x.is_error();
  if (x.kind == Kind::Text) {  // `object.name in ("lid", "base")`
    for (size_t i = 1; i < e.args.size(); ++i) ok = text_operand(*e.args[i], *e.args[0]) && ok;
    return ok ? Type::boolean() : Type::error();
  }
  auto hint = x.kind == Kind::Enum ? x.enum_type : schema::EnumType::None;
  for (size_t i = 1; i < e.args.size(); ++i) {
    Type t = expr(*e.args[i], ctx, hint);
    if (!ok || t.is_error()) {
      ok = false;
      continue;
    }
    bool same = (x.numeric() && t.numeric()) || x == t;
    if (!same) {
      sink_.error("E0204", e.args[i]->span,
                  fmt::format("cannot compare {} with {}", x.describe(), t.describe()),
                  "not the same kind of value as the left side");
      ok = false;
    } else if (x.numeric() && !same_units(*e.args[0], *e.args[i], e.text_span, "compare")) {
      ok = false;
    }
  }
  return ok ? Type::boolean() : Type::error();
}

Type Checker::if_expr(Expr& e, ExprContext& ctx, schema::EnumType hint) {
  Type c = expr(*e.args[0], ctx);
  Type a = expr(*e.args[1], ctx, hint);
  Type b = expr(*e.args[2], ctx, a.kind == Kind::Enum ? a.enum_type : hint);
  if (c.is_error() || a.is_error() || b.is_error()) return Type::error();
  if (c.kind != Kind::Bool) {
    sink_.error("E0201", e.args[0]->span,
                fmt::format("the condition of `if` must be true or false, found {}", c.describe()),
                "not true or false");
    return Type::error();
  }
  if (a.numeric() && b.numeric()) {
    if (!same_units(*e.args[1], *e.args[2], e.args[2]->span, "choose between")) return Type::error();
    if (a.kind == Kind::Int && b.kind == Kind::Int) return Type::integer();
    return Type::number(is_zero(*e.args[1]) ? unit_of(b) : unit_of(a));
  }
  if (a == b) return a;
  sink_.error("E0201", e.args[2]->span,
              fmt::format("the two branches of `if` differ: {} and {}", a.describe(), b.describe()),
              "this branch differs from the `then` branch");
  return Type::error();
}

}  // namespace tranche::compiler
