// Thin wrappers over Clipper for the polygon operations toolpaths need, on flat ring lists
// (outer rings counter-clockwise, holes clockwise, non-zero fill). Distances in mm.
#pragma once

#include "geometry/core/geom.h"

namespace tranche::toolpath {

// Grows (mm > 0) or shrinks (mm < 0) closed regions with round joins: the exact Minkowski
// sum/difference with a disc, up to the arc tolerance (5 µm). The rings are a region as a union
// leaves it (they may touch at vertices); a spike of no width is no part of it. Not the exact
// offset (as with Clipper's offset): a ring crossing itself, a loop turning against its ring's way,
// a slit of no width between edges that do not follow each other (a keyhole's: shrinking opens
// it). Unite such rings first.
geo::Rings offset(const geo::Rings& region, double mm);
// The same, and whether it is the offset curve as built, trimmed where it would cross itself,
// with no union to clean it (for tests and measurements).
geo::Rings offset(const geo::Rings& region, double mm, bool& as_built);
// The same with arcs to 25 µm: for support, whose beads need no finer (and whose outlines carry
// every vertex of the part's, grown by a gap).
geo::Rings offset_coarse(const geo::Rings& region, double mm);
// Shrinks by `mm`, then grows back by `open_mm`: removes parts narrower than 2·open_mm.
geo::Rings offset_open(const geo::Rings& region, double mm, double open_mm);
// The area within `mm` of closed lines (each ring taken as a loop of centreline), as rings whose
// non-zero winding is that area (each loop's band on its own, not united with the others: a
// boolean's non-zero clip or union_of unites them).
geo::Rings buffer_loops(const geo::Rings& loops, double mm);

geo::Rings intersection(const geo::Rings& a, const geo::Rings& b);
geo::Rings difference(const geo::Rings& a, const geo::Rings& b);
geo::Rings union_of(const geo::Rings& a, const geo::Rings& b = {});
// Whether `rings` are already what union_of would make of them, up to where each ring starts and
// vertices in line with their neighbours: at most 16 rings, no repeated vertex, no two edges
// meeting but consecutive ones at their common end, outers counter-clockwise inside no other
// ring or nested as a region's are, holes clockwise (exact tests, far cheaper than the union).
bool is_clean_region(const geo::Rings& rings);
// The closed rings of `loops`, taken as lines (each back to its first point), inside `region`
// (inside = true) or outside it: open pieces.
geo::Rings clip_loops(const geo::Rings& loops, const geo::Rings& region, bool inside);

// The convex hull of `pts` as one counter-clockwise ring (Andrew's monotone chain); empty for
// fewer than 3 points or collinear ones.
geo::Rings convex_hull(geo::Ring pts);

// `pts` (a polyline; `closed` when it ends at its first point) moved sideways by `mm`, positive
// to the left of travel: each vertex along the bisector of its two edges, mitred, the miter
// capped at sharp turns (a replacer's `offset` on a path).
geo::Ring offset_polyline(const geo::Ring& pts, bool closed, double mm);

// Area in mm² of a ring list under non-zero fill (outer positive, holes negative).
double area_mm2(const geo::Rings& rings);
// Rings whose bounding box meets `box` (others cannot change a boolean result inside it).
geo::Rings near(const geo::Rings& rings, const geo::BBox2& box);
geo::BBox2 bbox(const geo::Rings& rings);
// Drops vertices closer than `tol` units to the chord of their neighbours (Douglas-Peucker per
// ring); rings that collapse below 3 vertices are removed.
geo::Rings simplify(const geo::Rings& rings, geo::coord_t tol);
geo::Ring simplify(const geo::Ring& ring, geo::coord_t tol);

}  // namespace tranche::toolpath
