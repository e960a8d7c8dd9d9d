// The plan of one layer: every path in print order with its decisions, ready to be written.
// Layers are planned in parallel (layer_loop.h) and written in order (geometry/gcode), so a plan
// holds everything the writer needs and nothing that depends on another layer's plan.
// Coordinates are model units (1 nm); the writer adds the bed offset (PrintSetup::shift).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/core/geom.h"
#include "runtime/context/context.h"
#include "runtime/schema/schema.h"

namespace tranche::toolpath {
class Comber;
}

namespace tranche::plan {

// What the cascade recorded while deciding one element (provenance, --export-preview): filled
// only when the run records provenance (PrintSetup::provenance).
struct TraceLog final : ctx::Trace {
  std::vector<ctx::TraceStep> steps;
  uint32_t replacer = UINT32_MAX;  // the replacer rule that generated the element's output
  void step(const ctx::TraceStep& s) override { steps.push_back(s); }
  void replaced(schema::Level, uint32_t rule) override { replacer = rule; }
};
using TraceRef = std::shared_ptr<TraceLog>;

// One step of a replacer's output (`move to`, `gcode`, `comment`, `default`, `retract`).
struct Op {
  enum class Kind : uint8_t { Extrude, Travel, Text, Default, Retract };
  Kind kind = Kind::Text;
  geo::Point to;        // Extrude / Travel
  float speed = 0;      // mm/s
  float flow = 1;       // ratio
  float width = 0.45f;  // mm
  std::string text;     // Text: a whole G-code line

  static Op line(std::string_view gcode) {
    Op o;
    o.text = std::string(gcode);
    return o;
  }
  static Op of(Kind k) {
    Op o;
    o.kind = k;
    return o;
  }
};

// Speed and flow of one piece (or of every piece when decided once per path).
struct PieceProps {
  float speed = 60;  // mm/s
  float flow = 1;    // ratio
};

struct PathPlan {
  schema::PathKind kind = schema::PathKind::Custom;
  int perimeter = -1;  // 0 = outermost; -1 when not a perimeter
  int cell = -1;       // index of the cell it fills within the island; -1 otherwise
  int index = 0;       // order within the island
  bool closed = false;
  float width = 0.45f;      // mm, decided at path planning (gap fill: the mean of `widths`)
  // mm, per piece, for a path whose width varies (gap fill, variable-width walls); empty when
  // every piece is `width` wide. E per mm follows each piece's width.
  std::vector<float> widths;
  float flow_scale = 1.0f;  // geometric correction (solid pitch fitted to its cell)
  // Geometric flow of the pieces that run along a real border: a solid zig-zag's connector
  // there lies half over the ends of the lines it joins, so it lays half a bead.
  float border_flow = 1.0f;
  geo::Ring pts;                       // polyline; closed loops end at their first point
  std::vector<schema::Border> border;  // per piece
  std::vector<float> overhang;         // per piece, only when rules need piece fields
  std::vector<PieceProps> pieces;      // per piece, or a single entry for all (hoisted)
  float fan = 0;                       // ratio, decided at the cooling stage
  bool retract = false;                // retract for the travel that reaches pts[0]
  geo::Ring via;                       // that travel's intermediate points (combing around holes)
  bool replaced = false;               // output is `ops` (which may include the default) instead of pts
  std::vector<Op> ops;
  ctx::PropertyValues props;  // every property as decided for this path (executors read them)
  // Provenance (when recorded): the path's decisions (path planning, piece, cooling) and, when
  // speed or flow vary along it, each piece's.
  TraceRef trace;
  std::vector<TraceRef> piece_traces;

  size_t piece_count() const { return pts.size() < 2 ? 0 : pts.size() - 1; }
  const PieceProps& piece(size_t i) const { return pieces.size() == 1 ? pieces[0] : pieces[i]; }
  float piece_width(size_t i) const { return i < widths.size() ? widths[i] : width; }
  // flow_scale, times border_flow for a piece along a real border.
  double piece_scale(size_t i) const {
    return i < border.size() && border[i] == schema::Border::Real ? flow_scale * border_flow : flow_scale;
  }
  double length_mm() const;
};

struct CellPlan {
  int index = 0;
  double area_mm2 = 0;
  double fill_angle_deg = 0;
  bool solid = false;
};

struct IslandPlan {
  int index = 0;
  int object = 0;    // the plate's object it belongs to
  int object_text = -1;  // object.name: the index of its object's name among the rules' texts, or -1
  geo::Rings shape;  // outline and holes after any replacer offset
  // The same outline and holes at the print's `resolution`, which the outer walls follow; empty
  // when that is `shape` (resolution as coarse as the inner one, a replacer's offset).
  geo::Rings wall_outline;
  // What the outer walls follow: wall_outline, or the shape when that is empty.
  const geo::Rings& outline() const { return wall_outline.empty() ? shape : wall_outline; }
  // island.* fields, in the units of fields.def (mm, mm², ratio)
  double area = 0, border_length = 0;
  double supported = 0, covered = 0;                          // computed only when a rule reads them
  double size_x = 0, size_y = 0, center_x = 0, center_y = 0;  // centre in bed coordinates
  int holes = 0;
  // Computed only when a rule reads them: the outline's longest stretch (deg), the narrowest
  // width (mm), convexity; the island under this one (mm², ratio).
  double longest_edge_angle = 0, min_width = 0;
  bool convex = false;
  double below_area = 0, below_supported = 0;
  bool support = false;       // an island of support material (island.support)
  geo::Rings fill_region;     // support islands: the shape less half a bead, which beads fill and travels follow
  double overhang_area = 0;   // mm², island.overhang_area (geometry/plan/support_pass)
  ctx::PropertyValues props;  // as decided at the island stage
  TraceRef trace;             // provenance of the island stage (when recorded)
  std::vector<CellPlan> cells;
  std::vector<PathPlan> paths;  // print order; paths of a cell follow each other
  bool replaced = false;
  std::vector<Op> ops;  // replacer output when `replaced`
};

struct LayerPlan {
  int index = 0;
  double z_bottom = 0, z = 0, height = 0, area = 0;  // mm, mm²
  double max_slope = 0;                              // deg, layer.max_slope
  double support_area = 0;                           // mm², layer.support_area
  ctx::PropertyValues props;                         // as decided at the layer stage
  TraceRef trace;                                    // provenance of the layer stage and a layer-wide fan
  std::vector<PathPlan> skirt;                       // skirt and brim, before the islands, on layer 0
  std::vector<IslandPlan> islands;                   // print order
  double time_s = 0;        // estimated, excluding the travel from the previous layer
  double extruded_mm3 = 0;  // plastic volume
  bool slowed = false;      // min_layer_time slowed it down
  // The layer's material for routing travels inside it (the writer combs the layer change).
  std::shared_ptr<const toolpath::Comber> comber;
};

}  // namespace tranche::plan
