// Lightning infill: sparse infill only where the tops above need holding up. Where the lowest
// solid layer over a spot is k layers up (the spot has material on the top_layers + k − 1 layers
// above it but not on top_layers + k: a top skin starts k layers up), that skin's underside is
// carried down as a cone whose sides lean `lean_deg` from vertical: each layer further down it
// shrinks by the layer's height × tan(lean) (PrusaSlicer's and Cura's lightning prune their trees
// by the same overhang angle, 40° by default). A layer's region is the union of the cones of
// every skin above it, within its own material; the slicer zig-zags it at the infill density
// (geometry/plan/island_content.cpp). Computed top down for all layers at once:
//   R(i) = ((R(i + 1) shrunk by h(i)·tan(lean)) ∪ (A(i, T) − A(i, T + 1))) ∩ material(i),
// A(i, n) being the material of all of layers i + 1 … i + n (empty when one is past the top).
#pragma once

#include <map>
#include <mutex>
#include <span>
#include <vector>

#include "geometry/core/layer.h"

namespace tranche::toolpath {

// Every layer's lightning region, bottom to top, for islands with `top_layers` solid layers.
std::vector<geo::Rings> lightning_regions(std::span<const geo::Layer> layers, int top_layers, double lean_deg);

// lightning_regions() of one print's layers, computed at the first request for a top_layers
// value and kept: the layer tasks, run in parallel, share it. Thread-safe.
class LightningCache {
 public:
  // The region of layer `index` of `layers` (always the same layers for one cache).
  const geo::Rings& region(std::span<const geo::Layer> layers, int index, int top_layers) const;

  static constexpr double kLeanDeg = 40;  // Cura's lightning_infill_support_angle

 private:
  mutable std::mutex mu_;
  mutable std::map<int, std::vector<geo::Rings>> by_top_;
};

}  // namespace tranche::toolpath
