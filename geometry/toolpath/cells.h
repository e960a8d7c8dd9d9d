// The shape a fill region is zig-zagged in, with every edge labelled: Real where it lies on the
// island's fill border (along the innermost perimeter), Artificial where it is the border between
// a solid and a sparse region. The region's cells are the zig-zags zigzag() makes of it: its
// monotone pieces at the resolution of the fill lines (docs/gcode.md, "Cells").
#pragma once

#include <vector>

#include "geometry/toolpath/edge_grid.h"
#include "geometry/toolpath/zigzag.h"

namespace tranche::toolpath {

// `region`: rings of one fill region (non-zero fill); `borders`: the island's fill border (the
// edges of its whole fill region, and of that region grown as solid regions are). The rings come out of a
// union: outer counter-clockwise, holes clockwise, none overlapping. An edge within `on_border_mm` of the
// fill border is real: between it and the border there is at most a sliver no other region's lines fill
// (regions are built by booleans with the neighbouring layers and rounded by openings, so their edges along
// the border are rarely exactly on it), and its line ends must reach the border.
FillShape region_shape(const geo::Rings& region, const std::vector<const EdgeGrid*>& borders,
                       double on_border_mm);

// The core of a cell, the zig-zag `cell` at `angle_deg`: each of its lines (the pieces that run
// along no border) widened to a strip one `pitch_mm` wide, with the quadrilateral between each
// two neighbouring lines (which fills the notches the strips leave where the border runs slanted
// to the lines). Its ends stop at the line ends. A cell whose fill angle is decided apart from its
// island's is filled again in its core grown to the region's border and to the cuts (see
// geometry/plan/island_content.cpp).
geo::Rings cell_core(const FillPath& cell, double angle_deg, double pitch_mm);

}  // namespace tranche::toolpath
