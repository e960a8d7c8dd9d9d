#include "geometry/support/overhang.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/edge_grid.h"

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

std::vector<Rings> pieces(const Rings& region) {
  std::vector<Rings> out;
  std::vector<size_t> outer_of;  // out[j]'s outer: region[outer_of[j]]
  std::vector<double> outer_area;
  std::vector<geo::BBox2> outer_box;
  std::vector<size_t> holes;
  for (size_t i = 0; i < region.size(); ++i) {
    const double a = ClipperLib::Area(region[i]);
    if (a > 0) {
      out.push_back({region[i]});
      outer_of.push_back(i);
      outer_area.push_back(a);
      outer_box.push_back(geo::bbox(region[i]));
    } else if (a < 0) {
      holes.push_back(i);
    }
  }
  for (size_t h : holes) {
    const double hole_area = -ClipperLib::Area(region[h]);
    size_t best = out.size();
    for (const geo::Point& p : region[h]) {  // a vertex strictly inside its outer (one may touch it)
      bool on_edge = false;
      for (size_t j = 0; j < out.size(); ++j) {
        const geo::BBox2& b = outer_box[j];
        if (outer_area[j] <= hole_area || p.X < b.min_x || p.X > b.max_x || p.Y < b.min_y || p.Y > b.max_y) continue;
        const int in = ClipperLib::PointInPolygon(p, region[outer_of[j]]);
        if (in < 0) on_edge = true;
        else if (in > 0 && (best == out.size() || outer_area[j] < outer_area[best])) best = j;
      }
      if (!on_edge) break;  // this vertex decided it
      best = out.size();
    }
    if (best == out.size()) return components(region);
    out[best].push_back(region[h]);
  }
  return out;
}

double lines_length(const Rings& lines) {
  double len = 0;
  for (const geo::Ring& l : lines)
    for (size_t i = 1; i < l.size(); ++i)
      len += std::hypot(geo::to_mm(l[i].X - l[i - 1].X), geo::to_mm(l[i].Y - l[i - 1].Y));
  return len;
}

bool is_bridge(const Rings& piece, const Rings& below, double max_bridge_mm, double hold_mm) {
  if (max_bridge_mm <= 0 || below.empty() || piece.empty()) return false;
  // Nowhere kMinBridgeMm across: the sliver a curved underside adds on each layer (the belly of a
  // figure, the inside of a dome closing), held all round but printed by the walls leaning out,
  // not by lines spanning anything. On the Stanford bunny these were 860 mm² printed in the air.
  if (toolpath::offset_coarse(piece, -0.5 * kMinBridgeMm).empty()) return false;
  // Straight lines across the piece in one direction, as bridge infill lays them: a line spans
  // when both its ends, carried on by hold_mm, land on the layer below and it is at most
  // max_bridge long. The piece is a bridge when, in the best of 18 directions, lines that span
  // make at least half of the lines' length (PrusaSlicer's bridge detector asks the same of a
  // bridge surface: a direction whose lines are anchored at both ends). A cap's rim or a curved
  // underside's crescent, held along one edge only, has no such direction whatever its holds.
  const geo::BBox2 box = toolpath::bbox(piece);
  const double margin = hold_mm + 1;
  geo::BBox2 grown = box;
  grown.min_x -= geo::to_units(margin), grown.min_y -= geo::to_units(margin);
  grown.max_x += geo::to_units(margin), grown.max_y += geo::to_units(margin);
  const Rings near_below = toolpath::near(below, grown);
  if (near_below.empty()) return false;
  const toolpath::EdgeGrid piece_grid(piece), below_grid(near_below);
  const double cx = 0.5 * (double(box.min_x) + double(box.max_x)), cy = 0.5 * (double(box.min_y) + double(box.max_y));
  const double half = 0.5 * std::hypot(double(box.max_x - box.min_x), double(box.max_y - box.min_y)) +
                      geo::kUnitsPerMm;  // a radius round the box's centre, a mm to spare
  const double pitch = std::clamp(2 * half / 40, 0.2 * geo::kUnitsPerMm, 1.0 * geo::kUnitsPerMm);
  const double hold = hold_mm * geo::kUnitsPerMm, longest = max_bridge_mm * geo::kUnitsPerMm;
  auto at = [](double x, double y) { return geo::Point(std::llround(x), std::llround(y)); };
  double best = 0;
  for (int step = 0; step < 18; ++step) {
    const double a = step * std::numbers::pi / 18;
    const double dx = std::cos(a), dy = std::sin(a);  // along the lines
    double spanned = 0, total = 0;
    toolpath::for_each_chord(piece_grid, cx, cy, half, pitch, dx, dy,
                             [&](double x0, double y0, double x1, double y1, double l) {
                               total += l;
                               if (l > longest) return;
                               if (below_grid.inside(at(x0 - dx * hold, y0 - dy * hold)) &&
                                   below_grid.inside(at(x1 + dx * hold, y1 + dy * hold)))
                                 spanned += l;
                             });
    if (total > 0) best = std::max(best, spanned / total);
  }
  return best >= 0.5;
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
    if (is_bridge(piece, below, spec.max_bridge_mm, spec.reach_mm + 0.5 * spec.nozzle_mm)) continue;
    out.insert(out.end(), piece.begin(), piece.end());
  }
  return out;
}

}  // namespace tranche::support
