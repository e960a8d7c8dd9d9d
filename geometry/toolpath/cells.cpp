#include "geometry/toolpath/cells.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/zigzag.h"

namespace tranche::toolpath {

FillShape region_shape(const geo::Rings& region, const std::vector<const EdgeGrid*>& borders,
                       double on_border_mm) {
  const auto tol = static_cast<geo::coord_t>(std::llround(on_border_mm * geo::kUnitsPerMm));
  FillShape s;
  if (region.empty()) return s;
  // Regions come out of booleans and offsets, nearly always disjoint rings already: the union
  // that would make them so runs only when the exact test says they are not.
  ClipperLib::Paths rings;
  if (is_clean_region(region)) {
    rings = region;
  } else {
    ClipperLib::Clipper clip;
    clip.AddPaths(region, ClipperLib::ptSubject, true);
    clip.Execute(ClipperLib::ctUnion, rings, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  }
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

geo::Rings cell_core(const FillPath& cell, double angle_deg, double pitch_mm) {
  const double a = angle_deg * std::numbers::pi / 180;
  const double ux = std::cos(a), uy = std::sin(a);  // along the lines; (-uy, ux) across them
  const double half = 0.5 * pitch_mm * geo::kUnitsPerMm + 1000;  // a micrometre of overlap
  auto along = [&](const geo::Point& p) { return static_cast<double>(p.X) * ux + static_cast<double>(p.Y) * uy; };
  auto across = [&](const geo::Point& p) { return -static_cast<double>(p.X) * uy + static_cast<double>(p.Y) * ux; };
  auto side = [&](const geo::Point& p, double d) {
    return geo::Point(std::llround(static_cast<double>(p.X) - d * uy), std::llround(static_cast<double>(p.Y) + d * ux));
  };
  geo::Rings parts;
  const geo::Point* prev_a = nullptr;  // the previous line of the path
  const geo::Point* prev_b = nullptr;
  for (size_t i = 0; i + 1 < cell.pts.size(); ++i) {
    if (i < cell.border.size() && cell.border[i] != schema::Border::None) continue;
    const geo::Point& p = cell.pts[i];
    const geo::Point& q = cell.pts[i + 1];
    if (p == q) continue;
    parts.push_back({side(p, -half), side(q, -half), side(q, half), side(p, half)});  // the line's strip
    // Between this line and the one before it, when they are neighbours on the grid (one pitch
    // apart, side by side): the quadrilateral of their ends, which the strips leave notched
    // where the border runs slanted to the lines.
    if (prev_a) {
      const double gap = std::abs(across(p) - across(*prev_a)) * geo::kMmPerUnit;
      const double lo = std::max(std::min(along(p), along(q)), std::min(along(*prev_a), along(*prev_b)));
      const double hi = std::min(std::max(along(p), along(q)), std::max(along(*prev_a), along(*prev_b)));
      const bool same_way = (along(*prev_b) - along(*prev_a)) * (along(q) - along(p)) > 0;
      if (std::abs(gap - pitch_mm) < 0.05 * pitch_mm && lo < hi)
        parts.push_back(same_way ? geo::Ring{*prev_a, *prev_b, q, p} : geo::Ring{*prev_a, *prev_b, p, q});
    }
    prev_a = &p;
    prev_b = &q;
  }
  // The lines of a zig-zag run both ways: every part counter-clockwise, so that overlaps add up.
  for (auto& r : parts)
    if (!ClipperLib::Orientation(r)) ClipperLib::ReversePath(r);
  return union_of(parts);
}

}  // namespace tranche::toolpath
