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
Result<std::vector<std::pair<int, int>>> sweep_cuts(const PlanarGraph& g) {
  // The graph numbers its vertices in sweep order (built with the fill direction): v is swept v-th.
  const int nv = g.vertex_count();

  std::vector<Active> status;
  std::vector<std::pair<int, int>> cuts;
  std::vector<Active> down;
  for (int v = 0; v < nv; ++v) {
    const Point& p = g.point(v);
    int count_up = 0;
    down.clear();
    for (const PlanarGraph::Spoke& s : g.spokes(v)) {
      if (s.other < v) {
        ++count_up;
      } else {
        down.push_back({v, s.other, s.out, -1, false});
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
  exact::i128 area = 0;
  Rings rings;  // outer counter-clockwise, holes clockwise: material on the left of every edge
  auto add = [&](const Ring& ring, bool outer) {
    const exact::i128 a = exact::area2(ring);
    if (a == 0) return;
    rings.push_back((a > 0) == outer ? ring : Ring(ring.rbegin(), ring.rend()));
    area += outer ? (a > 0 ? a : -a) : (a > 0 ? -a : a);
  };
  add(shape.outer, true);
  for (const Ring& h : shape.holes) add(h, false);
  std::vector<Cell> cells;
  if (area <= 0) return cells;
  PlanarGraph g(rings, &dir);

  auto cuts = sweep_cuts(g);
  if (!cuts) return cuts.error();
  std::vector<int> chords;
  chords.reserve(cuts->size());
  for (const auto& [u, v] : *cuts) chords.push_back(g.add_chord(u, v));
  g.freeze();

  std::vector<std::vector<int>> faces;
  if (!g.faces(faces)) return Error{"", "the cuts do not close into cells"};
  std::vector<int> face_of(g.half_edge_count(), -1);
  for (int f = 0; f < static_cast<int>(faces.size()); ++f) {
    for (int h : faces[f]) face_of[h] = f;
  }
  if (stats) stats->sweep_cells = static_cast<int>(faces.size());

  // Merge neighbours across a cut while their union stays monotone; repeat until stable, since a
  // merge elsewhere can make a union monotone that was not. A monotone cell's boundary changes
  // direction across the fill lines exactly twice (steps along a fill line aside); that count
  // for the union follows from the steps next to the cut, which rejects most merges without a
  // walk around the union. Unions passing it get the full exact test.
  std::vector<int64_t> level(g.vertex_count());
  for (int v = 0; v < g.vertex_count(); ++v) level[v] = dir.across(g.point(v));
  auto step = [&](int h) {
    const int64_t d = level[g.half_edge(h).to] - level[g.half_edge(h).from];
    return (d > 0) - (d < 0);
  };
  std::vector<int> pos(g.half_edge_count(), -1);
  auto index_face = [&](int f) {
    for (int i = 0; i < static_cast<int>(faces[f].size()); ++i) pos[faces[f][i]] = i;
  };
  for (int f = 0; f < static_cast<int>(faces.size()); ++f) index_face(f);
  // The path around face f from the end of half-edge h back to its start: first and last
  // non-zero steps and the direction changes inside it (the face itself has 2 in all).
  struct Path {
    int first = 0, last = 0, changes = 0;
  };
  auto path_without = [&](int f, int h) {
    const auto& l = faces[f];
    const int n = static_cast<int>(l.size()), at = pos[h];
    Path p;
    for (int k = 1; k < n && p.first == 0; ++k) p.first = step(l[(at + k) % n]);
    for (int k = 1; k < n && p.last == 0; ++k) p.last = step(l[(at - k + n) % n]);
    if (p.first == 0) return p;
    const int s0 = step(h);
    p.changes = 2 - (s0 != 0 ? (p.last != s0) + (s0 != p.first) : (p.last != p.first));
    return p;
  };
  auto union_changes = [](const Path& a, const Path& b) {
    if (a.first == 0) return b.first == 0 ? 0 : b.changes + (b.last != b.first);
    if (b.first == 0) return a.changes + (a.last != a.first);
    return a.changes + b.changes + (a.last != b.first) + (b.last != a.first);
  };
  for (bool changed = true; changed;) {
    changed = false;
    for (const int c : chords) {
      if (g.half_edge(c).removed) continue;
      const int t = g.half_edge(c).twin;
      const int f1 = face_of[c], f2 = face_of[t];
      if (f1 == f2) continue;
      if (union_changes(path_without(f1, c), path_without(f2, t)) != 2) continue;
      g.set_removed(c, true);
      const int start = faces[f1][(pos[c] + 1) % faces[f1].size()];
      std::vector<int> merged = g.face(start);
      if (merged.empty() || !is_monotone(face_ring(g, merged), dir)) {
        g.set_removed(c, false);
        continue;
      }
      for (int h : merged) face_of[h] = f1;
      faces[f1] = std::move(merged);
      faces[f2].clear();
      index_face(f1);
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
    total += exact::area2(cell.ring);
    cells.push_back(std::move(cell));
  }
  // Sweep cells are monotone by construction and merged ones were tested when merged; the areas
  // are a cheap exact check that the cells still tile the island.
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

Result<std::vector<Cell>> decompose_island(const Layer& layer, size_t island, double angle_deg,
                                           DecomposeStats* stats) {
  auto cells = decompose(layer.islands[island].shape, angle_deg, stats);
  if (!cells) {
    const Error& e = cells.error();
    return Error{fmt::format("layer {} island {}{}{}", layer.index, island, e.where.empty() ? "" : " ", e.where),
                 e.message};
  }
  return cells;
}

}  // namespace tranche::geo
