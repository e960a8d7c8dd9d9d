// Layer heights: the z range of every layer, decided before any slicing (the "layer planning"
// stage: a layer's height may depend only on its index and its bottom z).
#pragma once

#include <functional>
#include <vector>

#include "geometry/core/layer.h"
#include "base/result.h"

namespace tranche::geo {

struct LayerHeightParams {
  double first_layer_height = 0.2;  // mm, layer 0
  double layer_height = 0.2;        // mm, every other layer
  // When set, decides every layer's height (mm) from its index and bottom z (mm), layer 0
  // included, instead of the two constants above: the hook for a `layer_height` rule.
  std::function<double(int index, double z_bottom)> height;
};

// Layers from z = 0 to `model_height` (mm; the model sits with its min z at 0), bottom to top,
// each with index, z_bottom and z_top (mm) and nothing sliced yet. Boundaries are computed on
// whole nanometres, so 0.2 mm layers put z_top at exactly 0.2, 0.4, ... 10.0.
// The last layer ends exactly at the model's top: when the remaining thickness r is less than
// the planned height h, the last layer is shortened to r; when r is also less than h / 4 it is
// merged into the layer below instead (which grows by less than h / 4), so no layer is a sliver.
// Errors: a height that is not positive/finite (≥ 1 µm), a non-positive model height, or more
// than 1 000 000 layers.
Result<std::vector<Layer>> plan_layer_heights(double model_height, const LayerHeightParams& params);

}  // namespace tranche::geo
