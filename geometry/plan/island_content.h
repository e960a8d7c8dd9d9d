// What an island prints, before any ordering: perimeters along its real borders, then its fill
// region split into solid and sparse regions (relations with the layers around it), each
// zig-zagged into cells (docs/gcode.md, "Cells"); and the skirt of layer 0. Widths are decided per
// path kind through the Nest; everything else is geometry from geometry/toolpath.
#pragma once

#include <vector>

#include "geometry/plan/nest.h"
#include "geometry/plan/plan.h"
#include "geometry/toolpath/edge_grid.h"
#include "geometry/toolpath/relations.h"

namespace tranche::plan {

// One fill region's edges, by kind: the order stage joins two zig-zags of a region by a short
// extrusion only when it stays inside the region.
struct FillGrid {
  schema::PathKind kind;
  toolpath::EdgeGrid grid;
};

// The island fields that cost more than a pass over the outline, each computed only when a rule,
// hook or replacer reads it.
struct IslandNeeds {
  bool relations = false;  // island.supported, island.covered: a boolean each
  bool edge_angle = false, min_width = false, convex = false;
  bool below = false;      // island.below_area, island.below_supported
  static IslandNeeds of(const Nest& nest);
};

// Sets the island.* fields of `ip` from its shape (mm, mm², bed coordinates with `shift`); the
// costly ones only when `needs` says so (else 0).
void measure_island(IslandPlan& ip, const geo::Point& shift, toolpath::Neighbours& nb, const IslandNeeds& needs);

// Builds ip.paths (unordered) and ip.cells from ip.shape and ip.props, at layer height `height_mm`;
// `regions` gets each fill region's edges. Replaces what ip held before (a replacer's `default`
// after an `offset` builds the island again).
Status build_island(IslandPlan& ip, Nest& nest, toolpath::Neighbours& nb, double height_mm,
                    std::vector<FillGrid>& regions);

// Builds a support island's paths: zig-zags over ip.shape (kind Support or SupportInterface) on a
// grid fixed to the bed, so that lines stand on the lines below; the interface's lines cross the
// base's. With `wall` (a tree's branch), a closed loop round the island first, the lines inside it.
Status build_support(IslandPlan& ip, Nest& nest, double height_mm, schema::PathKind kind, bool wall,
                     std::vector<FillGrid>& regions);

// The skirt of `plan` (layer 0): skirt_loops loops around setup.skirt_around, outermost first;
// then the brim (setup.brim).
Status build_skirt(LayerPlan& plan, Nest& nest, double height_mm);

}  // namespace tranche::plan
