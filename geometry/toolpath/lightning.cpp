#include "geometry/toolpath/lightning.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/relations.h"

namespace tranche::toolpath {

std::vector<geo::Rings> lightning_regions(std::span<const geo::Layer> layers, int top_layers, double lean_deg) {
  const int n = static_cast<int>(layers.size()), T = std::max(top_layers, 0);
  std::vector<geo::Rings> mat(layers.size()), out(layers.size());
  for (int i = 0; i < n; ++i) mat[static_cast<size_t>(i)] = union_of(material(layers[static_cast<size_t>(i)]));
  const double tan_lean = std::tan(std::clamp(lean_deg, 0.0, 89.0) * std::numbers::pi / 180);
  // A(i, m): the material of all of layers i + 1 … i + m; A(i, 0) is layer i's own.
  auto above = [&](int i, int m) -> geo::Rings {
    if (i + m >= n) return {};
    geo::Rings a = mat[static_cast<size_t>(i + (m > 0 ? 1 : 0))];
    for (int j = i + 2; j <= i + m && !a.empty(); ++j) a = intersection(a, mat[static_cast<size_t>(j)]);
    return a;
  };
  for (int i = n - 1; i >= 0; --i) {
    const auto k = static_cast<size_t>(i);
    if (mat[k].empty()) continue;
    geo::Rings r;
    // Simplified to 10 µm first: each shrink rounds the region's concave corners with arcs, and
    // without it the vertices pile up layer after layer (a plate with holes took minutes).
    if (i + 1 < n && !out[k + 1].empty()) r = offset(simplify(out[k + 1], 10000), -layers[k].height() * tan_lean);
    const geo::Rings a = above(i, T);
    if (!a.empty()) {
      const geo::Rings skin = i + T + 1 < n ? difference(a, intersection(a, mat[k + static_cast<size_t>(T) + 1])) : a;
      if (!skin.empty()) r = union_of(r, skin);
    }
    if (!r.empty()) out[k] = intersection(r, mat[k]);
  }
  return out;
}

const geo::Rings& LightningCache::region(std::span<const geo::Layer> layers, int index, int top_layers) const {
  static const geo::Rings kNone;
  std::lock_guard<std::mutex> lock(mu_);
  auto it = by_top_.find(top_layers);
  if (it == by_top_.end()) it = by_top_.emplace(top_layers, lightning_regions(layers, top_layers, kLeanDeg)).first;
  const auto& v = it->second;
  return index >= 0 && static_cast<size_t>(index) < v.size() ? v[static_cast<size_t>(index)] : kNone;
}

}  // namespace tranche::toolpath
