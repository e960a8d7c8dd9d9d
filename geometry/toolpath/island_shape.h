// Shape measures of an island for the island.* fields a rule reads (longest_edge_angle,
// min_width, convex): plain geometry on one island's rings (outer counter-clockwise, holes
// clockwise), in mm and degrees.
#pragma once

#include "geometry/core/geom.h"
#include "geometry/core/layer.h"

namespace tranche::toolpath {

// Direction (degrees in [0, 180), counter-clockwise from +x) of the longest straight stretch of
// the outline (rings[0]): consecutive edges that turn by less than 1° count as one stretch, so an
// edge split by a vertex is still one edge. 0 for an empty shape.
double longest_edge_angle_deg(const geo::Rings& rings);

// The width (mm) of the island's narrowest part: the smallest w such that a disc of diameter w
// rolled inside the island leaves out a part at least about as long as it is wide (an area of
// w² or more: the opening by the disc), or the whole island. A bar or an arm gives its width, a
// neck between wider parts the neck's, a hole near the outline the wall between them, a square
// or a disc its width. Rounding a corner leaves out too little to count; a spike sharper than
// about 20° counts (its tip is thinner than anything). Found to ±5 µm by doubling then bisecting.
// 0 for an empty shape.
double min_width_mm(const geo::Rings& rings);

// True when the island has no holes and no vertex of its outline lies more than 10 µm inside
// its convex hull (the noise of slicing a convex solid is not a dent).
bool is_convex(const geo::Rings& rings);

// The island of `below` that overlaps `rings` most (by area): its index, or -1 when none does.
int island_under(const geo::Rings& rings, const geo::Layer& below);

}  // namespace tranche::toolpath
