#include "geometry/support/raft.h"

#include <algorithm>

#include "geometry/toolpath/clip.h"

namespace tranche::support {

void lift_onto_raft(std::vector<geo::Layer>& layers, const RaftSpec& spec) {
  if (spec.layers <= 0) return;
  std::vector<geo::Layer> raft(static_cast<size_t>(spec.layers));
  double z = 0;
  for (int k = 0; k < spec.layers; ++k) {
    geo::Layer& l = raft[static_cast<size_t>(k)];
    l.index = k;
    l.z_bottom = z;
    z += k == 0 ? spec.first_height : spec.height;
    l.z_top = z;
  }
  const double lift = z + spec.gap;
  for (geo::Layer& l : layers) {
    l.index += spec.layers;
    l.z_bottom += lift;
    l.z_top += lift;
  }
  layers.insert(layers.begin(), std::make_move_iterator(raft.begin()), std::make_move_iterator(raft.end()));
}

geo::Rings raft_region(const geo::Rings& footprint, double expansion_mm, const geo::Rings& bed) {
  geo::Rings grown = toolpath::offset_coarse(toolpath::union_of(footprint), expansion_mm);
  // One sheet: the holes of a ring of parts (or of a part's first layer) are rafted over.
  std::erase_if(grown, [](const geo::Ring& r) { return !ClipperLib::Orientation(r); });
  grown = toolpath::union_of(grown);
  return bed.empty() ? grown : toolpath::intersection(grown, bed);
}

}  // namespace tranche::support
