// Print order within a layer, chosen to keep travel short: the skirt first, then the islands
// nearest first (odd layers backwards, so a layer starts where the one below ended), and within
// an island the fill and the perimeters (infill first by default: the last zig-zag runs into the
// innermost loop) with their seams. The primitives (seams, chaining) are geometry/toolpath/order.h.
#pragma once

#include <vector>

#include "geometry/plan/island_content.h"
#include "geometry/plan/plan.h"

namespace tranche::plan {

// Where a layer starts: the middle of the rear edge of its islands' extent (model units).
geo::Point layer_start(const std::vector<IslandPlan>& islands);

// Opens each skirt loop at its rear point and moves `pos` to its start.
void order_skirt(std::vector<PathPlan>& skirt, geo::Point& pos);

// The order islands are printed in (indices into `islands`): nearest first by bounding box from
// `from`, each next one from the centre of the previous; reversed on odd layers. (Layers are
// planned in parallel: a layer cannot know where the one below ended, but both find the same
// order when their islands match.)
std::vector<size_t> island_order(const std::vector<IslandPlan>& islands, const geo::Point& from, int layer_index);

// Orders ip.paths for printing, from `pos` (moved to where the island ends): loops by depth
// (innermost first unless outer_first) with their seams, zig-zags in the order with the fewest
// and shortest travels, joined where they end next to each other inside one of `regions`;
// infill_first puts the fill first and runs its last zig-zag into the innermost loop. Sets each
// path's index. `frame` is what the seam needs beyond the island: the layer (random seams are
// seeded by layer, island and loop) and the shift from model to bed coordinates (seam = point
// takes seam_x, seam_y on the bed).
struct SeamFrame {
  int layer = 0;
  geo::Point shift;  // model units + shift = bed units
};
void order_island(IslandPlan& ip, const std::vector<FillGrid>& regions, double height_mm, geo::Point& pos,
                  const SeamFrame& frame = {});

}  // namespace tranche::plan
