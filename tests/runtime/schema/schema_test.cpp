#include <doctest/doctest.h>

#include <set>
#include <string>

#include "runtime/schema/schema.h"

using namespace tranche::schema;

TEST_CASE("schema: every field has a unique dotted name owned by its level (or its island's object)") {
  std::set<std::string_view> names;
  for (const auto& f : fields()) {
    CHECK(names.insert(f.name).second);
    auto dot = f.name.find('.');
    REQUIRE(dot != std::string_view::npos);
    const auto prefix = f.name.substr(0, dot);
    if (prefix == "object")  // an island's object: known with the island, or print-wide (object.count)
      CHECK((f.level == Level::Island || f.level == Level::Print));
    else
      CHECK(prefix == level_name(f.level));
    CHECK(!f.doc.empty());
    // A field cannot be known before the level it describes exists.
    CHECK(static_cast<int>(stage_level(f.stage)) >= static_cast<int>(f.level) - (f.level == Level::Piece ? 0 : 0));
    if (f.type == Type::Enum) CHECK(f.enum_type != EnumType::None);
  }
  CHECK(find_field("layer.index") == FieldId::LayerIndex);
  CHECK_FALSE(find_field("layer.indx").has_value());
}

TEST_CASE("schema: properties have defaults inside their physical range") {
  std::set<std::string_view> names;
  for (const auto& p : properties()) {
    CHECK(names.insert(p.name).second);
    CHECK(p.min <= p.default_value);
    CHECK(p.default_value <= p.max);
    CHECK(!p.doc.empty());
  }
  CHECK(find_property("speed") == PropId::Speed);
  CHECK(property(PropId::LayerHeight).stage == Stage::LayerPlan);
  CHECK(property(PropId::FillAngle).stage == Stage::Island);
}

TEST_CASE("schema: C++ enums agree with the enum tables") {
  CHECK(find_enum_value(EnumType::PathKind, "outer_perimeter") == static_cast<int>(PathKind::OuterPerimeter));
  CHECK(find_enum_value(EnumType::PathKind, "custom") == static_cast<int>(PathKind::Custom));
  CHECK(find_enum_value(EnumType::PathKind, "support_interface") == static_cast<int>(PathKind::SupportInterface));
  CHECK(enum_info(EnumType::PathKind).values.size() == static_cast<size_t>(PathKind::GapFill) + 1);
  CHECK(find_enum_value(EnumType::Support, "normal") == static_cast<int>(Support::Normal));
  CHECK(find_enum_value(EnumType::SupportPattern, "grid") == static_cast<int>(SupportPattern::Grid));
  CHECK(find_enum_value(EnumType::InfillPattern, "gyroid") == static_cast<int>(InfillPattern::Gyroid));
  CHECK(find_enum_value(EnumType::InfillPattern, "lightning") == static_cast<int>(InfillPattern::Lightning));
  CHECK(enum_info(EnumType::InfillPattern).values.size() == static_cast<size_t>(InfillPattern::Lightning) + 1);
  CHECK(find_enum_value(EnumType::OverhangWalls, "bridge") == static_cast<int>(OverhangWalls::Bridge));
  CHECK(enum_info(EnumType::OverhangWalls).values.size() == static_cast<size_t>(OverhangWalls::Bridge) + 1);
  CHECK(find_enum_value(EnumType::Border, "artificial") == static_cast<int>(Border::Artificial));
  CHECK(find_enum_value(EnumType::Flavor, "reprapfirmware") == static_cast<int>(Flavor::RepRapFirmware));
  CHECK(find_enum_value(EnumType::Seam, "rear") == static_cast<int>(Seam::Rear));
  CHECK(enum_value_name(EnumType::Border, 1) == "real");
}

TEST_CASE("schema: the hash is stable within a build and non-trivial") {
  CHECK(schema_hash() == schema_hash());
  CHECK(schema_hash() != 0);
}
