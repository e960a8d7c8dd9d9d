// Loops → islands, the simple way: the nonzero union of a layer's loops, one Island per polygon
// with holes. A stand-in until geometry/polygon/ resolves overlap modes and splits strictly
// connected islands; kept in this one small file so it is easy to swap.
#pragma once

#include <functional>
#include <vector>

#include "geometry/core/layer.h"
#include "base/result.h"

namespace tranche::geo {

// Nonzero union of closed loops (units): polygons with holes, outer CCW, holes CW. A region is
// material when the loops wind around it a nonzero number of times, so overlapping shells merge
// and inside-out shells still count.
Result<Polygons> union_nonzero(const Rings& loops);

// Replaces layer.islands with one Island (shape, area_mm2) per polygon of union_nonzero(loops).
Status make_islands(Layer& layer);

// The same for every layer, in parallel; the first error (by layer order) is returned.
// `progress`, when set, is called from worker threads with the number of layers done so far.
Status make_islands(std::vector<Layer>& layers, const std::function<void(size_t)>& progress = {});

}  // namespace tranche::geo
