// Name resolution: bare names, fields, other layers, loop elements and function calls, with
// "did you mean" for every kind of name.
#include <fmt/format.h>

#include <array>

#include "compiler/checker.h"
#include "compiler/names.h"

namespace tranche::compiler {

using ast::Expr;
using ast::Kind;
using ast::RefKind;
using ast::Type;
using ast::Unit;

// A built-in function (checker.h declares it for Checker::call_result).
struct FuncInfo {
  std::string_view name;
  ast::Func id;
  size_t min_args, max_args;
  std::string_view signature;
};

namespace {

constexpr std::array<std::string_view, 6> kLevels = {"print", "layer", "island", "cell", "path", "piece"};

// Fields another layer gives through `below`, `above` and `layers[i]`.
bool other_layer_readable(schema::FieldId f) {
  using F = schema::FieldId;
  return f == F::LayerIndex || f == F::LayerZBottom || f == F::LayerZ || f == F::LayerHeight ||
         f == F::LayerArea || f == F::LayerIslands;
}

std::vector<std::string> fields_of(std::string_view prefix, std::string_view shown_prefix) {
  std::vector<std::string> out;
  for (const auto& f : schema::fields())
    if (f.name.starts_with(prefix))
      out.push_back(std::string(shown_prefix) + std::string(f.name.substr(prefix.size())));
  return out;
}

std::vector<std::string> property_names() {
  std::vector<std::string> out;
  for (const auto& p : schema::properties()) out.emplace_back(p.name);
  return out;
}

constexpr FuncInfo kFuncs[] = {
    {"min", ast::Func::Min, 2, 64, "min(a, b, ...)"},
    {"max", ast::Func::Max, 2, 64, "max(a, b, ...)"},
    {"clamp", ast::Func::Clamp, 3, 3, "clamp(x, lo, hi)"},
    {"abs", ast::Func::Abs, 1, 1, "abs(x)"},
    {"round", ast::Func::Round, 1, 1, "round(x)"},
    {"floor", ast::Func::Floor, 1, 1, "floor(x)"},
    {"ceil", ast::Func::Ceil, 1, 1, "ceil(x)"},
    {"sqrt", ast::Func::Sqrt, 1, 1, "sqrt(x)"},
    {"sin", ast::Func::Sin, 1, 1, "sin(angle)"},
    {"cos", ast::Func::Cos, 1, 1, "cos(angle)"},
    {"tan", ast::Func::Tan, 1, 1, "tan(angle)"},
    {"atan2", ast::Func::Atan2, 2, 2, "atan2(y, x)"},
    {"lerp", ast::Func::Lerp, 3, 3, "lerp(a, b, t)"},
};

Unit unit_of(const Type& t) { return t.kind == Kind::Number ? t.unit : Unit{}; }

std::string_view example_field(std::string_view level) {
  if (level == "print") return "height";
  if (level == "island" || level == "cell" || level == "below" || level == "above") return "area";
  if (level == "path") return "kind";
  if (level == "piece") return "length";
  return "index";
}

}  // namespace

Local* Checker::find_local(ExprContext& ctx, std::string_view n) {
  if (ctx.locals == nullptr) return nullptr;
  for (auto it = ctx.locals->rbegin(); it != ctx.locals->rend(); ++it)
    if (it->name == n) return &*it;
  return nullptr;
}

Type Checker::property_ref(Expr& e, schema::PropId id) {
  const auto& p = schema::property(id);
  e.ref = rule_sets_.count(id) ? RefKind::Inherited : RefKind::Property;
  e.prop = id;
  e.stage = p.stage;
  e.level = schema::stage_level(p.stage);
  return Type::of(p.type, p.unit, p.enum_type);
}

// A `let` or loop variable read as a value (a point, piece or island is not one).
Type Checker::local_value(Expr& e, Local& local) {
  const std::string& n = e.text;
  Local* l = &local;
  l->used = true;
  if (l->element != ast::Element::None && l->element != ast::Element::Int) {
    static const char* what[] = {"", "", "a point", "a piece", "an island"};
    static const char* example[] = {"", "", "`{0}.x`, `{0}.y`", "`{0}.length`, `{0}.overhang`", "`{0}.area`"};
    size_t k = static_cast<size_t>(l->element);
    sink_
        .error("E0201", e.span, fmt::format("`{}` is {}, not a value", n, what[k]),
               "has fields, but no value")
        .label(l->span, "defined here")
        .help(fmt::format(fmt::runtime(std::string("read one of its fields, like ") + example[k]), n));
    return Type::error();
  }
  e.ref = RefKind::Local;
  e.local = l->slot;
  return l->type;
}

// An enum value where its enum is not expected (`hint` names the one that is, if any).
Type Checker::misplaced_enum(Expr& e, const schema::EnumInfo& info, schema::EnumType hint) {
  const std::string& n = e.text;
  if (hint != schema::EnumType::None) {
    const auto& want = schema::enum_info(hint);
    std::vector<std::string> values(want.values.begin(), want.values.end());
    sink_
        .error("E0204", e.span,
               fmt::format("`{}` is a `{}` value, not a `{}` value", n, info.name, want.name),
               fmt::format("not a `{}` value", want.name))
        .note(fmt::format("`{}` values are {}", want.name, quoted_list(values, 12)));
  } else {
    std::string example;
    for (const auto& f : schema::fields())
      if (f.enum_type == info.id) {
        example = std::string(f.name);
        break;
      }
    auto& d =
        sink_.error("E0204", e.span, fmt::format("`{}` is a `{}` value, not something to read", n, info.name),
                    "an enum value on its own");
    if (!example.empty()) d.help(fmt::format("compare a field with it: `{} == {}`", example, n));
  }
  return Type::error();
}

Type Checker::name(Expr& e, ExprContext& ctx, schema::EnumType hint) {
  const std::string& n = e.text;
  if (hint != schema::EnumType::None) {
    if (auto v = schema::find_enum_value(hint, n)) {
      e.ref = RefKind::EnumValue;
      e.enum_value = *v;
      return Type::enumeration(hint);
    }
  }
  for (size_t k = bound_.size(); k-- > 0;) {
    if (bound_[k].name != n) continue;
    bound_[k].used = true;
    e.ref = RefKind::Bound;
    e.local = static_cast<int>(k);
    return Type::integer();
  }
  if (Local* l = find_local(ctx, n)) return local_value(e, *l);
  if (auto p = schema::find_property(n)) return property_ref(e, *p);
  if (auto it = params_.find(n); it != params_.end()) {
    e.constant = it->second.value;
    e.from_param = true;
    return it->second.type;
  }
  for (const auto& info : schema::enums())
    if (info.id != schema::EnumType::None && schema::find_enum_value(info.id, n))
      return misplaced_enum(e, info, hint);
  return unknown_name(e, ctx, hint);
}

// A name that is nothing known: suggestions, other slicers' names, levels, `True`.
Type Checker::unknown_name(Expr& e, ExprContext& ctx, schema::EnumType hint) {
  const std::string& n = e.text;
  if (hint != schema::EnumType::None) {
    const auto& want = schema::enum_info(hint);
    std::vector<std::string> values(want.values.begin(), want.values.end());
    auto& d = sink_.error("E0104", e.span, fmt::format("unknown `{}` value `{}`", want.name, n),
                          fmt::format("not a `{}` value", want.name));
    if (auto same = enum_synonym(want.name, n))
      d.help(fmt::format("what other slicers call `{}` is `{}` here", n, *same)).fix(e.text_span, std::string(*same));
    else if (auto best = suggest(n, values))
      d.did_you_mean(e.text_span, *best);
    d.note(fmt::format("`{}` values are {}", want.name, quoted_list(values, 12)));
    return Type::error();
  }
  if (level_named(n) || n == "below" || n == "above" || n == "layers") {
    sink_.error("E0100", e.span, fmt::format("`{}` is not a value", n), "a level, not a value")
        .help(n == "layers" ? std::string("read a field of one layer: `layers[layer.index - 1].area`")
                            : fmt::format("read one of its fields, like `{}.{}`", n, example_field(n)));
    return Type::error();
  }
  if (auto theirs = foreign_value(n)) {
    sink_.error("E0100", e.span, fmt::format("unknown name `{}`", n), "not a name of the rule language")
        .help(fmt::format("`{}` is {} name for it: here it is `{}`", n,
                          theirs->whose.empty() ? "another slicer's" : theirs->whose, theirs->ours))
        .fix(e.text_span, std::string(theirs->ours));
    return Type::error();
  }
  if (n == "True" || n == "False" || n == "TRUE" || n == "FALSE") {
    std::string lower = n == "True" || n == "TRUE" ? "true" : "false";
    sink_.error("E0100", e.span, fmt::format("unknown name `{}`", n), "not a name of the rule language")
        .did_you_mean(e.text_span, lower);
    return Type::error();
  }
  std::vector<std::string> candidates = property_names();
  for (const auto& f : schema::fields()) candidates.emplace_back(f.name);
  for (const auto& [name, value] : params_) candidates.push_back(name);
  if (ctx.locals)
    for (const auto& l : *ctx.locals) candidates.push_back(l.name);
  auto& d = sink_.error("E0100", e.span, fmt::format("unknown name `{}`", n),
                        ctx.locals ? "not a property, field or `let` name" : "not a property or field");
  if (auto best = suggest(n, candidates)) d.did_you_mean(e.text_span, *best);
  if (n == "s" || n == "mm")
    d.help("write units right after the number, without spaces around `/`: `20 mm/s`");
  return Type::error();
}

// A field of a loop variable: `p.x`, `pc.overhang`, `i.area`.
Type Checker::element_field(Expr& e, Local& local) {
  const std::string& obj = e.text;
  const std::string& m = e.member;
  Local* l = &local;
  l->used = true;
  e.ref = RefKind::ElementField;
  e.local = l->slot;
  e.element = l->element;
  switch (l->element) {
    case ast::Element::Point:
      if (m == "x" || m == "y") {
        e.point_field = m == "x" ? ast::PointField::X : ast::PointField::Y;
        return Type::number(Unit{1, 0, 0, 0});
      }
      if (m == "index") {
        e.point_field = ast::PointField::Index;
        return Type::integer();
      }
      sink_
          .error("E0102", e.member_span, fmt::format("unknown field `{}.{}`", obj, m),
                 "not a field of a point")
          .note("a point has `x`, `y` and `index`");
      return Type::error();
    case ast::Element::Piece:
    case ast::Element::Island: {
      std::string prefix = l->element == ast::Element::Piece ? "piece." : "island.";
      if (auto f = schema::find_field(prefix + m)) {
        e.field = *f;
        const auto& info = schema::field(*f);
        return Type::of(info.type, info.unit, info.enum_type);
      }
      auto& d = sink_.error(
          "E0102", e.member_span, fmt::format("unknown field `{}.{}`", obj, m),
          fmt::format("not a field of {}", l->element == ast::Element::Piece ? "a piece" : "an island"));
      if (auto best = suggest(obj + "." + m, fields_of(prefix, obj + ".")))
        d.did_you_mean(join(e.text_span, e.member_span), *best);
      return Type::error();
    }
    default:
      e.ref = RefKind::None;
      sink_.error("E0102", e.member_span, fmt::format("`{}` has no fields", obj), "not a field")
          .label(l->span, "a number, defined here");
      return Type::error();
  }
}

// `level.field` (and `object.index`): a field of the print, layer, island, cell, path or piece.
Type Checker::level_field(Expr& e) {
  const std::string& obj = e.text;
  const std::string& m = e.member;
  std::string full = obj + "." + m;
  if (auto f = schema::find_field(full)) {
    const auto& info = schema::field(*f);
    e.ref = RefKind::Field;
    e.field = *f;
    e.stage = info.stage;
    e.level = info.level;
    return Type::of(info.type, info.unit, info.enum_type);
  }
  if (full == "path.points") {
    sink_.error("E0102", e.span, "`path.points` is a list of points, not a value", "a list")
        .help("loop over it: `for p in path.points { ... }`");
    return Type::error();
  }
  auto& d = sink_.error("E0102", e.span, fmt::format("unknown field `{}`", full),
                        fmt::format("not a field of `{}`", obj));
  if (auto same = field_synonym(obj, m)) {
    d.did_you_mean(join(e.text_span, e.member_span), std::string(*same));
    if (*same == "path.kind")
      d.note("what other slicers call a path's feature type or extrusion role is `path.kind`");
  } else if (auto best = suggest(full, fields_of(obj + ".", obj + "."))) {
    d.did_you_mean(join(e.text_span, e.member_span), *best);
  } else if (schema::find_property(m)) {
    d.help(fmt::format("`{}` is a property: write `{}`", m, m));
  }
  return Type::error();
}

Type Checker::member(Expr& e, ExprContext& ctx) {
  const std::string& obj = e.text;
  const std::string& m = e.member;
  if (Local* l = find_local(ctx, obj)) return element_field(e, *l);
  // `object.index`: an island's object, known with the island.
  if (obj == "object" || level_named(obj)) return level_field(e);
  if (obj == "below" || obj == "above") {
    e.other = obj == "below" ? ast::OtherLayer::Below : ast::OtherLayer::Above;
    return other_layer_field(e, e.text_span);
  }
  if (obj == "layers") {
    sink_.error("E0101", e.text_span, "`layers` needs the index of a layer", "which layer?")
        .help(fmt::format("write `layers[layer.index - 1].{}`, or `below.{}`", m, m));
    return Type::error();
  }
  return unknown_level(e, ctx);
}

// `x.field` where x is no level, other layer or loop variable.
Type Checker::unknown_level(Expr& e, ExprContext& ctx) {
  const std::string& obj = e.text;
  std::vector<std::string> candidates(kLevels.begin(), kLevels.end());
  candidates.insert(candidates.end(), {"below", "above"});
  if (ctx.locals)
    for (const auto& l : *ctx.locals) candidates.push_back(l.name);
  auto& d = sink_.error("E0101", e.text_span, fmt::format("unknown level `{}`", obj), "not a level");
  if (auto best = suggest(obj, candidates)) {
    d.did_you_mean(e.text_span, *best);
  } else if (schema::find_property(obj)) {
    d.help(fmt::format("`{}` is a property: it has no fields", obj));
  }
  d.note(
      "levels are `print`, `layer`, `island`, `cell`, `path` and `piece`; other layers are `below`, `above` "
      "and `layers[i]`");
  return Type::error();
}

Type Checker::layer_access(Expr& e, ExprContext& ctx) {
  Type index = expr(*e.args[0], ctx);
  if (e.text != "layers") {
    sink_
        .error("E0101", e.text_span, fmt::format("`{}` cannot be indexed", e.text),
               "only `layers` takes `[...]`")
        .help("read another layer with `layers[i].area`");
    return Type::error();
  }
  if (index.is_error()) return Type::error();
  if (index.kind != Kind::Int) {
    sink_
        .error("E0201", e.args[0]->span,
               fmt::format("a layer index is an integer, found {}", index.describe()), "not an integer")
        .help("use `round(...)`, `floor(...)` or `ceil(...)` to make one");
    return Type::error();
  }
  e.other = ast::OtherLayer::Indexed;
  return other_layer_field(e, e.text_span);
}

Type Checker::other_layer_field(Expr& e, const ast::Span& object_span) {
  std::string full = fmt::format("layer.{}", e.member);
  auto f = schema::find_field(full);
  std::string shown = std::string(sources_.text(join(object_span, e.member_span)));
  if (!f) {
    auto& d = sink_.error("E0102", e.member_span, fmt::format("unknown field `{}`", shown),
                          "not a field of a layer");
    if (auto best = suggest(full, fields_of("layer.", "layer.")))
      d.did_you_mean(e.member_span, best->substr(6));
    return Type::error();
  }
  if (!other_layer_readable(*f)) {
    sink_
        .error("E0303", e.member_span, fmt::format("`{}` cannot be read for another layer", full),
               "only known for the current layer")
        .note("other layers give `index`, `z_bottom`, `z`, `height`, `area` and `islands`");
    return Type::error();
  }
  const auto& info = schema::field(*f);
  e.ref = RefKind::OtherLayer;
  e.field = *f;
  e.stage = std::max(info.stage, schema::Stage::Layer);
  e.level = schema::Level::Layer;
  return Type::of(info.type, info.unit, info.enum_type);
}

Type Checker::call(Expr& e, ExprContext& ctx) {
  const FuncInfo* fn = nullptr;
  for (const auto& f : kFuncs)
    if (f.name == e.text) fn = &f;
  std::vector<Type> args;
  for (auto& a : e.args) args.push_back(expr(*a, ctx));
  if (fn == nullptr) {
    std::vector<std::string> names;
    for (const auto& f : kFuncs) names.emplace_back(f.name);
    auto& d =
        sink_.error("E0105", e.text_span, fmt::format("unknown function `{}`", e.text), "not a function");
    if (auto best = suggest(e.text, names)) d.did_you_mean(e.text_span, *best);
    d.note(fmt::format("functions are {}", quoted_list(names, 20)));
    return Type::error();
  }
  e.func = fn->id;
  if (!call_arguments(e, *fn, args)) return Type::error();
  return call_result(e, *fn, args);
}

// The number of arguments `fn` takes, each a number (E0109, E0201).
bool Checker::call_arguments(Expr& e, const FuncInfo& function, const std::vector<Type>& args) {
  const FuncInfo* fn = &function;
  if (args.size() < fn->min_args || args.size() > fn->max_args) {
    sink_
        .error("E0109", e.span,
               fmt::format("`{}` takes {} argument{}, found {}", fn->name,
                           fn->min_args == fn->max_args ? std::to_string(fn->min_args)
                                                        : fmt::format("{} or more", fn->min_args),
                           fn->max_args == 1 ? "" : "s", args.size()),
               "wrong number of arguments")
        .note(fmt::format("`{}`", fn->signature));
    return false;
  }
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i].is_error()) return false;
    if (!args[i].numeric()) {
      sink_.error("E0201", e.args[i]->span,
                  fmt::format("`{}` needs numbers, found {}", fn->name, args[i].describe()), "not a number");
      return false;
    }
  }
  return true;
}

// The type of a call of `fn` on arguments of types `args`, or a unit error (E0205).
Type Checker::call_result(Expr& e, const FuncInfo& function, const std::vector<Type>& args) {
  const FuncInfo* fn = &function;
  auto unit_error = [&](size_t i, std::string message) {
    sink_
        .error("E0205", e.args[i]->span, std::move(message),
               fmt::format("this is {}", unit_of(args[i]).quoted()))
        .note(fmt::format("`{}`", fn->signature));
    return Type::error();
  };
  // A plain zero takes the unit of the others: `max(0, speed - 10 mm/s)`.
  auto zero = [&](size_t i) { return e.args[i]->constant == 0.0 && unit_of(args[i]).plain(); };
  size_t ref = 0;
  while (ref + 1 < args.size() && zero(ref)) ++ref;
  auto same = [&](size_t from, size_t to) {
    size_t r = std::max(from, std::min(ref, to - 1));
    for (size_t i = from; i < to; ++i)
      if (i != r && unit_of(args[i]) != unit_of(args[r]) && !zero(i)) return i;
    return size_t{0};
  };
  bool all_int = true;
  for (const auto& t : args) all_int = all_int && t.kind == Kind::Int;
  switch (fn->id) {
    case ast::Func::Min:
    case ast::Func::Max:
    case ast::Func::Clamp:
      if (size_t bad = same(0, args.size()))
        return unit_error(bad,
                          fmt::format("the arguments of `{}` must have the same unit: {} and {}", fn->name,
                                      unit_of(args[ref]).quoted(), unit_of(args[bad]).quoted()));
      return all_int ? Type::integer() : Type::number(unit_of(args[ref]));
    case ast::Func::Abs:
      return args[0];
    case ast::Func::Round:
    case ast::Func::Floor:
    case ast::Func::Ceil:
      return unit_of(args[0]).plain() ? Type::integer() : Type::number(unit_of(args[0]));
    case ast::Func::Sqrt:
      if (auto u = unit_of(args[0]).sqrt()) return Type::number(*u);
      return unit_error(0, fmt::format("the square root of {} has no unit", unit_of(args[0]).quoted()));
    case ast::Func::Sin:
    case ast::Func::Cos:
    case ast::Func::Tan: {
      Unit u = unit_of(args[0]);
      if (!u.plain() && u != Unit{0, 0, 1, 0})
        return unit_error(0, fmt::format("`{}` needs an angle (deg) or a plain number (radians), found {}",
                                         fn->name, u.quoted()));
      return Type::number();
    }
    case ast::Func::Atan2:
      if (same(0, 2))
        return unit_error(1, fmt::format("the arguments of `atan2` must have the same unit: {} and {}",
                                         unit_of(args[0]).quoted(), unit_of(args[1]).quoted()));
      return Type::number(Unit{0, 0, 1, 0});
    case ast::Func::Lerp:
      if (same(0, 2))
        return unit_error(1, fmt::format("`lerp` goes between values of the same unit: {} and {}",
                                         unit_of(args[0]).quoted(), unit_of(args[1]).quoted()));
      if (!unit_of(args[2]).plain())
        return unit_error(2, fmt::format("the fraction `t` of `lerp` is a plain number, found {}",
                                         unit_of(args[2]).quoted()));
      return Type::number(unit_of(args[0]));
  }
  return Type::error();
}

}  // namespace tranche::compiler
