#include <doctest/doctest.h>

#include "grammar/ast/types.h"

using tranche::ast::parse_unit;
using tranche::ast::Type;
using tranche::ast::Unit;
namespace schema = tranche::schema;

TEST_CASE("units: schema units map to exponents of mm, s, deg, °C") {
  CHECK(Unit::from_schema(schema::Unit::MmPerS) == Unit{1, -1, 0, 0});
  CHECK(Unit::from_schema(schema::Unit::Mm3PerS) == Unit{3, -1, 0, 0});
  CHECK(Unit::from_schema(schema::Unit::MmPerS2) == Unit{1, -2, 0, 0});
  CHECK(Unit::from_schema(schema::Unit::Celsius) == Unit{0, 0, 0, 1});
  CHECK(Unit::from_schema(schema::Unit::Ratio).plain());
  CHECK(Unit::from_schema(schema::Unit::None).plain());
}

TEST_CASE("units: multiplication and division add and subtract exponents") {
  Unit mm{1, 0, 0, 0}, s{0, 1, 0, 0}, mm2{2, 0, 0, 0};
  Unit speed = mm / s;
  CHECK(speed == Unit::from_schema(schema::Unit::MmPerS));
  CHECK(speed * s == mm);
  CHECK(mm * mm == mm2);
  CHECK(mm2 / mm == mm);
  CHECK((mm / mm).plain());
  CHECK((speed * mm2) / s == Unit{3, -2, 0, 0});
}

TEST_CASE("units: sqrt halves even exponents and refuses odd ones") {
  CHECK(Unit{2, 0, 0, 0}.sqrt() == Unit{1, 0, 0, 0});
  CHECK(Unit{2, -2, 0, 0}.sqrt() == Unit{1, -1, 0, 0});
  CHECK_FALSE(Unit{3, 0, 0, 0}.sqrt().has_value());
  CHECK_FALSE(Unit{1, -1, 0, 0}.sqrt().has_value());
  CHECK(Unit{}.sqrt() == Unit{});
}

TEST_CASE("units: names read like the rules that write them") {
  CHECK(Unit{1, -1, 0, 0}.name() == "mm/s");
  CHECK(Unit{2, 0, 0, 0}.name() == "mm2");
  CHECK(Unit{3, -1, 0, 0}.name() == "mm3/s");
  CHECK(Unit{1, -2, 0, 0}.name() == "mm/s2");
  CHECK(Unit{0, 0, 1, 0}.name() == "deg");
  CHECK(Unit{0, 0, 0, 1}.name() == "°C");
  CHECK(Unit{0, -1, 0, 0}.name() == "1/s");
  CHECK(Unit{2, -1, 0, 0}.name() == "mm2/s");
  CHECK(Unit{1, 1, 0, 0}.name() == "mm·s");
  CHECK(Unit{}.name().empty());
  CHECK(Unit{}.quoted() == "a plain number");
  CHECK(Unit{1, 0, 0, 0}.quoted() == "`mm`");
}

TEST_CASE("units: every spelling parses, percent scales by 1/100") {
  struct Case {
    const char* text;
    Unit unit;
    double scale;
  };
  const Case cases[] = {
      {"mm", {1, 0, 0, 0}, 1},     {"mm2", {2, 0, 0, 0}, 1},    {"mm²", {2, 0, 0, 0}, 1},
      {"mm3", {3, 0, 0, 0}, 1},    {"mm³", {3, 0, 0, 0}, 1},    {"mm/s", {1, -1, 0, 0}, 1},
      {"mm/s2", {1, -2, 0, 0}, 1}, {"mm/s²", {1, -2, 0, 0}, 1}, {"mm3/s", {3, -1, 0, 0}, 1},
      {"mm³/s", {3, -1, 0, 0}, 1}, {"deg", {0, 0, 1, 0}, 1},    {"°", {0, 0, 1, 0}, 1},
      {"s", {0, 1, 0, 0}, 1},      {"°C", {0, 0, 0, 1}, 1},     {"C", {0, 0, 0, 1}, 1},
      {"%", {0, 0, 0, 0}, 0.01},
  };
  for (const auto& c : cases) {
    INFO(c.text);
    auto p = parse_unit(c.text);
    REQUIRE(p.has_value());
    CHECK(p->unit == c.unit);
    CHECK(p->scale == c.scale);
  }
  CHECK_FALSE(parse_unit("mms").has_value());
  CHECK_FALSE(parse_unit("cm").has_value());
  CHECK_FALSE(parse_unit("").has_value());
}

TEST_CASE("units: exponents are bounded so that folding cannot overflow them") {
  Unit u{1, 0, 0, 0};
  for (int i = 0; i < 11; ++i) u = u * Unit{1, 0, 0, 0};
  CHECK(u.in_range());
  CHECK_FALSE((u * Unit{1, 0, 0, 0}).in_range());
}

TEST_CASE("types: descriptions used in messages") {
  CHECK(Type::integer().describe() == "an integer");
  CHECK(Type::number().describe() == "a plain number");
  CHECK(Type::number(Unit{1, -1, 0, 0}).describe() == "a number in `mm/s`");
  CHECK(Type::boolean().describe() == "a boolean");
  CHECK(Type::enumeration(schema::EnumType::PathKind).describe() == "a `path_kind` value");
  CHECK(Type::of(schema::Type::Number, schema::Unit::Mm2, schema::EnumType::None) ==
        Type::number(Unit{2, 0, 0, 0}));
}
