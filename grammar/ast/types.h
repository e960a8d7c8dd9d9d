// Value types of the rule language. A number carries a unit: exponents of four base
// dimensions (length in mm, time in s, angle in deg, temperature in °C), so `mm/s * s` is mm
// and `sqrt(mm2)` is mm. Ratios and percentages are plain numbers (`50%` is 0.5).
#pragma once

#include <compare>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "runtime/schema/schema.h"

namespace tranche::ast {

struct Unit {
  int16_t mm = 0, s = 0, deg = 0, temp = 0;

  static Unit from_schema(schema::Unit u);
  bool plain() const { return mm == 0 && s == 0 && deg == 0 && temp == 0; }
  Unit operator*(const Unit& o) const;
  Unit operator/(const Unit& o) const;
  // Halves every exponent; nothing when one is odd (`sqrt(mm3)`).
  std::optional<Unit> sqrt() const;
  // Exponents stay small (|e| <= kMaxExponent) so that folding `x*x*x...` cannot overflow them.
  bool in_range() const;
  // As written in rules: "mm/s", "mm2", "°C"; composites like "mm2/s", "1/s"; "" when plain.
  std::string name() const;
  // "`mm/s`" or "a plain number", for messages.
  std::string quoted() const;
  auto operator<=>(const Unit&) const = default;

  static constexpr int kMaxExponent = 12;
};

// A unit as written after a number, and the factor it applies (`%` is 0.01).
struct UnitSpelling {
  Unit unit;
  double scale = 1;
};
std::optional<UnitSpelling> parse_unit(std::string_view written);
// Every accepted spelling, for "did you mean".
const std::vector<std::string_view>& unit_spellings();

enum class Kind : uint8_t {
  Error,  // an expression that already produced a diagnostic: never reported again
  Int,    // integer (no unit)
  Number,
  Bool,
  Enum,
  Text,   // a name (object.name): compared with quoted text only, never computed with
};

struct Type {
  Kind kind = Kind::Error;
  Unit unit;  // Number only
  schema::EnumType enum_type = schema::EnumType::None;

  static Type error() { return {}; }
  static Type integer() { return {Kind::Int, {}, schema::EnumType::None}; }
  static Type number(Unit u = {}) { return {Kind::Number, u, schema::EnumType::None}; }
  static Type boolean() { return {Kind::Bool, {}, schema::EnumType::None}; }
  static Type enumeration(schema::EnumType e) { return {Kind::Enum, {}, e}; }
  static Type text() { return {Kind::Text, {}, schema::EnumType::None}; }
  static Type of(schema::Type t, schema::Unit u, schema::EnumType e);

  bool is_error() const { return kind == Kind::Error; }
  bool numeric() const { return kind == Kind::Int || kind == Kind::Number; }
  // "a number in mm/s", "an integer", "a plain number", "a boolean", "a `path_kind` value".
  std::string describe() const;
  bool operator==(const Type&) const = default;
};

}  // namespace tranche::ast
