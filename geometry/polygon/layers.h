// The polygon stage over a whole print: every layer resolved, then decomposed, in parallel
// (layers are independent). Warnings come out in layer order; the first error by layer order wins.
#pragma once

#include <vector>

#include "geometry/core/layer.h"
#include "geometry/polygon/decompose.h"
#include "geometry/polygon/resolve.h"
#include "runtime/base/report.h"
#include "runtime/base/result.h"

namespace tranche::geo {

// resolve_layer for every layer (options.layer_index is taken from each layer).
Status resolve_layers(std::vector<Layer>& layers, const ResolveOptions& options, Report& report);

// decompose_layer for every layer: each island at its fill_angle_deg, or the default 45°/135°
// alternation when NaN. `total` sums the statistics over all islands.
Status decompose_layers(std::vector<Layer>& layers, DecomposeStats* total = nullptr);

}  // namespace tranche::geo
