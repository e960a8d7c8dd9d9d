#include "grammar/ast/types.h"

#include <fmt/format.h>
#include <cstdlib>

namespace tranche::ast {

Unit Unit::from_schema(schema::Unit u) {
  switch (u) {
    case schema::Unit::None:
    case schema::Unit::Ratio:
      return {};
    case schema::Unit::Mm:
      return {1, 0, 0, 0};
    case schema::Unit::Mm2:
      return {2, 0, 0, 0};
    case schema::Unit::Mm3:
      return {3, 0, 0, 0};
    case schema::Unit::MmPerS:
      return {1, -1, 0, 0};
    case schema::Unit::MmPerS2:
      return {1, -2, 0, 0};
    case schema::Unit::Mm3PerS:
      return {3, -1, 0, 0};
    case schema::Unit::Deg:
      return {0, 0, 1, 0};
    case schema::Unit::S:
      return {0, 1, 0, 0};
    case schema::Unit::Celsius:
      return {0, 0, 0, 1};
  }
  return {};
}

Unit Unit::operator*(const Unit& o) const {
  return {static_cast<int16_t>(mm + o.mm), static_cast<int16_t>(s + o.s), static_cast<int16_t>(deg + o.deg),
          static_cast<int16_t>(temp + o.temp)};
}

Unit Unit::operator/(const Unit& o) const {
  return {static_cast<int16_t>(mm - o.mm), static_cast<int16_t>(s - o.s), static_cast<int16_t>(deg - o.deg),
          static_cast<int16_t>(temp - o.temp)};
}

std::optional<Unit> Unit::sqrt() const {
  if (mm % 2 || s % 2 || deg % 2 || temp % 2) return std::nullopt;
  return Unit{static_cast<int16_t>(mm / 2), static_cast<int16_t>(s / 2), static_cast<int16_t>(deg / 2),
              static_cast<int16_t>(temp / 2)};
}

bool Unit::in_range() const {
  return std::abs(mm) <= kMaxExponent && std::abs(s) <= kMaxExponent && std::abs(deg) <= kMaxExponent &&
         std::abs(temp) <= kMaxExponent;
}

std::string Unit::name() const {
  std::string num, den;
  auto add = [](std::string& out, std::string_view base, int e) {
    if (e == 0) return;
    if (!out.empty()) out += "·";
    out += base;
    if (e != 1) out += std::to_string(e);
  };
  add(num, "mm", mm > 0 ? mm : 0);
  add(num, "deg", deg > 0 ? deg : 0);
  add(num, "°C", temp > 0 ? temp : 0);
  add(num, "s", s > 0 ? s : 0);
  add(den, "mm", mm < 0 ? -mm : 0);
  add(den, "deg", deg < 0 ? -deg : 0);
  add(den, "°C", temp < 0 ? -temp : 0);
  add(den, "s", s < 0 ? -s : 0);
  if (den.empty()) return num;
  return fmt::format("{}/{}", num.empty() ? "1" : num, den);
}

std::string Unit::quoted() const {
  return plain() ? std::string("a plain number") : fmt::format("`{}`", name());
}

namespace {
struct Spelling {
  std::string_view text;
  Unit unit;
  double scale;
};
const Spelling kSpellings[] = {
    {"mm", {1, 0, 0, 0}, 1},     {"mm2", {2, 0, 0, 0}, 1},    {"mm²", {2, 0, 0, 0}, 1},
    {"mm3", {3, 0, 0, 0}, 1},    {"mm³", {3, 0, 0, 0}, 1},    {"mm/s", {1, -1, 0, 0}, 1},
    {"mm/s2", {1, -2, 0, 0}, 1}, {"mm/s²", {1, -2, 0, 0}, 1}, {"mm3/s", {3, -1, 0, 0}, 1},
    {"mm³/s", {3, -1, 0, 0}, 1}, {"deg", {0, 0, 1, 0}, 1},    {"°", {0, 0, 1, 0}, 1},
    {"s", {0, 1, 0, 0}, 1},      {"°C", {0, 0, 0, 1}, 1},     {"C", {0, 0, 0, 1}, 1},
    {"%", {0, 0, 0, 0}, 0.01},
};
}  // namespace

std::optional<UnitSpelling> parse_unit(std::string_view written) {
  for (const auto& s : kSpellings)
    if (s.text == written) return UnitSpelling{s.unit, s.scale};
  return std::nullopt;
}

const std::vector<std::string_view>& unit_spellings() {
  static const std::vector<std::string_view> all = [] {
    std::vector<std::string_view> v;
    for (const auto& s : kSpellings) v.push_back(s.text);
    return v;
  }();
  return all;
}

Type Type::of(schema::Type t, schema::Unit u, schema::EnumType e) {
  switch (t) {
    case schema::Type::Number:
      return number(Unit::from_schema(u));
    case schema::Type::Int:
      return integer();
    case schema::Type::Bool:
      return boolean();
    case schema::Type::Enum:
      return enumeration(e);
    case schema::Type::Text:
      return text();
  }
  return error();
}

std::string Type::describe() const {
  switch (kind) {
    case Kind::Error:
      return "an invalid value";
    case Kind::Int:
      return "an integer";
    case Kind::Number:
      return unit.plain() ? "a plain number" : fmt::format("a number in `{}`", unit.name());
    case Kind::Bool:
      return "a boolean";
    case Kind::Enum:
      return fmt::format("a `{}` value", schema::enum_info(enum_type).name);
    case Kind::Text:
      return "a name";
  }
  return "?";
}

}  // namespace tranche::ast
