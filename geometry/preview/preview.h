// The G-code preview's data: what was printed, layer by layer, and why. The pipeline fills a
// PreviewPrint from its layer plans (one PreviewLayer per printed layer, paths in print order);
// write_preview_html (preview_html.h) draws it in a browser and the thumbnail rasterizer
// (thumbnail.h) renders it for printer screens. Nothing here depends on the toolpath planner:
// coordinates are bed coordinates in mm (what the G-code says), values are as printed.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "runtime/schema/schema.h"

namespace tranche::preview {

struct PointMm {
  float x = 0, y = 0;  // mm, bed coordinates
};

// Where a value in a decision chain came from, lowest cascade layer first.
enum class SourceKind : uint8_t {
  SchemaDefault,   // properties.def's constant
  BuiltinDefault,  // stdlib/defaults.rules or the built-in defaults (speed by path kind...)
  Profile,         // a printer or material profile's rule (stdlib/printers, stdlib/materials)
  Script,          // the --fill-angle-script hook
  Rule,            // a rule of a --rules file
  Set,             // a --set key=value override
  Slicer,          // the slicer itself after the cascade (the min_layer_time slowdown...)
};
inline constexpr int kSourceKindCount = 7;
const char* source_kind_name(SourceKind k);  // "schema default", "rule", "--set", ...

// One step of a value chain: the slot held `value` after this source set it.
struct ChainStep {
  double value = 0;  // in the property's unit (schema::PropInfo::unit): mm/s, ratio, mm, deg
  SourceKind source = SourceKind::SchemaDefault;
  std::string rule;  // rule name ("bridges"); empty for defaults and --set
  std::string file;  // rules file as given on the command line; empty for schema defaults and --set
  int line = 0;      // 1-based line of the assignment; 0 when unknown
  std::string text;  // the assignment as written ("speed = speed * 50%", or "flow=0.95" for --set), optional
};

// The cascade of one property for one path (or piece): defaults first, the decider last.
struct SlotChain {
  schema::PropId prop = schema::PropId::Speed;
  std::vector<ChainStep> steps;  // never empty once recorded; steps.back() decided the value
};

// G-code an executor (`before path`, `after island`...) added around the path.
struct ExecutorNote {
  bool after = false;                         // false: before the path's G-code
  schema::Level level = schema::Level::Path;  // the hook's level (an island hook runs once per island)
  std::string rule, file;
  int line = 0;
  std::string text;  // the G-code lines it wrote, '\n'-separated
};

// The replacer that produced the path's G-code instead of the default.
struct ReplacerNote {
  std::string rule, file;
  int line = 0;
  bool emitted_default = false;  // its body ran `default` (the default G-code is in its output)
};

// Everything recorded about why a path (or one of its pieces) is printed as it is. Paths that
// were decided alike may share one Provenance (the HTML stores each distinct one once).
struct Provenance {
  std::vector<SlotChain> slots;  // any subset of properties; typically speed, flow, width, fan, fill_angle
  std::vector<ExecutorNote> executors;
  std::shared_ptr<const ReplacerNote> replacer;  // null: the default G-code
};

// One extrusion path: a polyline of pieces (straight moves), printed in order.
struct PreviewPath {
  schema::PathKind kind = schema::PathKind::Custom;
  std::vector<PointMm> points;  // >= 2 for a printed path; closed loops repeat the first point
  // Per piece (points.size() - 1 entries) or a single entry for every piece.
  std::vector<float> width;                    // mm
  std::vector<float> speed;                    // mm/s, as written in F (after any min_layer_time slowdown)
  std::vector<float> flow;                     // extrusion multiplier, ratio (geometric corrections included)
  float fan = 0;                               // ratio 0..1
  float nozzle_temp = 0;                       // °C
  int island = -1, cell = -1, perimeter = -1;  // context indices (-1: not applicable)
  std::shared_ptr<const Provenance> provenance;  // null: nothing recorded
  // Per piece where pieces were decided differently (empty: `provenance` for all pieces).
  std::vector<std::shared_ptr<const Provenance>> piece_provenance;

  size_t piece_count() const { return points.size() < 2 ? 0 : points.size() - 1; }
  float width_at(size_t i) const { return width.size() == 1 ? width[0] : width[i]; }
  float speed_at(size_t i) const { return speed.size() == 1 ? speed[0] : speed[i]; }
  float flow_at(size_t i) const { return flow.size() == 1 ? flow[0] : flow[i]; }
};

// A move without extrusion between two paths (or from the layer change).
struct PreviewTravel {
  PointMm from, to;
  std::vector<PointMm> via;  // combing points between from and to
  bool retracted = false;
};

struct PreviewLayer {
  int index = 0;
  float z = 0, height = 0;         // mm: top of the layer and its thickness
  std::vector<PreviewPath> paths;  // print order
  std::vector<PreviewTravel> travels;
};

struct PreviewPrint {
  float bed_x = 200, bed_y = 200;    // mm
  std::string title;                 // model name, shown in the page's title
  std::vector<PreviewLayer> layers;  // bottom to top
};

// Cross-section of a bead of width w and height h (Slic3r's rounded rectangle), mm².
double bead_area_mm2(double width_mm, double height_mm);
// Plastic extruded per second by a piece, mm³/s: bead area × speed × flow.
double volumetric_rate_mm3_s(double width_mm, double height_mm, double speed_mm_s, double flow);

}  // namespace tranche::preview
