#include "runtime/context/overrides.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

namespace tranche::ctx {
namespace {

using schema::Type;
using schema::Unit;

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

// The unit spellings accepted after a number for each unit ("" = none written).
bool unit_matches(Unit unit, std::string_view written) {
  if (written.empty()) return true;
  switch (unit) {
    case Unit::None:
      return false;
    case Unit::Ratio:
      return written == "%";
    case Unit::Mm:
      return written == "mm";
    case Unit::Mm2:
      return written == "mm2" || written == "mm²";
    case Unit::Mm3:
      return written == "mm3" || written == "mm³";
    case Unit::MmPerS:
      return written == "mm/s";
    case Unit::MmPerS2:
      return written == "mm/s2" || written == "mm/s²";
    case Unit::Mm3PerS:
      return written == "mm3/s" || written == "mm³/s";
    case Unit::Deg:
      return written == "deg" || written == "°";
    case Unit::S:
      return written == "s";
    case Unit::Celsius:
      return written == "C" || written == "°C";
  }
  return false;
}

std::string with_unit(double v, Unit u) {
  if (u == Unit::Ratio) return fmt::format("{:g}%", v * 100);
  auto name = schema::unit_name(u);
  return name.empty() ? fmt::format("{:g}", v) : fmt::format("{:g} {}", v, name);
}

std::string enum_list(schema::EnumType t) {
  std::string out;
  for (auto v : schema::enum_info(t).values) out += (out.empty() ? "" : ", ") + std::string(v);
  return out;
}

}  // namespace

std::vector<std::string_view> close_property_names(std::string_view name, size_t max) {
  std::vector<std::pair<size_t, std::string_view>> scored;
  for (const auto& p : schema::properties()) {
    size_t d = edit_distance(name, p.name);
    bool related = !name.empty() && (p.name.find(name) != std::string_view::npos ||
                                     name.find(p.name) != std::string_view::npos);
    if (d <= std::max<size_t>(2, name.size() / 3) || related) scored.emplace_back(related ? 0 : d, p.name);
  }
  std::stable_sort(scored.begin(), scored.end(), [](auto& a, auto& b) { return a.first < b.first; });
  std::vector<std::string_view> out;
  for (size_t i = 0; i < scored.size() && out.size() < max; ++i) out.push_back(scored[i].second);
  return out;
}

Result<Override> parse_override(std::string_view key, std::string_view value) {
  key = trim(key);
  value = trim(value);
  std::string where = fmt::format("--set {}={}", key, value);
  auto id = schema::find_property(key);
  if (!id) {
    std::string msg = fmt::format("unknown property '{}'", key);
    if (schema::find_field(key)) msg += " (it is a context field that rules read, not a property)";
    auto close = close_property_names(key);
    if (!close.empty()) {
      msg += "; did you mean ";
      for (size_t i = 0; i < close.size(); ++i)
        msg += fmt::format("{}{}", i == 0 ? "" : i + 1 == close.size() ? " or " : ", ", close[i]);
      msg += "?";
    } else {
      msg += "; the properties are listed in docs/settings.md";
    }
    return Error{where, msg};
  }
  const auto& info = schema::property(*id);
  if (value.empty()) return Error{where, fmt::format("missing value for {}", info.name)};

  if (info.type == Type::Bool) {
    if (value == "true") return Override{*id, 1.0};
    if (value == "false") return Override{*id, 0.0};
    return Error{where, fmt::format("{} is true or false, not '{}'", info.name, value)};
  }
  if (info.type == Type::Enum) {
    if (auto v = schema::find_enum_value(info.enum_type, value))
      return Override{*id, static_cast<double>(*v)};
    return Error{where,
                 fmt::format("{} is one of {}, not '{}'", info.name, enum_list(info.enum_type), value)};
  }

  // A number, then an optional unit.
  double v = 0;
  const char* begin = value.data();
  const char* end = value.data() + value.size();
  auto [ptr, ec] = std::from_chars(begin, end, v);
  if (ec != std::errc() || !std::isfinite(v)) {
    return Error{
        where,
        fmt::format("{} needs a number{}, not '{}'", info.name,
                    info.unit == Unit::None ? "" : fmt::format(" in {}", with_unit(1, info.unit).substr(2)),
                    value)};
  }
  std::string_view unit = trim(std::string_view(ptr, static_cast<size_t>(end - ptr)));
  if (!unit_matches(info.unit, unit)) {
    return Error{where, fmt::format("{} is in {}; '{}' is not a unit it accepts", info.name,
                                    info.unit == Unit::None ? "plain numbers"
                                                            : std::string(schema::unit_name(info.unit)),
                                    unit)};
  }
  if (unit == "%") v /= 100.0;
  if (info.type == Type::Int && v != std::floor(v))
    return Error{where, fmt::format("{} is a whole number, not {}", info.name, value)};
  if (v < info.min || v > info.max) {
    std::string hint;
    if (info.unit == Unit::Ratio && unit.empty() && v > 1 && v <= 100)
      hint = fmt::format(" (write {}% or {:g} for a percentage)", v, v / 100);
    return Error{where,
                 fmt::format("{} is outside the range of {}: {} to {}{}", with_unit(v, info.unit), info.name,
                             with_unit(info.min, info.unit), with_unit(info.max, info.unit), hint)};
  }
  return Override{*id, v};
}

bool is_plain_override(std::string_view key, std::string_view value) {
  return schema::find_property(key) && parse_override(key, value).ok();
}

Result<double> parse_field_value(std::string_view name, std::string_view value) {
  name = trim(name);
  value = trim(value);
  auto id = schema::find_field(name);
  if (!id) {
    std::string msg = fmt::format("unknown field '{}'", name);
    if (schema::find_property(name)) msg = fmt::format("'{}' is a property, not a field", name);
    return Error{std::string(name), msg};
  }
  const auto& info = schema::field(*id);
  if (value.empty()) return Error{std::string(name), "missing value"};
  if (info.type == Type::Bool) {
    if (value == "true") return 1.0;
    if (value == "false") return 0.0;
    return Error{std::string(name), fmt::format("{} is true or false, not '{}'", name, value)};
  }
  if (info.type == Type::Text)  // its number is the text's index in a rule program (vm::RuleSet::text_index)
    return Error{std::string(name), fmt::format("{} is a name: its value depends on the rules that compare it", name)};
  if (info.type == Type::Enum) {
    if (auto v = schema::find_enum_value(info.enum_type, value)) return static_cast<double>(*v);
    return Error{std::string(name), fmt::format("{} is one of {}, not '{}'", name, enum_list(info.enum_type), value)};
  }
  double v = 0;
  const char* end = value.data() + value.size();
  auto [ptr, ec] = std::from_chars(value.data(), end, v);
  if (ec != std::errc() || !std::isfinite(v))
    return Error{std::string(name), fmt::format("{} needs a number, not '{}'", name, value)};
  std::string_view unit = trim(std::string_view(ptr, static_cast<size_t>(end - ptr)));
  if (!unit_matches(info.unit, unit))
    return Error{std::string(name), fmt::format("{} is in {}; '{}' is not a unit it accepts", name,
                                                info.unit == Unit::None ? "plain numbers"
                                                                        : std::string(schema::unit_name(info.unit)),
                                                unit)};
  if (unit == "%") v /= 100.0;
  if (info.type == Type::Int && v != std::floor(v))
    return Error{std::string(name), fmt::format("{} is a whole number, not {}", name, value)};
  return v;
}

Result<Overrides> Overrides::parse(const std::vector<std::pair<std::string, std::string>>& sets) {
  Overrides out;
  for (const auto& [k, v] : sets) {
    auto o = parse_override(k, v);
    if (!o) return o.error();
    out.add(*o);
  }
  return out;
}

Status Overrides::decide(schema::Stage stage, const Context& ctx, PropertyValues& props) const {
  for (const auto& o : items_) {
    if (schema::property(o.prop).stage != stage && schema::finest_stage(o.prop) != stage) continue;
    props[o.prop] = o.value;
    if (Trace* t = ctx.trace()) t->step({o.prop, recorded_as, UINT32_MAX, UINT32_MAX, o.value, 0});
  }
  return ok_status();
}

}  // namespace tranche::ctx
