#include "geometry/toolpath/relations.h"

#include "geometry/toolpath/clip.h"

namespace tranche::toolpath {

using schema::PathKind;

geo::Rings material(const geo::Layer& layer) {
  geo::Rings out;
  for (const auto& isl : layer.islands) {
    out.push_back(isl.shape.outer);
    for (const auto& h : isl.shape.holes) out.push_back(h);
  }
  return out;
}

Neighbours::Neighbours(std::span<const geo::Layer> layers, int index) : layers_(layers), index_(index) {}

const geo::Rings& Neighbours::layer(int k) {
  int i = index_ + k;
  auto it = material_.find(i);
  if (it != material_.end()) return it->second;
  geo::Rings m;
  if (i >= 0 && static_cast<size_t>(i) < layers_.size()) m = material(layers_[static_cast<size_t>(i)]);
  return material_.emplace(i, std::move(m)).first->second;
}

const geo::Rings& Neighbours::all_above(int n) {
  while (static_cast<int>(above_.size()) < n) {
    int k = static_cast<int>(above_.size()) + 1;
    above_.push_back(k == 1 ? layer(1) : intersection(above_.back(), layer(k)));
  }
  return above_[static_cast<size_t>(n - 1)];
}

const geo::Rings& Neighbours::all_below(int n) {
  while (static_cast<int>(below_.size()) < n) {
    int k = static_cast<int>(below_.size()) + 1;
    below_.push_back(k == 1 ? layer(-1) : intersection(below_.back(), layer(-k)));
  }
  return below_[static_cast<size_t>(n - 1)];
}

const EdgeGrid& Neighbours::below_grid() {
  if (!below_grid_built_) {
    below_grid_ = EdgeGrid(layer(-1));
    below_grid_built_ = true;
  }
  return below_grid_;
}

double fraction_on(const geo::Rings& island, const geo::Rings& other) {
  double a = area_mm2(island);
  if (a <= 0) return 0;
  double on = area_mm2(intersection(island, near(other, bbox(island))));
  return std::clamp(on / a, 0.0, 1.0);
}

std::vector<FillRegion> split_fill(const geo::Rings& fill, Neighbours& nb, const SolidSpec& spec) {
  std::vector<FillRegion> out;
  if (fill.empty()) return out;
  const double w = spec.width;
  const bool all_solid = spec.density >= 1.0 - 1e-9;
  auto clean = [&](geo::Rings r) { return offset_open(r, 0, 0.25 * w); };
  if (nb.index() == 0) {
    out.push_back({PathKind::BottomSolid, fill});
    return out;
  }
  geo::BBox2 box = bbox(fill);
  // Solid wherever the next top_layers or the bottom_layers below do not all cover this spot.
  geo::Rings solid;
  {
    geo::Rings keep;  // covered on both sides: may stay sparse
    bool up = spec.top_layers > 0, down = spec.bottom_layers > 0;
    if (up && down) {
      keep =
          intersection(near(nb.all_above(spec.top_layers), box), near(nb.all_below(spec.bottom_layers), box));
    } else if (up) {
      keep = near(nb.all_above(spec.top_layers), box);
    } else if (down) {
      keep = near(nb.all_below(spec.bottom_layers), box);
    } else {
      keep = fill;
    }
    solid = clean(difference(fill, keep));
  }
  geo::Rings bridge, top;
  if (spec.bottom_layers > 0) bridge = clean(difference(fill, near(nb.layer(-1), box)));
  if (spec.top_layers > 0) {
    top = difference(fill, near(nb.layer(1), box));
    if (!bridge.empty()) top = difference(top, bridge);
    top = clean(top);
  }
  if (all_solid) {
    geo::Rings rest = difference(fill, union_of(bridge, top));
    if (!bridge.empty()) out.push_back({PathKind::Bridge, bridge});
    if (!top.empty()) out.push_back({PathKind::TopSolid, top});
    rest = clean(rest);
    if (!rest.empty()) out.push_back({PathKind::SolidInfill, rest});
    return out;
  }
  if (solid.empty()) {
    out.push_back({PathKind::Infill, fill});
    return out;
  }
  // Anchor the skins one bead into the sparse region.
  solid = intersection(offset(solid, w), fill);
  geo::Rings internal = solid;
  if (!bridge.empty() || !top.empty()) internal = clean(difference(solid, union_of(bridge, top)));
  geo::Rings sparse = clean(difference(fill, solid));
  if (!bridge.empty()) out.push_back({PathKind::Bridge, bridge});
  if (!internal.empty()) out.push_back({PathKind::SolidInfill, internal});
  if (!top.empty()) out.push_back({PathKind::TopSolid, top});
  if (!sparse.empty()) out.push_back({PathKind::Infill, sparse});
  return out;
}

}  // namespace tranche::toolpath
