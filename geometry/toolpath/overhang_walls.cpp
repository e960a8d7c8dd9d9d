#include "geometry/toolpath/overhang_walls.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/edge_grid.h"

namespace tranche::toolpath {

using geo::Rings;

OverhangWallSplit split_overhang_walls(const Rings& island, const Rings& below, double band_mm, double bead_mm,
                                       double anchor_mm) {
  OverhangWallSplit out;
  if (island.empty() || bead_mm <= 0 || band_mm <= 0) return out;
  const geo::BBox2 box = bbox(island);
  geo::BBox2 grown = box;
  const geo::coord_t m = geo::to_units(bead_mm + anchor_mm + 1);
  grown.min_x -= m, grown.min_y -= m, grown.max_x += m, grown.max_y += m;
  const Rings near_below = near(below, grown);
  // Parts nowhere kMinAirAcrossMm wide go: a slope's walls leaning out a little each layer, a
  // curved underside's crescent. First without growing the layer below (the common case, on
  // every layer of every island, is answered by a boolean and a shrink of the slivers it leaves):
  // what lies off the layer below contains the air, so if it is nowhere 2r wide neither is the air.
  const double r = 0.5 * std::max(bead_mm, kMinAirAcrossMm);
  const Rings bare = difference(island, near_below);
  if (bare.empty() || offset(bare, -r).empty()) return out;
  // A bead rests on the layer below when material lies within half a bead of its centre.
  Rings air_raw = difference(island, offset(near_below, 0.5 * bead_mm));
  if (air_raw.empty()) return out;
  const Rings wide = offset_open(air_raw, 0, r);
  if (wide.empty()) return out;
  // The air a bead wide around the wide parts (their corners as they are, not rounded).
  const Rings air = intersection(offset_open(air_raw, 0, 0.5 * bead_mm), offset(wide, r + 0.5 * bead_mm));
  if (air.empty()) return out;
  const Rings band = difference(island, offset(island, -band_mm));
  if (offset_open(intersection(air, band), 0, 0.5 * bead_mm).empty()) return out;
  double held = 0;
  const double angle = bridge_angle_deg(air, near_below, 0.5 * bead_mm + 0.3, &held);
  if (held < kMinHeldShare) return out;
  out.air = air;
  out.bridge = intersection(offset(air, anchor_mm), island);
  out.angle_deg = angle;
  return out;
}

double bridge_angle_deg(const Rings& air, const Rings& below, double hold_mm, double* held_share) {
  if (held_share) *held_share = 0;
  if (air.empty()) return 0;
  const geo::BBox2 box = bbox(air);
  const EdgeGrid air_grid(air), below_grid(below);
  const double cx = 0.5 * (double(box.min_x) + double(box.max_x)), cy = 0.5 * (double(box.min_y) + double(box.max_y));
  const double half = 0.5 * std::hypot(double(box.max_x - box.min_x), double(box.max_y - box.min_y)) + geo::kUnitsPerMm;
  const double pitch = std::clamp(2 * half / 60, 0.1 * geo::kUnitsPerMm, 1.0 * geo::kUnitsPerMm);
  const double hold = hold_mm * geo::kUnitsPerMm;
  const double across = 2 * half * geo::kMmPerUnit;  // longer than any line: what a line held nowhere counts
  auto at = [](double x, double y) { return geo::Point(std::llround(x), std::llround(y)); };
  auto held = [&](double x, double y) { return !below_grid.empty() && below_grid.inside(at(x, y)); };
  double best_cost = 1e300, best_deg = 0;
  for (int step = 0; step < 36; ++step) {
    const double deg = step * 5.0, a = deg * std::numbers::pi / 180;
    const double dx = std::cos(a), dy = std::sin(a);  // along the lines
    double hanging = 0, total = 0, held_len = 0;
    for_each_chord(air_grid, cx, cy, half, pitch, dx, dy, [&](double x0, double y0, double x1, double y1, double len) {
      const double l = len * geo::kMmPerUnit;
      const int ends = int(held(x0 - dx * hold, y0 - dy * hold)) + int(held(x1 + dx * hold, y1 + dy * hold));
      total += l;
      if (ends > 0) held_len += l;
      hanging += l * (ends == 2 ? l : ends == 1 ? 2 * l : 4 * across);
    });
    if (total <= 0) continue;
    const double cost = hanging / total;
    if (cost < best_cost - 1e-9) {
      best_cost = cost, best_deg = deg;
      if (held_share) *held_share = held_len / total;
    }
  }
  return best_deg;
}

std::vector<geo::Ring> loops_outside(const std::vector<geo::Ring>& loops, const Rings& region, double min_mm) {
  std::vector<geo::Ring> out;
  Rings lines = clip_loops(Rings(loops.begin(), loops.end()), region, false);
  // A loop cut where it does not start comes out as pieces meeting at its first point: joined.
  for (bool joined = true; joined;) {
    joined = false;
    for (size_t i = 0; i < lines.size() && !joined; ++i)
      for (size_t j = 0; j < lines.size() && !joined; ++j) {
        if (i == j || lines[i].empty() || lines[j].empty() || lines[i].back() != lines[j].front()) continue;
        lines[i].insert(lines[i].end(), lines[j].begin() + 1, lines[j].end());
        lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(j));
        joined = true;
      }
  }
  for (geo::Ring& l : lines) {
    double len = 0;
    for (size_t i = 1; i < l.size(); ++i)
      len += std::hypot(geo::to_mm(l[i].X - l[i - 1].X), geo::to_mm(l[i].Y - l[i - 1].Y));
    if (len >= min_mm) out.push_back(std::move(l));
  }
  return out;
}

}  // namespace tranche::toolpath
