// Internal to geometry/polygon: the boolean resolution behind resolve.h. Rings that describe
// material by an overlap mode are united (Clipper; coincident edges cancelled first, snap rounding
// when rounding leaves crossings) into rings that meet only at shared vertices, and their planar
// graph, from which resolve.cpp builds the islands. Also paint() of resolve.h. Not for use
// outside geometry/polygon.
#pragma once

#include "base/result.h"
#include "geometry/core/geom.h"
#include "geometry/polygon/planar_graph.h"
#include "geometry/polygon/resolve.h"

namespace tranche::geo::unite {

// Whether every point lies within the polygon stage's range (±2147 mm), and the error beyond.
bool in_range(const Rings& rings);
Error range_error();

// The ring without repeated consecutive points (nor a last point equal to the first).
Ring without_repeats(const Ring& ring);

// Whether the path turns straight back at v (a zero-width spike tip).
bool turns_back(const Point& p, const Point& v, const Point& q);

// The union of `rings` under `mode` (loops shorter than 3 points ignored) as rings without
// spikes that meet only at shared vertices, in `graph`. Errors: the union fails or leaves
// crossing edges even after snap rounding.
Status union_graph(const Rings& rings, OverlapMode mode, PlanarGraph& graph);

}  // namespace tranche::geo::unite
