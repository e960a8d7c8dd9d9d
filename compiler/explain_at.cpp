#include "compiler/explain_at.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "compiler/names.h"
#include "runtime/context/overrides.h"
#include "runtime/vm/trace_text.h"

namespace tranche::compiler {

namespace {

using schema::FieldId;

constexpr long kMaxLayer = 100000;  // `layers[N]` beyond this is a typing mistake, not a print

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// A field of another layer, as written: `below.area` (offset -1), `above.z` (+1), `layers[3].z`.
struct OtherLayer {
  bool relative = false;
  long index = 0;  // the offset when relative
  FieldId field = FieldId::LayerIndex;
};

// The layer fields another layer has, for messages: "index, z_bottom, z, ...".
std::string layer_field_list() {
  std::string out;
  for (const auto& f : schema::fields())
    if (ctx::LayerTable::holds(f.id)) out += (out.empty() ? "" : ", ") + std::string(f.name.substr(6));
  return out;
}

// nullopt: `name` names no other layer (it may be a field or a property); an error: it tries to.
Result<std::optional<OtherLayer>> other_layer(std::string_view name) {
  OtherLayer o;
  std::string_view rest;
  if (name.starts_with("below.") || name.starts_with("above.")) {
    o.relative = true;
    o.index = name.starts_with("below.") ? -1 : 1;
    rest = name.substr(6);
  } else if (name.starts_with("layers[")) {
    const size_t close = name.find("].");
    if (close == std::string_view::npos)
      return Error{"--at", fmt::format("`{}`: write layers[N].FIELD, e.g. layers[3].z", name)};
    const std::string n(trim(name.substr(7, close - 7)));
    char* end = nullptr;
    const long i = std::strtol(n.c_str(), &end, 10);
    if (n.empty() || *end != '\0' || i < 0 || i > kMaxLayer)
      return Error{"--at", fmt::format("`{}`: the layer is a whole number from 0 to {}, not `{}`", name, kMaxLayer, n)};
    o.index = i;
    rest = name.substr(close + 2);
  } else {
    return std::optional<OtherLayer>();
  }
  auto f = schema::find_field(fmt::format("layer.{}", rest));
  if (!f || !ctx::LayerTable::holds(*f))
    return Error{"--at", fmt::format("`{}`: another layer has only these fields: {}", name, layer_field_list())};
  o.field = *f;
  return std::optional<OtherLayer>(o);
}

// Puts the element's layer fields and the other layers' values into the table, bound to the context.
Status fill_table(ExplainAt& out, const std::vector<std::pair<std::string, OtherLayer>>& others,
                  const std::vector<double>& values) {
  const double li = out.context.get(FieldId::LayerIndex);
  if (li < 0 || li > kMaxLayer || li != std::floor(li))
    return Error{"--at", fmt::format("layer.index is a whole number from 0 to {}, not {:g}", kMaxLayer, li)};
  const long current = static_cast<long>(li);
  long last = current;
  for (size_t k = 0; k < others.size(); ++k) {
    const auto& [name, o] = others[k];
    const long i = o.relative ? current + o.index : o.index;
    if (i < 0)
      return Error{"--at", fmt::format("`{}`: layer.index is {}, so there is no layer below (give layer.index=N)",
                                       name, current)};
    if (i == current)
      return Error{"--at", fmt::format("`{}` is this layer (layer.index = {}): give it as layer.{}", name, current,
                                       schema::field(o.field).name.substr(6))};
    out.other[{i, o.field}] = values[k];
    last = std::max(last, i);
  }
  out.table = ctx::LayerTable(static_cast<size_t>(last) + 1);
  for (long i = 0; i <= last; ++i) out.table.set(static_cast<size_t>(i), FieldId::LayerIndex, static_cast<double>(i));
  for (const auto& f : schema::fields())
    if (ctx::LayerTable::holds(f.id) && f.id != FieldId::LayerIndex)
      out.table.set(static_cast<size_t>(current), f.id, out.context.get(f.id));
  for (const auto& [key, v] : out.other) out.table.set(static_cast<size_t>(key.first), key.second, v);
  out.context.set_layers(&out.table);
  return ok_status();
}

Error unknown_name(std::string_view name) {
  std::vector<std::string> names;
  for (const auto& f : schema::fields()) names.emplace_back(f.name);
  for (const auto& q : schema::properties()) names.emplace_back(q.name);
  std::string msg = fmt::format("`{}` is neither a context field nor a property", name);
  if (auto best = suggest(std::string(name), names)) msg += fmt::format("; did you mean `{}`?", *best);
  msg += " (other layers: below.FIELD, above.FIELD, layers[N].FIELD)";
  return Error{"--at", msg};
}

}  // namespace

std::string field_text(FieldId f, double v) {
  const auto& i = schema::field(f);
  switch (i.type) {
    case schema::Type::Bool: return v != 0 ? "true" : "false";
    case schema::Type::Enum: return std::string(schema::enum_value_name(i.enum_type, static_cast<int>(v)));
    case schema::Type::Int: return fmt::format("{:g}", v);
    case schema::Type::Text: return v < 0 ? "a name no rule compares with" : fmt::format("text {:g}", v);
    case schema::Type::Number: break;
  }
  if (i.unit == schema::Unit::Ratio) return fmt::format("{:g}%", v * 100);
  auto u = schema::unit_name(i.unit);
  return u.empty() ? fmt::format("{:g}", v) : fmt::format("{:g} {}", v, u);
}

std::string ExplainAt::layer_field_name(long index, FieldId field) const {
  const long current = static_cast<long>(context.get(FieldId::LayerIndex));
  const std::string_view f = schema::field(field).name.substr(6);
  if (index == current - 1) return fmt::format("below.{}", f);
  if (index == current + 1) return fmt::format("above.{}", f);
  return fmt::format("layers[{}].{}", index, f);
}

std::string ExplainAt::text() const {
  std::vector<std::string> items;
  for (FieldId f : given)
    items.push_back(fmt::format("{} = {}", schema::field(f).name,
                                texts.count(f) ? fmt::format("\"{}\"", texts.at(f)) : field_text(f, context.get(f))));
  for (const auto& [key, v] : other)
    items.push_back(fmt::format("{} = {}", layer_field_name(key.first, key.second), field_text(key.second, v)));
  for (const auto& [q, v] : props)
    items.push_back(fmt::format("{} = {} (below the rules)", schema::property(q).name, vm::value_text(q, v)));
  if (items.empty()) return "(nothing given)";
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : "; ") + s;
  return out;
}

Status parse_explain_at(const std::string& at, ExplainAt& out) {
  std::vector<std::pair<std::string, OtherLayer>> others;
  std::vector<double> values;
  std::string_view rest = at;
  while (!trim(rest).empty()) {
    const size_t comma = rest.find(',');
    const std::string_view item = trim(rest.substr(0, comma));
    rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
    if (item.empty()) continue;
    const size_t eq = item.find('=');
    if (eq == std::string_view::npos) return Error{"--at", fmt::format("`{}` needs a value: write `name=value`", item)};
    const std::string_view name = trim(item.substr(0, eq)), value = trim(item.substr(eq + 1));
    auto other = other_layer(name);
    if (!other) return other.error();
    if (*other) {
      auto v = ctx::parse_field_value(schema::field((*other)->field).name, value);
      if (!v) return Error{"--at", fmt::format("`{}`: {}", name, v.error().message)};
      others.emplace_back(std::string(name), **other);
      values.push_back(*v);
    } else if (auto tf = schema::find_field(name); tf && schema::field(*tf).type == schema::Type::Text) {
      // A name (`object.name=lid`, quotes optional): matched by its text, as when slicing.
      const bool quoted = value.size() >= 2 && value.front() == '"' && value.back() == '"';
      out.texts[*tf] = std::string(quoted ? value.substr(1, value.size() - 2) : value);
      out.given.insert(*tf);
    } else if (auto f = schema::find_field(name)) {
      auto v = ctx::parse_field_value(name, value);
      if (!v) return Error{"--at", v.error().message};
      out.context.set(*f, *v);
      out.given.insert(*f);
    } else if (schema::find_property(name)) {
      auto o = ctx::parse_override(name, value);
      if (!o) return Error{"--at", o.error().message};
      out.props.emplace_back(o->prop, o->value);
    } else {
      return unknown_name(name);
    }
  }
  return fill_table(out, others, values);
}

}  // namespace tranche::compiler
