// What the layer exports (--export-svg, --export-layers) draw of one layer: its material (the
// islands) and, when the layer was planned, what the G-code prints there — every path of every
// island in print order, with the cells the toolpath stage cut (one zig-zag each) — and, on
// request, the seed's exact monotone decomposition of each island as an analysis view.
// The writers format layers in parallel (append_layer is pure) and write them in order.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/core/layer.h"
#include "geometry/plan/plan.h"

namespace tranche::exports {

struct ExportLayer {
  const geo::Layer* layer = nullptr;  // the islands as resolved: the material
  // printed[i]: what the G-code prints on island i of `layer` (empty, or null for an island: not
  // planned); `skirt`: the layer's skirt loops.
  std::vector<const plan::IslandPlan*> printed;
  const std::vector<plan::PathPlan>* skirt = nullptr;
  std::vector<const plan::IslandPlan*> support;  // the layer's support islands (island.support)
  const std::vector<std::vector<geo::Cell>>* exact = nullptr;  // per island: exact cells (analysis)

  const plan::IslandPlan* printed_on(size_t island) const {
    return island < printed.size() ? printed[island] : nullptr;
  }
};

// The export of a planned layer: `resolved_index` (PrintSetup's, for this layer) maps the plan's
// islands to `layer`'s.
ExportLayer planned_layer(const geo::Layer& layer, const plan::LayerPlan& plan,
                          const std::vector<uint32_t>& resolved_index);

// The name of a path kind as the exports write it ("outer_perimeter", as in the rule language).
std::string_view kind_name(schema::PathKind kind);

}  // namespace tranche::exports
