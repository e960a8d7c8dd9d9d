// Monotone ("pseudo-convex") cells (seed section 4): an island is cut into cells that each fill
// with one continuous zig-zag at the fill angle, cutting only where the boundary turns back
// against the sweep. See docs/polygons.md for the method.
#pragma once

#include "geometry/core/layer.h"
#include "base/report.h"
#include "base/result.h"

namespace tranche::geo {

struct DecomposeStats {
  int sweep_cells = 0;  // cells made by the sweep, before merging
  int cells = 0;        // after merging neighbours whose union is still monotone
  int cuts = 0;         // artificial cuts left
};

// Cuts `shape` (outer CCW, holes CW, rings meeting only at shared vertices: what resolve.h makes)
// into cells monotone for the fill angle `angle_deg` (degrees, counter-clockwise from +x). Each
// cell: ring CCW, edges[i] the kind of ring[i] -> ring[i+1] (Real on the island's outline and
// holes, Artificial on cuts), fill_angle_deg = angle_deg, solid = false. The cells tile the shape
// exactly and use only its vertices. Errors: coordinates beyond ±2147 mm, inconsistent input.
Result<std::vector<Cell>> decompose(const Polygon& shape, double angle_deg, DecomposeStats* stats = nullptr);

// Cells of a region given as rings by the nonzero rule (e.g. an island's inset fill region, which
// may pinch or split): its strict islands (resolve.h strict_islands), each decomposed for
// angle_deg. Stats add up over the islands.
Result<std::vector<Cell>> decompose_region(const Rings& region, double angle_deg,
                                           DecomposeStats* stats = nullptr);

// The cells of island `island` of `layer` (errors name the layer and island).
Result<std::vector<Cell>> decompose_island(const Layer& layer, size_t island, double angle_deg,
                                           DecomposeStats* stats = nullptr);

}  // namespace tranche::geo
