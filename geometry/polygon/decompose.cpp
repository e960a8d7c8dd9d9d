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

// Rings with material on the left of every edge (outer counter-clockwise, holes clockwise),
// rings of zero area dropped, and their total area (×2, units²).
struct OrientedRings {
  Rings rings;
  exact::i128 area = 0;
};

// The rings of `shape` oriented for the sweep.
OrientedRings oriented_rings(const Polygon& shape) {
  OrientedRings out;
  auto add = [&](const Ring& ring, bool outer) {
    const exact::i128 a = exact::area2(ring);
    if (a == 0) return;
    out.rings.push_back((a > 0) == outer ? ring : Ring(ring.rbegin(), ring.rend()));
    out.area += outer ? (a > 0 ? a : -a) : (a > 0 ? -a : a);
  };
  add(shape.outer, true);
  for (const Ring& h : shape.holes) add(h, false);
  return out;
}

// Merges neighbours across a cut while their union stays monotone; repeats until stable, since a
// merge elsewhere can make a union monotone that was not. A monotone cell's boundary changes
// direction across the fill lines exactly twice (steps along a fill line aside); that count
// for the union follows from the steps next to the cut, which rejects most merges without a
// walk around the union. Unions passing it get the full exact test.
class CellMerger {
 public:
  CellMerger(PlanarGraph& g, std::vector<std::vector<int>>& faces, const FillDirection& dir);

  // Merges across the chords (half-edges of the cuts) until no merge is left.
  void merge(const std::vector<int>& chords);

 private:
  // The path around a face from the end of a half-edge back to its start: first and last
  // non-zero steps and the direction changes inside it (the face itself has 2 in all).
  struct Path {
    int first = 0, last = 0, changes = 0;
  };
  int step(int h) const;
  void index_face(int f);
  Path path_without(int f, int h) const;
  static int union_changes(const Path& a, const Path& b);
  bool try_merge(int c);

  PlanarGraph& g_;
  std::vector<std::vector<int>>& faces_;
  const FillDirection& dir_;
  std::vector<int64_t> level_;  // per vertex: its position across the fill lines
  std::vector<int> face_of_;    // per half-edge: its face
  std::vector<int> pos_;        // per half-edge: its index in its face
};

// Indexes the faces: each half-edge's face and place in it, each vertex's level.
CellMerger::CellMerger(PlanarGraph& g, std::vector<std::vector<int>>& faces, const FillDirection& dir)
    : g_(g), faces_(faces), dir_(dir), face_of_(g.half_edge_count(), -1) {
  for (int f = 0; f < static_cast<int>(faces_.size()); ++f) {
    for (int h : faces_[f]) face_of_[h] = f;
  }
  level_.resize(g_.vertex_count());
  for (int v = 0; v < g_.vertex_count(); ++v) level_[v] = dir_.across(g_.point(v));
  pos_.assign(g_.half_edge_count(), -1);
  for (int f = 0; f < static_cast<int>(faces_.size()); ++f) index_face(f);
}

// The direction of half-edge h across the fill lines: -1, 0 (along a line) or 1.
int CellMerger::step(int h) const {
  const int64_t d = level_[g_.half_edge(h).to] - level_[g_.half_edge(h).from];
  return (d > 0) - (d < 0);
}

// Records where each half-edge of face f lies in it.
void CellMerger::index_face(int f) {
  for (int i = 0; i < static_cast<int>(faces_[f].size()); ++i) pos_[faces_[f][i]] = i;
}

// The path around face f without half-edge h.
CellMerger::Path CellMerger::path_without(int f, int h) const {
  const auto& l = faces_[f];
  const int n = static_cast<int>(l.size()), at = pos_[h];
  Path p;
  for (int k = 1; k < n && p.first == 0; ++k) p.first = step(l[(at + k) % n]);
  for (int k = 1; k < n && p.last == 0; ++k) p.last = step(l[(at - k + n) % n]);
  if (p.first == 0) return p;
  const int s0 = step(h);
  p.changes = 2 - (s0 != 0 ? (p.last != s0) + (s0 != p.first) : (p.last != p.first));
  return p;
}

// The direction changes around the union of two faces joined along their cut.
int CellMerger::union_changes(const Path& a, const Path& b) {
  if (a.first == 0) return b.first == 0 ? 0 : b.changes + (b.last != b.first);
  if (b.first == 0) return a.changes + (a.last != a.first);
  return a.changes + b.changes + (a.last != b.first) + (b.last != a.first);
}

// Removes chord c when the union of the faces on its two sides is monotone; true when it did.
bool CellMerger::try_merge(int c) {
  if (g_.half_edge(c).removed) return false;
  const int t = g_.half_edge(c).twin;
  const int f1 = face_of_[c], f2 = face_of_[t];
  if (f1 == f2) return false;
  if (union_changes(path_without(f1, c), path_without(f2, t)) != 2) return false;
  g_.set_removed(c, true);
  const int start = faces_[f1][(pos_[c] + 1) % faces_[f1].size()];
  std::vector<int> merged = g_.face(start);
  if (merged.empty() || !is_monotone(face_ring(g_, merged), dir_)) {
    g_.set_removed(c, false);
    return false;
  }
  for (int h : merged) face_of_[h] = f1;
  faces_[f1] = std::move(merged);
  faces_[f2].clear();
  index_face(f1);
  return true;
}

// Passes over the chords until one merges nothing.
void CellMerger::merge(const std::vector<int>& chords) {
  for (bool changed = true; changed;) {
    changed = false;
    for (const int c : chords) changed |= try_merge(c);
  }
}

// The faces left as cells (empty faces were merged away); their total area (×2, units²) in `total`.
std::vector<Cell> cells_of(const PlanarGraph& g, const std::vector<std::vector<int>>& faces, double angle_deg,
                           exact::i128& total) {
  std::vector<Cell> cells;
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
  return cells;
}

}  // namespace

Result<std::vector<Cell>> decompose(const Polygon& shape, double angle_deg, DecomposeStats* stats) {
  if (!std::isfinite(angle_deg)) return Error{"", "fill angle is not a number"};
  if (!in_range(shape.outer)) return Error{"", "coordinates beyond ±2147 mm"};
  for (const Ring& h : shape.holes) {
    if (!in_range(h)) return Error{"", "coordinates beyond ±2147 mm"};
  }
  const FillDirection dir(angle_deg);
  const OrientedRings oriented = oriented_rings(shape);
  if (oriented.area <= 0) return std::vector<Cell>{};
  PlanarGraph g(oriented.rings, &dir);

  auto cuts = sweep_cuts(g);
  if (!cuts) return cuts.error();
  std::vector<int> chords;
  chords.reserve(cuts->size());
  for (const auto& [u, v] : *cuts) chords.push_back(g.add_chord(u, v));
  g.freeze();

  std::vector<std::vector<int>> faces;
  if (!g.faces(faces)) return Error{"", "the cuts do not close into cells"};
  if (stats) stats->sweep_cells = static_cast<int>(faces.size());
  CellMerger(g, faces, dir).merge(chords);

  exact::i128 total = 0;
  std::vector<Cell> cells = cells_of(g, faces, angle_deg, total);
  // Sweep cells are monotone by construction and merged ones were tested when merged; the areas
  // are a cheap exact check that the cells still tile the island.
  if (total != oriented.area) return Error{"", "cells do not tile the island"};
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
    return Error{
        fmt::format("layer {} island {}{}{}", layer.index, island, e.where.empty() ? "" : " ", e.where),
        e.message};
  }
  return cells;
}

}  // namespace tranche::geo
