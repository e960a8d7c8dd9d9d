// The polygon stage over a whole print: every layer resolved, then decomposed, in parallel
// (layers are independent). Warnings come out in layer order; the first error by layer order wins.
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

// decompose_layer for every layer: each island at its fill_angle_deg, or the default 45°/135°
// alternation when NaN. `total` sums the statistics over all islands. With a `report`, an island
// that cannot be decomposed is a "decompose-failed" warning (the island keeps no cells) instead
// of an error.
Status decompose_layers(std::vector<Layer>& layers, DecomposeStats* total = nullptr, Report* report = nullptr,
                        const LayerProgress& progress = {});

}  // namespace tranche::geo
