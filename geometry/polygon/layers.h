// The polygon stage over a whole print: every layer resolved (and, for analysis, decomposed), in
// parallel (layers are independent). Warnings come out in layer order; the first error by layer order wins.
#pragma once

#include <functional>
#include <vector>

#include "geometry/core/layer.h"
#include "geometry/polygon/decompose.h"
#include "geometry/polygon/resolve.h"
#include "base/report.h"
#include "base/result.h"

namespace tranche::geo {

// Called from worker threads with the number of layers finished so far.
using LayerProgress = std::function<void(size_t layers_done)>;

// resolve_layer for every layer (options.layer_index is taken from each layer).
Status resolve_layers(std::vector<Layer>& layers, const ResolveOptions& options, Report& report,
                      const LayerProgress& progress = {});

// The fill angle (deg) island `island` of `layer` is cut at.
using IslandAngle = std::function<double(const Layer& layer, size_t island)>;
// One layer's cells: cells[i] are island i's (empty when it could not be cut, with a report).
using LayerCells = std::vector<std::vector<Cell>>;

// decompose_island for every island of every layer at `angle`: the seed's exact monotone cells
// (an analysis view: the G-code's cells are cut by the toolpath stage at the resolution of its
// lines). `total` sums the statistics over all islands. With a `report`, an island that cannot
// be decomposed is a "decompose-failed" warning (the island gets no cells) instead of an error.
Result<std::vector<LayerCells>> decompose_layers(const std::vector<Layer>& layers, const IslandAngle& angle,
                                                 DecomposeStats* total = nullptr, Report* report = nullptr,
                                                 const LayerProgress& progress = {});

}  // namespace tranche::geo
