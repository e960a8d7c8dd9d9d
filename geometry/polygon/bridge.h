// One path per island (seed section 4): every hole is joined to the outline, or to a hole already
// joined, by a there-and-back cut, so that the island's boundary becomes a single closed path
// (weakly simple: the cuts are walked once each way). The monotone decomposition does not need
// this (its cuts reach every hole); it is for consumers that want one path, e.g. exports.
#pragma once

#include <vector>

#include "geometry/core/layer.h"
#include "base/result.h"

namespace tranche::geo {

struct BridgedPath {
  Ring ring;                    // counter-clockwise; a cut's two endpoints each appear twice
  std::vector<EdgeKind> edges;  // edges[i]: ring[i] -> ring[i+1]; Artificial on the cuts
  int cuts = 0;                 // number of there-and-back cuts (holes not touching a joined ring)
};

// Joins the holes of `shape` (outer CCW, holes CW, rings meeting only at shared vertices: what
// resolve.h makes). Cuts run between vertices, inside the material, crossing no edge and no other
// cut; short ones are preferred (a minimum spanning tree over the nearest admissible pairs).
Result<BridgedPath> bridge_holes(const Polygon& shape);

}  // namespace tranche::geo
