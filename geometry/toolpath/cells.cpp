#include "geometry/toolpath/cells.h"

#include "geometry/toolpath/clip.h"

namespace tranche::toolpath {

namespace {
constexpr geo::coord_t kOnBorderTol = 20;  // units (20 nm): Clipper rounding of shared edges

std::vector<geo::EdgeKind> label(const geo::Ring& ring, const EdgeGrid& border) {
  std::vector<geo::EdgeKind> kinds(ring.size());
  for (size_t i = 0; i < ring.size(); ++i)
    kinds[i] = border.along(ring[i], ring[(i + 1) % ring.size()], kOnBorderTol) ? geo::EdgeKind::Real
                                                                                : geo::EdgeKind::Artificial;
  return kinds;
}
}  // namespace

std::vector<CellShape> make_cells(const geo::Rings& region, double /*angle_deg*/, const EdgeGrid& fill_border,
                                  Report& /*report*/, const std::string& /*where*/) {
  std::vector<CellShape> out;
  if (region.empty()) return out;
  CellShape c;
  for (const auto& r : region) {
    c.shape.rings.push_back(r);
    c.shape.kinds.push_back(label(r, fill_border));
  }
  c.area_mm2 = area_mm2(region);
  c.monotone = false;
  out.push_back(std::move(c));
  return out;
}

}  // namespace tranche::toolpath
