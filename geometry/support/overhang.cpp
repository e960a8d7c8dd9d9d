#include "geometry/support/overhang.h"

#include <cmath>
#include <numbers>

#include "geometry/toolpath/clip.h"

namespace tranche::support {

namespace {
constexpr double kMinBridgeMm = 2.0;  // mm: a bridge is at least this wide somewhere
}  // namespace

using geo::Rings;

std::vector<Rings> components(const Rings& region) {
  std::vector<Rings> out;
  if (region.empty()) return out;
  ClipperLib::Clipper c;
  c.AddPaths(region, ClipperLib::ptSubject, true);
  ClipperLib::PolyTree tree;
  c.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  for (const geo::Polygon& p : geo::to_polygons(tree)) {
    Rings r{p.outer};
    r.insert(r.end(), p.holes.begin(), p.holes.end());
    out.push_back(std::move(r));
  }
  return out;
}

Rings clip_loops(const Rings& loops, const Rings& region, bool inside) {
  ClipperLib::Clipper c;
  for (const geo::Ring& r : loops) {
    if (r.size() < 2) continue;
    geo::Ring line = r;
    line.push_back(r.front());  // as an open line: the whole loop
    c.AddPath(line, ClipperLib::ptSubject, false);
  }
  c.AddPaths(region, ClipperLib::ptClip, true);
  ClipperLib::PolyTree tree;
  c.Execute(inside ? ClipperLib::ctIntersection : ClipperLib::ctDifference, tree, ClipperLib::pftNonZero,
            ClipperLib::pftNonZero);
  Rings lines;
  ClipperLib::OpenPathsFromPolyTree(tree, lines);
  return lines;
}

double lines_length(const Rings& lines) {
  double len = 0;
  for (const geo::Ring& l : lines)
    for (size_t i = 1; i < l.size(); ++i)
      len += std::hypot(geo::to_mm(l[i].X - l[i - 1].X), geo::to_mm(l[i].Y - l[i - 1].Y));
  return len;
}

double length_inside(const Rings& outline, const Rings& region) {
  if (outline.empty() || region.empty()) return 0;
  return lines_length(clip_loops(outline, region, true));
}

bool is_bridge(const Rings& piece, const Rings& below, double max_bridge_mm, double reach_mm, double hold_mm) {
  if (max_bridge_mm <= 0 || below.empty()) return false;
  // Nowhere kMinBridgeMm across: the sliver a curved underside adds on each layer (the belly of a
  // figure, the inside of a dome closing), held all round but printed by the walls leaning out,
  // not by lines spanning anything. On the Stanford bunny these were 860 mm² printed in the air.
  if (toolpath::offset_coarse(piece, -0.5 * kMinBridgeMm).empty()) return false;
  const Rings zone = toolpath::offset_coarse(piece, hold_mm);
  const Rings near_below = toolpath::near(below, toolpath::bbox(zone));
  const Rings holds = toolpath::intersection(zone, near_below);
  if (toolpath::area_mm2(holds) <= 0) return false;
  // Two-sided: two separate holds, or one hold all round its outer outline (a ceiling on four
  // walls: the outline runs a reach from the walls). Holes do not count: a slope's sliver round a
  // funnel is held along its inner edge only, its outer edge further out than the reach.
  if (components(holds).size() < 2) {
    Rings outers;
    double outline = 0;
    for (const geo::Ring& r : piece)
      if (ClipperLib::Orientation(r)) outers.push_back(r), outline += geo::length_mm(r);
    if (length_inside(outers, toolpath::offset_coarse(near_below, reach_mm + 0.01)) < 0.75 * outline) return false;
  }
  // Short enough: every point within half a span of a hold.
  const Rings far = toolpath::difference(piece, toolpath::offset_coarse(holds, 0.5 * max_bridge_mm + hold_mm));
  return toolpath::area_mm2(far) < 1e-3;
}

Rings overhang(const Rings& island, const Rings& below_reach, const Rings& below, const OverhangSpec& spec) {
  Rings out;
  Rings raw = toolpath::difference(island, toolpath::near(below_reach, toolpath::bbox(island)));
  if (raw.empty()) return out;
  if (spec.min_width_mm > 0) {  // an opening: what is narrower than min_width goes
    const double r = 0.5 * spec.min_width_mm;
    raw = toolpath::offset_coarse(toolpath::offset_coarse(raw, -r), r);
  }
  const double speck = 0.25 * std::numbers::pi * spec.nozzle_mm * spec.nozzle_mm;
  for (Rings& piece : components(raw)) {
    if (toolpath::area_mm2(piece) < speck) continue;
    if (is_bridge(piece, below, spec.max_bridge_mm, spec.reach_mm, spec.reach_mm + 0.5 * spec.nozzle_mm)) continue;
    out.insert(out.end(), piece.begin(), piece.end());
  }
  return out;
}

}  // namespace tranche::support
