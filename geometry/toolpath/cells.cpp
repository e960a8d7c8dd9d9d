#include "geometry/toolpath/cells.h"

#include <algorithm>
#include <cmath>

#include "geometry/toolpath/clip.h"

namespace tranche::toolpath {

FillShape region_shape(const geo::Rings& region, const std::vector<const EdgeGrid*>& borders,
                       double on_border_mm) {
  const auto tol = static_cast<geo::coord_t>(std::llround(on_border_mm * geo::kUnitsPerMm));
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
      kinds[i] =
          std::any_of(borders.begin(), borders.end(),
                      [&](const EdgeGrid* b) { return b->along(ring[i], ring[(i + 1) % ring.size()], tol); })
              ? geo::EdgeKind::Real
              : geo::EdgeKind::Artificial;
    s.rings.push_back(std::move(ring));
    s.kinds.push_back(std::move(kinds));
  }
  return s;
}

}  // namespace tranche::toolpath
