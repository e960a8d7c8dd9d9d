// The context schema: every field a rule can read and every property a rule can set, with
// its type, unit and the stage at which it becomes known (fields) or is decided (properties).
//
// This is the single contract between the rule compiler (name resolution, type/unit/stage
// checking), the runtime (a field is read by its slot number, never by name) and the slicer
// (which fills the slots as it walks print ⊃ layer ⊃ island ⊃ cell ⊃ path ⊃ piece).
// The tables live in fields.def, properties.def and enums.def; everything here derives from them.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace tranche::schema {

// Context levels: the nesting of the slicing loop. Executors hook `before`/`after` a level.
enum class Level : uint8_t { Print, Layer, Island, Cell, Path, Piece };
inline constexpr int kLevelCount = 6;

// Stages: the order in which the slicer decides things. A field is known from its stage on;
// a property is decided at its stage and a rule that sets it may read only fields known by then.
// Stages refine levels where one level decides things in two steps (a layer's height is planned
// before the layer is sliced; a path's width is chosen before its geometry exists; the fan is
// chosen after the layer's time is known).
enum class Stage : uint8_t {
  Print,      // once, before anything is sliced: the model and machine are known
  LayerPlan,  // per layer, while planning heights: only the index and the bottom z are known
  Layer,      // per layer, once every layer is sliced: areas, islands, other layers
  Island,     // per island: its shape, area, what supports and covers it
  Cell,       // per cell of the island's fill decomposition
  PathPlan,   // per path, before its geometry is built: its kind and perimeter number
  Path,       // per path, with its geometry: length, points
  Piece,      // per piece (one straight extrusion move) of a path
  Cooling,    // per path/piece, once the layer's print time is estimated
};
inline constexpr int kStageCount = 9;

// Value types. At run time every scalar is stored as a double (ints, bools and enum values
// are exactly representable), so the VM reads any field with one load and no boxing.
// Text (a name: object.name) is stored as the index of the same text in the rule program's
// string table, or -1 when no rule names it: rules compare it with quoted text only (the
// compiler interns the text; see docs/language.md, "Names").
enum class Type : uint8_t { Number, Int, Bool, Enum, Text };

// Units, as written in rules. Percent is not a unit of its own: `50%` is the plain number 0.5.
enum class Unit : uint8_t {
  None,     // plain number or count
  Ratio,    // plain number shown as a percentage (fan, infill_density, island.supported)
  Mm,
  Mm2,
  Mm3,
  MmPerS,   // mm/s
  MmPerS2,  // mm/s2
  Mm3PerS,  // mm3/s
  Deg,
  S,
  Celsius,  // written °C or C in rules
};

// Enumerations: each enum type and its value names, in value order.
enum class EnumType : uint8_t {
  None,
#define TRANCHE_ENUM(Id, name, values, doc) Id,
#include "runtime/schema/enums.def"
#undef TRANCHE_ENUM
};

enum class FieldId : uint16_t {
#define TRANCHE_FIELD(Id, name, level, stage, type, unit, enum_type, doc) Id,
#include "runtime/schema/fields.def"
#undef TRANCHE_FIELD
  Count_
};
inline constexpr int kFieldCount = static_cast<int>(FieldId::Count_);

enum class PropId : uint16_t {
#define TRANCHE_PROP(Id, name, stage, type, unit, enum_type, def, lo, hi, doc) Id,
#include "runtime/schema/properties.def"
#undef TRANCHE_PROP
  Count_
};
inline constexpr int kPropCount = static_cast<int>(PropId::Count_);

// Enum values used by the slicer (the value of a path.kind field is static_cast<double>(PathKind)).
enum class PathKind : uint8_t {
  OuterPerimeter, InnerPerimeter, Infill, SolidInfill, TopSolid, BottomSolid, Bridge, Skirt,
  Ironing, Custom, Support, SupportInterface, Brim, GapFill
};
enum class Border : uint8_t { None, Real, Artificial };
enum class Flavor : uint8_t { Marlin, Klipper, RepRapFirmware };
enum class Seam : uint8_t { Aligned, Nearest, Rear, Random, SharpestCorner, Point };
enum class BedShape : uint8_t { Rectangular, Circular };
enum class PrintOrder : uint8_t { Layers, Sequential };
enum class Thumbnails : uint8_t { None, Png, Qoi };
enum class Support : uint8_t { None, Normal, Tree };
enum class SupportPattern : uint8_t { Lines, Grid };
enum class WallGenerator : uint8_t { Classic, Variable };
enum class OverhangWalls : uint8_t { Loops, Bridge };
enum class InfillPattern : uint8_t {
  Zigzag, Grid, Triangles, Cubic, Gyroid, Honeycomb, Concentric, Lightning
};

struct FieldInfo {
  FieldId id;
  std::string_view name;  // "layer.index"
  Level level;            // the context level the field belongs to
  Stage stage;            // from when its value is known
  Type type;
  Unit unit;
  EnumType enum_type;
  std::string_view doc;
};

struct PropInfo {
  PropId id;
  std::string_view name;  // "speed"
  Stage stage;            // when it is decided
  Type type;
  Unit unit;
  EnumType enum_type;
  double default_value;   // built-in default (context-dependent defaults are rules in stdlib/)
  double min, max;        // physical range; outside it the compiler warns (W-range)
  std::string_view doc;
  // A direction (fill_angle, its range a whole turn or more) is brought into [0°, 360°); a bounded
  // angle (support_angle: 0° to 90°) has a range like any number.
  bool wraps() const { return unit == Unit::Deg && max - min >= 360; }
};

struct EnumInfo {
  EnumType id;
  std::string_view name;                   // "path_kind"
  std::span<const std::string_view> values;  // value i is stored as the double i
  std::string_view doc;
};

std::span<const FieldInfo> fields();
std::span<const PropInfo> properties();
std::span<const EnumInfo> enums();

const FieldInfo& field(FieldId id);
const PropInfo& property(PropId id);
const EnumInfo& enum_info(EnumType id);

std::optional<FieldId> find_field(std::string_view name);
std::optional<PropId> find_property(std::string_view name);
// Value index of `value` in the enum, if it names one.
std::optional<int> find_enum_value(EnumType type, std::string_view value);
std::string_view enum_value_name(EnumType type, int value);

std::string_view level_name(Level);   // "print", "layer", ...
std::string_view stage_name(Stage);   // "print", "layer planning", ...
std::string_view unit_name(Unit);     // "mm/s", "°C", "" for None
Level stage_level(Stage);             // the context level a stage belongs to
// The last stage at which a property may be decided again for a finer element: its own stage,
// except fill_angle, decided per island and again per fill cell by rules that read `cell.*`
// (the island's fill is cut into cells at the island's angle; a cell decided otherwise is
// filled again at its own angle).
Stage finest_stage(PropId);

// A stable 64-bit hash of every table above (names, types, units, stages, enum values, in
// order). Bundles record it; a bundle compiled against another schema is refused.
uint64_t schema_hash();

}  // namespace tranche::schema
