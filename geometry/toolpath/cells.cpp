#include "geometry/toolpath/cells.h"

#include "geometry/toolpath/clip.h"

namespace tranche::toolpath {

namespace {
constexpr geo::coord_t kOnBorderTol = 20;  // units (20 nm): Clipper rounding of shared edges
}  // namespace

FillShape region_shape(const geo::Rings& region, const EdgeGrid& fill_border) {
  FillShape s;
  if (region.empty()) return s;
  ClipperLib::Clipper clip;
  clip.AddPaths(region, ClipperLib::ptSubject, true);
  ClipperLib::Paths rings;
  clip.Execute(ClipperLib::ctUnion, rings, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  for (auto& ring : rings) {
    if (ring.size() < 3) continue;
    std::vector<geo::EdgeKind> kinds(ring.size());
    for (size_t i = 0; i < ring.size(); ++i)
      kinds[i] = fill_border.along(ring[i], ring[(i + 1) % ring.size()], kOnBorderTol) ? geo::EdgeKind::Real
                                                                                      : geo::EdgeKind::Artificial;
    s.rings.push_back(std::move(ring));
    s.kinds.push_back(std::move(kinds));
  }
  return s;
}

}  // namespace tranche::toolpath
