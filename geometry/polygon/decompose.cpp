#include "geometry/polygon/decompose.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "geometry/polygon/exact.h"
#include "geometry/polygon/monotone.h"
#include "geometry/polygon/planar_graph.h"
#include "geometry/polygon/resolve.h"

namespace tranche::geo {
namespace {

std::string at(const Point& p) { return fmt::format("at ({:.3f}, {:.3f}) mm", to_mm(p.X), to_mm(p.Y)); }

// An edge crossing the sweep line. Material lies to its right when it runs downward (material is
// on the left of every boundary half-edge); such an edge is the left side of a material interval
// and carries that interval's helper: the last vertex swept inside the interval.
struct Active {
  int upper = -1, lower = -1;
  bool interior_right = false;
  int helper = -1;
  bool helper_is_merge = false;  // the helper still needs a cut downward
};

// The sweep: returns the cuts (pairs of vertices). It generalises the classic split/merge
// vertex method to points where several rings meet: every wedge of material at the point is
// handled at once from the edges ending there (U, from above) and starting there (D).
Result<std::vector<std::pair<int, int>>> sweep_cuts(const PlanarGraph& g, const FillDirection& dir) {
  const int nv = g.vertex_count();
  std::vector<int> order(nv);
  for (int v = 0; v < nv; ++v) order[v] = v;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return dir.before(g.point(a), g.point(b)); });
  std::vector<int> rank(nv);
  for (int i = 0; i < nv; ++i) rank[order[i]] = i;

  std::vector<Active> status;
  std::vector<std::pair<int, int>> cuts;
  std::vector<Active> down;
  for (const int v : order) {
    const Point& p = g.point(v);
    int count_up = 0;
    down.clear();
    for (const auto* list : {&g.boundary_out(v), &g.boundary_in(v)}) {
      for (const int h : *list) {
        const auto& e = g.half_edge(h);
        const int other = e.from == v ? e.to : e.from;
        if (rank[other] < rank[v]) {
          ++count_up;
        } else {
          down.push_back({v, other, e.from == v, -1, false});
        }
      }
    }
    const auto lo_it = std::partition_point(status.begin(), status.end(), [&](const Active& e) {
      return exact::orientation(g.point(e.upper), g.point(e.lower), p) > 0;
    });
    const size_t lo = static_cast<size_t>(lo_it - status.begin());
    size_t k = 0;
    while (lo + k < status.size() && status[lo + k].lower == v) ++k;
    if (static_cast<int>(k) != count_up ||
        (lo + k < status.size() &&
         exact::orientation(g.point(status[lo + k].upper), g.point(status[lo + k].lower), p) == 0)) {
      return Error{at(p),
                   "inconsistent outline (crossing edges or a vertex on an edge) in the monotone sweep"};
    }
    // Material intervals just above v that reach v: split (no edge from above) or closing.
    for (size_t j = 0; j <= k; ++j) {
      const Active* left = j == 0 ? (lo > 0 ? &status[lo - 1] : nullptr) : &status[lo + j - 1];
      if (left == nullptr || !left->interior_right) continue;
      if (left->helper < 0) return Error{at(p), "material interval without a helper in the monotone sweep"};
      if (k == 0 || left->helper_is_merge) cuts.emplace_back(v, left->helper);
    }
    std::sort(down.begin(), down.end(), [&](const Active& a, const Active& b) {
      return exact::orientation(p, g.point(a.lower), g.point(b.lower)) > 0;
    });
    for (size_t j = 1; j < down.size(); ++j) {
      if (exact::orientation(p, g.point(down[j - 1].lower), g.point(down[j].lower)) == 0) {
        return Error{at(p), "overlapping edges in the monotone sweep"};
      }
    }
    status.erase(status.begin() + static_cast<std::ptrdiff_t>(lo),
                 status.begin() + static_cast<std::ptrdiff_t>(lo + k));
    status.insert(status.begin() + static_cast<std::ptrdiff_t>(lo), down.begin(), down.end());
    // Material intervals just below v that reach v: v is their helper; with nothing going down
    // from v (a merge), the one interval below still needs a cut downward.
    const size_t m = down.size();
    for (size_t j = 0; j <= m; ++j) {
      Active* left = j == 0 ? (lo > 0 ? &status[lo - 1] : nullptr) : &status[lo + j - 1];
      if (left == nullptr || !left->interior_right) continue;
      left->helper = v;
      left->helper_is_merge = m == 0;
    }
  }
  if (!status.empty()) return Error{"", "open outline in the monotone sweep"};
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  return cuts;
}

Ring face_ring(const PlanarGraph& g, const std::vector<int>& face) {
  Ring r;
  r.reserve(face.size());
  for (int h : face) r.push_back(g.point(g.half_edge(h).from));
  return r;
}

bool in_range(const Ring& r) {
  for (const Point& p : r) {
    if (std::llabs(p.X) >= kMaxSweepCoord || std::llabs(p.Y) >= kMaxSweepCoord) return false;
  }
  return true;
}

}  // namespace

Result<std::vector<Cell>> decompose(const Polygon& shape, double angle_deg, DecomposeStats* stats) {
  if (!std::isfinite(angle_deg)) return Error{"", "fill angle is not a number"};
  if (!in_range(shape.outer)) return Error{"", "coordinates beyond ±2147 mm"};
  for (const Ring& h : shape.holes) {
    if (!in_range(h)) return Error{"", "coordinates beyond ±2147 mm"};
  }
  const FillDirection dir(angle_deg);
  PlanarGraph g;
  exact::i128 area = 0;
  auto add = [&](const Ring& ring, bool outer) {
    const exact::i128 a = exact::area2(ring);
    if (a == 0) return;
    if ((a > 0) == outer) {
      g.add_ring(ring);
    } else {
      Ring r(ring.rbegin(), ring.rend());
      g.add_ring(r);
    }
    area += outer ? (a > 0 ? a : -a) : (a > 0 ? -a : a);
  };
  add(shape.outer, true);
  for (const Ring& h : shape.holes) add(h, false);
  std::vector<Cell> cells;
  if (area <= 0) return cells;

  auto cuts = sweep_cuts(g, dir);
  if (!cuts) return cuts.error();
  std::vector<int> chords;
  chords.reserve(cuts->size());
  for (const auto& [u, v] : *cuts) chords.push_back(g.add_chord(u, v));

  std::vector<std::vector<int>> faces;
  if (!g.faces(faces)) return Error{"", "the cuts do not close into cells"};
  std::vector<int> face_of(g.half_edge_count(), -1);
  for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
    for (int h : faces[f]) face_of[h] = f;
  }
  if (stats) stats->sweep_cells = static_cast<int>(faces.size());

  // Merge neighbours across a cut while their union stays monotone; repeat until stable, since a
  // merge elsewhere can make a union monotone that was not.
  for (bool changed = true; changed;) {
    changed = false;
    for (const int c : chords) {
      if (g.half_edge(c).removed) continue;
      const int f1 = face_of[c], f2 = face_of[g.half_edge(c).twin];
      if (f1 == f2) continue;
      g.set_removed(c, true);
      int start = -1;
      for (int h : faces[f1]) {
        if (h != c) start = h;
      }
      std::vector<int> merged = start < 0 ? std::vector<int>{} : g.face(start);
      if (merged.empty() || !is_monotone(face_ring(g, merged), dir)) {
        g.set_removed(c, false);
        continue;
      }
      for (int h : merged) face_of[h] = f1;
      faces[f1] = std::move(merged);
      faces[f2].clear();
      changed = true;
    }
  }

  exact::i128 total = 0;
  for (const auto& f : faces) {
    if (f.empty()) continue;
    Cell cell;
    cell.ring = face_ring(g, f);
    cell.edges.reserve(f.size());
    for (int h : f) cell.edges.push_back(g.half_edge(h).kind);
    cell.fill_angle_deg = angle_deg;
    if (!is_monotone(cell.ring, dir)) {
      return Error{at(cell.ring[0]), fmt::format("a cell is not monotone at {}°", angle_deg)};
    }
    total += exact::area2(cell.ring);
    cells.push_back(std::move(cell));
  }
  if (total != area) return Error{"", "cells do not tile the island"};
  if (stats) {
    stats->cells = static_cast<int>(cells.size());
    stats->cuts = 0;
    for (int c : chords) stats->cuts += !g.half_edge(c).removed;
  }
  return cells;
}

Result<std::vector<Cell>> decompose_region(const Rings& region, double angle_deg, DecomposeStats* stats) {
  auto islands = strict_islands(region, OverlapMode::Additive);
  if (!islands) return islands.error();
  std::vector<Cell> cells;
  for (const Island& is : *islands) {
    DecomposeStats s;
    auto part = decompose(is.shape, angle_deg, &s);
    if (!part) return part.error();
    cells.insert(cells.end(), std::make_move_iterator(part->begin()), std::make_move_iterator(part->end()));
    if (stats) {
      stats->sweep_cells += s.sweep_cells;
      stats->cells += s.cells;
      stats->cuts += s.cuts;
    }
  }
  return cells;
}

double default_fill_angle(int layer_index) { return layer_index % 2 == 0 ? 45.0 : 135.0; }

Status decompose_island(Island& island, double angle_deg, DecomposeStats* stats) {
  auto cells = decompose(island.shape, angle_deg, stats);
  if (!cells) return cells.error();
  island.fill_angle_deg = angle_deg;
  island.cells = std::move(*cells);
  return ok_status();
}

Status decompose_layer(Layer& layer, DecomposeStats* total) {
  for (size_t i = 0; i < layer.islands.size(); ++i) {
    Island& is = layer.islands[i];
    const double angle = std::isnan(is.fill_angle_deg) ? default_fill_angle(layer.index) : is.fill_angle_deg;
    DecomposeStats s;
    Status st = decompose_island(is, angle, &s);
    if (!st) {
      const Error& e = st.error();
      return Error{fmt::format("layer {} island {}{}{}", layer.index, i, e.where.empty() ? "" : " ", e.where),
                   e.message};
    }
    if (total) {
      total->sweep_cells += s.sweep_cells;
      total->cells += s.cells;
      total->cuts += s.cuts;
    }
  }
  return ok_status();
}

}  // namespace tranche::geo
