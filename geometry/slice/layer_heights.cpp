#include "geometry/slice/layer_heights.h"

#include <cmath>
#include <cstdint>

#include <fmt/format.h>

namespace tranche::geo {
namespace {

constexpr size_t kMaxLayers = 1'000'000;

// Division, not multiplication by 1e-6: 200000 units give the same double as the literal 0.2.
double units_to_mm(int64_t u) { return static_cast<double>(u) / kUnitsPerMm; }

}  // namespace

Result<std::vector<Layer>> plan_layer_heights(double model_height, const LayerHeightParams& params) {
  if (!std::isfinite(model_height) || model_height <= 0)
    return Error{"", fmt::format("the model has no height ({} mm): nothing to slice", model_height)};
  const int64_t top = to_units(model_height);
  if (top <= 0) return Error{"", fmt::format("the model is too thin to slice ({} mm)", model_height)};

  std::vector<Layer> layers;
  int64_t z = 0;
  while (z < top) {
    const int index = static_cast<int>(layers.size());
    const double h_mm = params.height ? params.height(index, units_to_mm(z))
                        : index == 0  ? params.first_layer_height
                                      : params.layer_height;
    if (!std::isfinite(h_mm) || h_mm < 0.001)
      return Error{fmt::format("layer {}", index),
                   fmt::format("layer height must be at least 0.001 mm, got {} mm", h_mm)};
    if (layers.size() >= kMaxLayers)
      return Error{fmt::format("layer {}", index),
                   fmt::format("more than {} layers: the layer height ({} mm) is too small for a model "
                               "{} mm tall",
                               kMaxLayers, h_mm, model_height)};
    const int64_t h = to_units(h_mm);
    const int64_t rest = top - z;
    if (rest < h && 4 * rest < h && !layers.empty()) {
      layers.back().z_top = units_to_mm(top);  // a sliver: merged into the layer below
      break;
    }
    Layer layer;
    layer.index = index;
    layer.z_bottom = units_to_mm(z);
    z += std::min(h, rest);
    layer.z_top = units_to_mm(z);
    layers.push_back(std::move(layer));
  }
  return layers;
}

}  // namespace tranche::geo
