// The shape a fill region is zig-zagged in, with every edge labelled: Real where it lies on the
// island's fill border (along the innermost perimeter), Artificial where it is the border between
// a solid and a sparse region. The region's cells are the zig-zags zigzag() makes of it: its
// monotone pieces at the resolution of the fill lines (docs/gcode.md, "Cells").
#pragma once

#include "geometry/toolpath/edge_grid.h"
#include "geometry/toolpath/zigzag.h"

namespace tranche::toolpath {

// `region`: rings of one fill region (non-zero fill); `fill_border`: edges of the whole fill
// region of the island. The rings come out of a union: outer counter-clockwise, holes clockwise,
// none overlapping.
FillShape region_shape(const geo::Rings& region, const EdgeGrid& fill_border);

}  // namespace tranche::toolpath
