#include "geometry/polygon/bridge.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "geometry/polygon/exact.h"
#include "geometry/polygon/planar_graph.h"

namespace tranche::geo {
namespace {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  bool unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    parent[b] = a;
    return true;
  }
};

exact::i128 dist2(const Point& a, const Point& b) {
  const exact::i128 dx = a.X - b.X, dy = a.Y - b.Y;
  return dx * dx + dy * dy;
}

// Boundary edges bucketed by a uniform grid, to test a candidate cut against nearby edges only.
class EdgeIndex {
 public:
  EdgeIndex(const std::vector<std::pair<Point, Point>>& edges, const BBox2& box) : box_(box) {
    const double w = static_cast<double>(box.max_x - box.min_x) + 1,
                 h = static_cast<double>(box.max_y - box.min_y) + 1;
    const double count = std::max<double>(1, static_cast<double>(edges.size()));
    cell_ = std::max(1.0, std::sqrt(w * h / count) * 2);
    nx_ = static_cast<int>(w / cell_) + 1;
    ny_ = static_cast<int>(h / cell_) + 1;
    buckets_.resize(static_cast<size_t>(nx_) * ny_);
    for (int i = 0; i < static_cast<int>(edges.size()); ++i) {
      cells(edges[i].first, edges[i].second, [&](size_t k) { buckets_[k].push_back(i); });
    }
  }
  // Calls f(edge index) for every edge sharing a bucket with the segment's box (maybe repeated).
  template <class F>
  void near(const Point& a, const Point& b, F&& f) const {
    cells(a, b, [&](size_t k) {
      for (int i : buckets_[k]) f(i);
    });
  }

 private:
  template <class F>
  void cells(const Point& a, const Point& b, F&& f) const {
    auto cx = [&](coord_t x) { return std::clamp(static_cast<int>((x - box_.min_x) / cell_), 0, nx_ - 1); };
    auto cy = [&](coord_t y) { return std::clamp(static_cast<int>((y - box_.min_y) / cell_), 0, ny_ - 1); };
    for (int i = cx(std::min(a.X, b.X)); i <= cx(std::max(a.X, b.X)); ++i) {
      for (int j = cy(std::min(a.Y, b.Y)); j <= cy(std::max(a.Y, b.Y)); ++j)
        f(static_cast<size_t>(i) * ny_ + j);
    }
  }
  BBox2 box_;
  double cell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> buckets_;
};

}  // namespace

Result<BridgedPath> bridge_holes(const Polygon& shape) {
  Rings rings;
  auto oriented = [](const Ring& r, bool ccw) {
    const exact::i128 a = exact::area2(r);
    return (a > 0) == ccw ? r : Ring(r.rbegin(), r.rend());
  };
  rings.push_back(oriented(shape.outer, true));
  for (const Ring& h : shape.holes) rings.push_back(oriented(h, false));
  PlanarGraph g(rings);

  // Rings sharing a point are already one path there.
  const int nr = static_cast<int>(rings.size());
  UnionFind joined(nr);
  std::vector<int> ring_of(g.vertex_count(), -1);
  std::vector<std::pair<Point, Point>> edges;
  BBox2 box;
  for (int r = 0; r < nr; ++r) {
    for (const int v : g.ring_vertices()[r]) {
      if (ring_of[v] >= 0) joined.unite(ring_of[v], r);
      ring_of[v] = r;
    }
    for (size_t i = 0; i < rings[r].size(); ++i) {
      edges.emplace_back(rings[r][i], rings[r][(i + 1) % rings[r].size()]);
      box.add(rings[r][i]);
    }
  }
  const EdgeIndex index(edges, box);
  std::vector<std::pair<int, int>> cuts;

  auto admissible = [&](int v, int w) {
    const Point &p = g.point(v), &q = g.point(w);
    if (!g.points_into_material(v, q) || !g.points_into_material(w, p)) return false;
    bool ok = true;
    index.near(p, q, [&](int i) {
      if (!ok) return;
      const auto& [a, b] = edges[i];
      const exact::Contact k = exact::contact(p, q, a, b);
      if (k == exact::Contact::None) return;
      // Only an edge ending at the cut's own endpoints may touch it.
      ok = k == exact::Contact::Touch && (a == p || a == q || b == p || b == q) &&
           !exact::strictly_between(p, a, q) && !exact::strictly_between(p, b, q);
    });
    for (const auto& [c, d] : cuts) {
      if (!ok) break;
      const exact::Contact k = exact::contact(p, q, g.point(c), g.point(d));
      ok =
          k == exact::Contact::None || (k == exact::Contact::Touch && (c == v || c == w || d == v || d == w));
    }
    return ok;
  };

  // Candidates: each hole vertex to its nearest vertices on other rings, shortest first.
  struct Candidate {
    exact::i128 d2;
    int v, w;
  };
  std::vector<int> by_x(g.vertex_count());
  std::iota(by_x.begin(), by_x.end(), 0);
  std::sort(by_x.begin(), by_x.end(), [&](int a, int b) { return g.point(a).X < g.point(b).X; });
  std::vector<int> pos(g.vertex_count());
  for (int i = 0; i < static_cast<int>(by_x.size()); ++i) pos[by_x[i]] = i;
  constexpr size_t kNearest = 6;
  std::vector<Candidate> candidates;
  for (int v = 0; v < g.vertex_count(); ++v) {
    if (ring_of[v] == 0) continue;
    std::vector<Candidate> best;
    auto consider = [&](int w) {
      if (joined.find(ring_of[w]) == joined.find(ring_of[v])) return;
      best.push_back({dist2(g.point(v), g.point(w)), v, w});
      std::sort(best.begin(), best.end(), [](const Candidate& a, const Candidate& b) { return a.d2 < b.d2; });
      if (best.size() > kNearest) best.pop_back();
    };
    // Walk outwards in x until the x gap alone exceeds the kth distance.
    for (int dir : {-1, 1}) {
      for (int i = pos[v] + dir; i >= 0 && i < static_cast<int>(by_x.size()); i += dir) {
        const exact::i128 dx = g.point(by_x[i]).X - g.point(v).X;
        if (best.size() == kNearest && dx * dx > best.back().d2) break;
        consider(by_x[i]);
      }
    }
    candidates.insert(candidates.end(), best.begin(), best.end());
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.d2 < b.d2; });
  for (const Candidate& c : candidates) {
    if (joined.find(ring_of[c.v]) == joined.find(ring_of[c.w]) || !admissible(c.v, c.w)) continue;
    joined.unite(ring_of[c.v], ring_of[c.w]);
    cuts.emplace_back(c.v, c.w);
  }
  // Rare: every near candidate was blocked. Try all pairs from a separate group, shortest first.
  for (int r = 1; r < nr; ++r) {
    if (joined.find(r) == joined.find(0)) continue;
    std::vector<Candidate> all;
    for (int v = 0; v < g.vertex_count(); ++v) {
      if (joined.find(ring_of[v]) != joined.find(r)) continue;
      for (int w = 0; w < g.vertex_count(); ++w) {
        if (joined.find(ring_of[w]) != joined.find(r)) all.push_back({dist2(g.point(v), g.point(w)), v, w});
      }
    }
    std::sort(all.begin(), all.end(), [](const Candidate& a, const Candidate& b) { return a.d2 < b.d2; });
    bool done = false;
    for (const Candidate& c : all) {
      if (!admissible(c.v, c.w)) continue;
      joined.unite(ring_of[c.v], ring_of[c.w]);
      cuts.emplace_back(c.v, c.w);
      done = true;
      break;
    }
    if (!done) return Error{"", "a hole cannot be joined to the outline (inconsistent island)"};
    r = 0;  // groups merged: look again from ring 1
  }

  for (const auto& [v, w] : cuts) g.add_chord(v, w);
  g.freeze();
  std::vector<std::vector<int>> faces;
  if (!g.faces(faces) || faces.size() != 1) {
    return Error{"", fmt::format("joining the holes left {} paths instead of one", faces.size())};
  }
  BridgedPath out;
  for (int h : faces[0]) {
    out.ring.push_back(g.point(g.half_edge(h).from));
    out.edges.push_back(g.half_edge(h).kind);
  }
  out.cuts = static_cast<int>(cuts.size());
  return out;
}

}  // namespace tranche::geo
