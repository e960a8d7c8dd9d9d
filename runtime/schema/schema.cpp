#include "runtime/schema/schema.h"

#include <array>
#include <string>
#include <vector>

#include "base/fnv.h"

namespace tranche::schema {
namespace {

constexpr FieldInfo kFields[] = {
#define TRANCHE_FIELD(Id, name, level, stage, type, unit, enum_type, doc) \
  {FieldId::Id, name, Level::level, Stage::stage, Type::type, Unit::unit, EnumType::enum_type, doc},
#include "runtime/schema/fields.def"
#undef TRANCHE_FIELD
};

constexpr PropInfo kProps[] = {
#define TRANCHE_PROP(Id, name, stage, type, unit, enum_type, def, lo, hi, doc) \
  {PropId::Id, name, Stage::stage, Type::type, Unit::unit, EnumType::enum_type, def, lo, hi, doc},
#include "runtime/schema/properties.def"
#undef TRANCHE_PROP
};

struct EnumSource {
  EnumType id;
  std::string_view name;
  std::string_view values;  // space separated
  std::string_view doc;
};
constexpr EnumSource kEnumSources[] = {
    {EnumType::None, "", "", ""},
#define TRANCHE_ENUM(Id, name, values, doc) {EnumType::Id, name, values, doc},
#include "runtime/schema/enums.def"
#undef TRANCHE_ENUM
};
constexpr size_t kEnumCount = std::size(kEnumSources);

struct EnumTables {
  std::array<std::vector<std::string_view>, kEnumCount> values;
  std::array<EnumInfo, kEnumCount> infos;
  EnumTables() {
    for (size_t i = 0; i < kEnumCount; ++i) {
      std::string_view s = kEnumSources[i].values;
      while (!s.empty()) {
        size_t sp = s.find(' ');
        values[i].push_back(s.substr(0, sp));
        if (sp == std::string_view::npos) break;
        s.remove_prefix(sp + 1);
      }
      infos[i] = EnumInfo{kEnumSources[i].id, kEnumSources[i].name, values[i], kEnumSources[i].doc};
    }
  }
};
const EnumTables& enum_tables() {
  static const EnumTables t;
  return t;
}

}  // namespace

std::span<const FieldInfo> fields() { return kFields; }
std::span<const PropInfo> properties() { return kProps; }
std::span<const EnumInfo> enums() { return enum_tables().infos; }

const FieldInfo& field(FieldId id) { return kFields[static_cast<size_t>(id)]; }
const PropInfo& property(PropId id) { return kProps[static_cast<size_t>(id)]; }
const EnumInfo& enum_info(EnumType id) { return enum_tables().infos[static_cast<size_t>(id)]; }

std::optional<FieldId> find_field(std::string_view name) {
  for (const auto& f : kFields)
    if (f.name == name) return f.id;
  return std::nullopt;
}

std::optional<PropId> find_property(std::string_view name) {
  for (const auto& p : kProps)
    if (p.name == name) return p.id;
  return std::nullopt;
}

std::optional<int> find_enum_value(EnumType type, std::string_view value) {
  const auto& vals = enum_info(type).values;
  for (size_t i = 0; i < vals.size(); ++i)
    if (vals[i] == value) return static_cast<int>(i);
  return std::nullopt;
}

std::string_view enum_value_name(EnumType type, int value) {
  const auto& vals = enum_info(type).values;
  if (value < 0 || static_cast<size_t>(value) >= vals.size()) return "?";
  return vals[static_cast<size_t>(value)];
}

std::string_view level_name(Level l) {
  static constexpr std::string_view names[] = {"print", "layer", "island", "cell", "path", "piece"};
  return names[static_cast<size_t>(l)];
}

std::string_view stage_name(Stage s) {
  static constexpr std::string_view names[] = {
      "print",  "layer planning", "layer", "island", "cell", "path planning",
      "path",   "piece",          "cooling"};
  return names[static_cast<size_t>(s)];
}

Level stage_level(Stage s) {
  switch (s) {
    case Stage::Print: return Level::Print;
    case Stage::LayerPlan:
    case Stage::Layer: return Level::Layer;
    case Stage::Island: return Level::Island;
    case Stage::Cell: return Level::Cell;
    case Stage::PathPlan:
    case Stage::Path:
    case Stage::Cooling: return Level::Path;
    case Stage::Piece: return Level::Piece;
  }
  return Level::Print;
}

std::string_view unit_name(Unit u) {
  switch (u) {
    case Unit::None: return "";
    case Unit::Ratio: return "%";
    case Unit::Mm: return "mm";
    case Unit::Mm2: return "mm2";
    case Unit::Mm3: return "mm3";
    case Unit::MmPerS: return "mm/s";
    case Unit::MmPerS2: return "mm/s2";
    case Unit::Mm3PerS: return "mm3/s";
    case Unit::Deg: return "deg";
    case Unit::S: return "s";
    case Unit::Celsius: return "°C";
  }
  return "";
}

Stage finest_stage(PropId id) { return id == PropId::FillAngle ? Stage::Cell : property(id).stage; }

uint64_t schema_hash() {
  uint64_t h = kFnv1a64Basis;
  auto mix = [&h](std::string_view s) {
    h = fnv1a64(s, h);
    h = fnv1a64("\xff", h);  // a separator no name contains
  };
  auto mixn = [&mix](int v) { mix(std::to_string(v)); };
  for (const auto& f : kFields) {
    mix(f.name);
    mixn(static_cast<int>(f.level));
    mixn(static_cast<int>(f.stage));
    mixn(static_cast<int>(f.type));
    mixn(static_cast<int>(f.unit));
    mixn(static_cast<int>(f.enum_type));
  }
  for (const auto& p : kProps) {
    mix(p.name);
    mixn(static_cast<int>(p.stage));
    mixn(static_cast<int>(p.type));
    mixn(static_cast<int>(p.unit));
    mixn(static_cast<int>(p.enum_type));
    mixn(static_cast<int>(finest_stage(p.id)));
  }
  for (const auto& e : enum_tables().infos) {
    mix(e.name);
    for (auto v : e.values) mix(v);
  }
  return h;
}

}  // namespace tranche::schema
