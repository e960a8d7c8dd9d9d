// Overhangs: the part of an island that rests on nothing, the first question of support
// material. An island leans out over the layer below by at most `reach` (the layer's height
// times tan(support_angle), the angle from vertical) before it needs holding up; what lies
// further out is an overhang, unless it is a bridge (held on two sides and short enough to span)
// or a speck smaller than the nozzle. Pure geometry on model units: the rules' decisions arrive
// as an OverhangSpec (geometry/plan/support_pass decides them per island).
#pragma once

#include <vector>

#include "geometry/core/geom.h"

namespace tranche::support {

struct OverhangSpec {
  double reach_mm = 0.2;      // how far an island may lean out over the layer below, unsupported
  double nozzle_mm = 0.4;     // overhangs smaller than a nozzle (area under a nozzle's disc) are left alone
  double max_bridge_mm = 10;  // a region held on two sides, no point further than half this from a hold: a bridge (0: none)
  // Numerical slivers narrower than this (what a slope barely steeper than support_angle leaves on
  // each layer) are dropped.
  double min_width_mm = 0.04;
};

// Each outer ring of `region` with the holes inside it (Clipper's nesting): one region per
// connected piece. Rings follow the usual orientation (outer CCW, holes CW).
std::vector<geo::Rings> components(const geo::Rings& region);
// The same for a boolean's result (rings that do not cross, outers CCW, holes CW, as every
// SupportLayer region is), without the union: each hole goes to the smallest outer around one of
// its vertices; outers in the order given. Falls back on components() when a hole has no vertex
// strictly inside an outer.
std::vector<geo::Rings> pieces(const geo::Rings& region);

// Length (mm) of open lines.
double lines_length(const geo::Rings& lines);

// Whether `piece` (one connected overhang) is a bridge over the material `below`: at least 2 mm
// across somewhere (a narrower sliver is a curved underside's, printed by the walls), and in some
// direction, straight lines across it that land on `below` at both ends (carried on by `hold_mm`,
// how far outside the piece a hold may lie: the reach plus a little) and are at most
// max_bridge_mm long make at least half of the lines' length.
bool is_bridge(const geo::Rings& piece, const geo::Rings& below, double max_bridge_mm, double hold_mm);

// What of `island` needs support: the island minus `below_reach` (the layer below grown by the
// reach), without slivers, specks and bridges over `below`.
geo::Rings overhang(const geo::Rings& island, const geo::Rings& below_reach, const geo::Rings& below,
                    const OverhangSpec& spec);

}  // namespace tranche::support
