// Perimeters: closed loops that follow an island's real borders (its outline and holes) inward.
// Artificial cuts (hole bridging, the monotone decomposition) are made later, inside the fill
// region, so no loop ever runs along one.
//
// Loop k's centreline is the island shrunk by d_k, with round joins: d_0 = w_0/2 puts the outer
// bead's edge exactly on the outline (round joins reproduce reflex corners instead of
// overshooting them as a miter would), and d_k = d_{k-1} + spacing. Loops k ≥ 1 are opened
// (shrunk then grown by 0.3·spacing) so that where a part is too thin for them they vanish
// instead of laying two overlapping beads.
#pragma once

#include <vector>

#include "geometry/core/geom.h"

namespace tranche::toolpath {

struct Loop {
  geo::Ring ring;  // centreline; counter-clockwise around material, clockwise around holes
  int depth = 0;   // 0 = outer perimeter
  bool hole = false;
  // Below 1 for a thin wall: an island too thin for any loop is printed as one loop around
  // its core with the flow scaled so that the plastic matches the island's area (its parts
  // narrower than PerimeterSpec::min_feature left out).
  double flow_scale = 1.0;
};

struct PerimeterSpec {
  std::vector<double> widths = {0.45, 0.45};  // mm, one per loop, outermost first
  double fill_width = 0.45;                   // mm, width of the infill that meets the innermost loop
  double height = 0.2;                        // mm, layer height
  double infill_overlap = 0.15;               // ratio of fill_width the fill region reaches into the loops
  // mm: parts of a thin island narrower than this are not printed (a nozzle cannot lay a bead
  // that thin; PrusaSlicer's thin walls use nozzle / 3 too).
  double min_feature = 0.4 / 3;
};

struct Perimeters {
  std::vector<Loop> loops;  // by depth, outermost first
  // Where the fill's centrelines may go: the island minus every loop's bead, kept one fill
  // spacing (less the overlap) away from the beads. It includes gaps a vanished loop left
  // when they are wide enough for a fill bead.
  geo::Rings fill_region;
};

// `island`: the island's outline and holes (non-zero fill). Widths and heights in mm.
Perimeters make_perimeters(const geo::Rings& island, const PerimeterSpec& spec);

}  // namespace tranche::toolpath
