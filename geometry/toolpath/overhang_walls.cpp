#include "geometry/toolpath/overhang_walls.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

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
  // curved underside's crescent. First without growing the layer below: what lies off the layer
  // below contains the air, so if it is nowhere 2r wide neither is the air. The common case, on
  // every layer of every island, is answered without a boolean by may_hold_disc (on the Stanford
  // bunny 945 of its 968 islands, all those the boolean and the shrink below would answer: they
  // were a tenth of the run's time); what it lets through, by the boolean and the shrink.
  const double r = 0.5 * std::max(bead_mm, kMinAirAcrossMm);
  if (!may_hold_disc(island, near_below, r)) return out;
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

bool may_hold_disc(const Rings& region, const Rings& below, double r_mm) {
  if (region.empty()) return false;
  const double rho = (r_mm - kDiscMarginMm) * geo::kUnitsPerMm;
  if (rho <= 0) return true;
  const geo::BBox2 box = bbox(region);
  if (double(box.max_x - box.min_x) < 2 * rho || double(box.max_y - box.min_y) < 2 * rho) return false;
  // Rows y0 + (i + ½)·pitch: every point of the region's box lies within half a pitch of one.
  // A disc of radius rho centred at p, with row i nearest p, crosses row i + k in a chord
  // centred at p.x of half-length √(rho² − d²), d the row's distance from p.y, lying in one
  // stretch of the difference along that row: p.x lies in every such stretch shrunk by that
  // much at both ends. With p.y known to within a quarter of a pitch (kSlots slots per row),
  // d is bounded above row by row, and so the chords' lengths below: no p.x common to the
  // stretches for any row and slot, no disc.
  const double pitch = rho / 4;
  constexpr int K = 5, kSlots = 4;  // rows farther than K from row i: (K − ½)·pitch > rho, never asked
  double w[kSlots][2 * K + 1];     // half-chord by slot and row (−1: not asked)
  for (int j = 0; j < kSlots; ++j)
    for (int k = -K; k <= K; ++k) {
      const double lo = (j / double(kSlots) - 0.5) * pitch, hi = lo + pitch / kSlots;  // p.y − y_i
      const double d = std::max(std::abs(k * pitch - lo), std::abs(k * pitch - hi));
      w[j][k + K] = d < rho ? std::sqrt(rho * rho - d * d) : -1;
    }
  const double y0 = double(box.min_y), span = std::ceil(double(box.max_y - box.min_y) / pitch);
  if (!(span < 1e6)) return true;  // a region kilometres across: left to the boolean
  const int rows = std::max(1, int(span));
  // Where each ring's edges cross each row: x, and the winding's step there (+1 or −1) for the
  // region (first) or for below (second). Half-open in y, as a point-in-polygon ray is.
  struct Cross {
    int row;
    double x;
    int8_t dr, db;
  };
  std::vector<Cross> xs;
  auto add = [&](const Rings& rings, bool is_below) {
    for (const auto& r : rings)
      for (size_t j = 0; j < r.size(); ++j) {
        const geo::Point &a = r[j], &b = r[(j + 1) % r.size()];
        if (a.Y == b.Y) continue;
        const double lo = double(std::min(a.Y, b.Y)), hi = double(std::max(a.Y, b.Y));
        int i = std::max(0, int(std::ceil((lo - y0) / pitch - 0.5)));
        const int8_t step = b.Y > a.Y ? 1 : -1;
        for (; i < rows; ++i) {
          const double y = y0 + (i + 0.5) * pitch;
          if (y >= hi) break;
          if (y < lo) continue;
          const double x = double(a.X) + (y - double(a.Y)) * double(b.X - a.X) / double(b.Y - a.Y);
          xs.push_back({i, x, is_below ? int8_t(0) : step, is_below ? step : int8_t(0)});
        }
      }
  };
  add(region, false);
  add(below, true);
  // By row (counting), then by x within each row (a few each).
  std::vector<size_t> first(static_cast<size_t>(rows) + 1, 0);
  for (const Cross& c : xs) ++first[static_cast<size_t>(c.row) + 1];
  for (size_t i = 1; i < first.size(); ++i) first[i] += first[i - 1];
  std::vector<Cross> sorted(xs.size());
  {
    std::vector<size_t> at(first.begin(), first.end() - 1);
    for (const Cross& c : xs) sorted[at[static_cast<size_t>(c.row)]++] = c;
  }
  for (size_t i = 0; i + 1 < first.size(); ++i)
    std::sort(sorted.begin() + static_cast<std::ptrdiff_t>(first[i]), sorted.begin() + static_cast<std::ptrdiff_t>(first[i + 1]),
              [](const Cross& u, const Cross& v) { return u.x < v.x; });
  xs.swap(sorted);
  // Each row's stretches of the region less below (non-zero winding), as [lo, hi] pairs.
  std::vector<std::pair<double, double>> runs;
  for (size_t k = 0, row = 0; row < static_cast<size_t>(rows); ++row) {
    first[row] = runs.size();
    int wr = 0, wb = 0;
    bool in = false;
    double start = 0;
    while (k < xs.size() && xs[k].row == int(row)) {
      const double x = xs[k].x;
      for (; k < xs.size() && xs[k].row == int(row) && xs[k].x == x; ++k) wr += xs[k].dr, wb += xs[k].db;
      const bool now = wr != 0 && wb == 0;
      if (now && !in) start = x;
      if (!now && in) runs.emplace_back(start, x);
      in = now;
    }
  }
  first[static_cast<size_t>(rows)] = runs.size();
  // The p.x allowed so far (sorted disjoint closed intervals), narrowed row by row.
  std::vector<std::pair<double, double>> can, next;
  auto narrow = [&](int row, double half) {
    next.clear();
    if (row < 0 || row >= rows) {
      can.clear();
      return;
    }
    size_t a = 0, b = first[static_cast<size_t>(row)];
    const size_t end = first[static_cast<size_t>(row) + 1];
    while (a < can.size() && b < end) {
      const double lo = std::max(can[a].first, runs[b].first + half), hi = std::min(can[a].second, runs[b].second - half);
      if (lo <= hi) next.emplace_back(lo, hi);
      if (can[a].second < runs[b].second - half) ++a;
      else ++b;
    }
    can.swap(next);
  };
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < kSlots; ++j) {
      can.clear();
      const double w0 = w[j][K];
      for (size_t b = first[static_cast<size_t>(i)]; b < first[static_cast<size_t>(i) + 1]; ++b)
        if (runs[b].second - runs[b].first >= 2 * w0) can.emplace_back(runs[b].first + w0, runs[b].second - w0);
      for (int k = 1; k <= K && !can.empty(); ++k) {
        if (w[j][K - k] >= 0) narrow(i - k, w[j][K - k]);
        if (!can.empty() && w[j][K + k] >= 0) narrow(i + k, w[j][K + k]);
      }
      if (!can.empty()) return true;
    }
  }
  return false;
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
