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

constexpr size_t kNearest = 6;  // cut candidates kept per hole vertex

// A cut candidate: vertices v and w, d2 apart (units²).
struct Candidate {
  exact::i128 d2;
  int v, w;
};

// Orders candidates shortest first.
bool shorter(const Candidate& a, const Candidate& b) { return a.d2 < b.d2; }

// The rings of `shape`, the outer counter-clockwise, the holes clockwise.
Rings oriented_rings(const Polygon& shape) {
  Rings rings;
  auto oriented = [](const Ring& r, bool ccw) {
    const exact::i128 a = exact::area2(r);
    return (a > 0) == ccw ? r : Ring(r.rbegin(), r.rend());
  };
  rings.push_back(oriented(shape.outer, true));
  for (const Ring& h : shape.holes) rings.push_back(oriented(h, false));
  return rings;
}

// Every edge of the rings, ring by ring.
std::vector<std::pair<Point, Point>> ring_edges(const Rings& rings) {
  std::vector<std::pair<Point, Point>> edges;
  for (const Ring& ring : rings) {
    for (size_t i = 0; i < ring.size(); ++i) edges.emplace_back(ring[i], ring[(i + 1) % ring.size()]);
  }
  return edges;
}

// The box around the rings.
BBox2 rings_box(const Rings& rings) {
  BBox2 box;
  for (const Ring& ring : rings) {
    for (const Point& p : ring) box.add(p);
  }
  return box;
}

// Joins the holes of one island: the rings' graph, which rings are already one path, and the
// cuts chosen so far.
class HoleJoiner {
 public:
  explicit HoleJoiner(const Polygon& shape)
      : rings_(oriented_rings(shape)),
        g_(rings_),
        nr_(static_cast<int>(rings_.size())),
        joined_(nr_),
        ring_of_(g_.vertex_count(), -1),
        edges_(ring_edges(rings_)),
        index_(edges_, rings_box(rings_)) {}

  // The single path, or an error when the holes cannot all be joined.
  Result<BridgedPath> run();

 private:
  void join_touching();
  bool admissible(int v, int w) const;
  void consider(int v, int w, std::vector<Candidate>& best);
  std::vector<Candidate> nearest_candidates();
  void join_nearest();
  Status join_remaining();
  Result<BridgedPath> walk_path();

  Rings rings_;
  PlanarGraph g_;
  const int nr_;
  UnionFind joined_;  // ring groups already one path
  std::vector<int> ring_of_;
  const std::vector<std::pair<Point, Point>> edges_;
  const EdgeIndex index_;
  std::vector<std::pair<int, int>> cuts_;
};

// Rings sharing a point are already one path there.
void HoleJoiner::join_touching() {
  for (int r = 0; r < nr_; ++r) {
    for (const int v : g_.ring_vertices()[r]) {
      if (ring_of_[v] >= 0) joined_.unite(ring_of_[v], r);
      ring_of_[v] = r;
    }
  }
}

// Whether the cut v-w runs inside the material, crossing no edge and no cut already made.
bool HoleJoiner::admissible(int v, int w) const {
  const Point &p = g_.point(v), &q = g_.point(w);
  if (!g_.points_into_material(v, q) || !g_.points_into_material(w, p)) return false;
  bool ok = true;
  index_.near(p, q, [&](int i) {
    if (!ok) return;
    const auto& [a, b] = edges_[i];
    const exact::Contact k = exact::contact(p, q, a, b);
    if (k == exact::Contact::None) return;
    // Only an edge ending at the cut's own endpoints may touch it.
    ok = k == exact::Contact::Touch && (a == p || a == q || b == p || b == q) &&
         !exact::strictly_between(p, a, q) && !exact::strictly_between(p, b, q);
  });
  for (const auto& [c, d] : cuts_) {
    if (!ok) break;
    const exact::Contact k = exact::contact(p, q, g_.point(c), g_.point(d));
    ok = k == exact::Contact::None || (k == exact::Contact::Touch && (c == v || c == w || d == v || d == w));
  }
  return ok;
}

// Keeps the cut v-w among the kNearest shortest in `best` when w is on a ring not joined to v's.
void HoleJoiner::consider(int v, int w, std::vector<Candidate>& best) {
  if (joined_.find(ring_of_[w]) == joined_.find(ring_of_[v])) return;
  best.push_back({dist2(g_.point(v), g_.point(w)), v, w});
  std::sort(best.begin(), best.end(), shorter);
  if (best.size() > kNearest) best.pop_back();
}

// Candidates: each hole vertex to its nearest vertices on other rings, shortest first.
std::vector<Candidate> HoleJoiner::nearest_candidates() {
  std::vector<int> by_x(g_.vertex_count());
  std::iota(by_x.begin(), by_x.end(), 0);
  std::sort(by_x.begin(), by_x.end(), [&](int a, int b) { return g_.point(a).X < g_.point(b).X; });
  std::vector<int> pos(g_.vertex_count());
  for (int i = 0; i < static_cast<int>(by_x.size()); ++i) pos[by_x[i]] = i;
  std::vector<Candidate> candidates;
  for (int v = 0; v < g_.vertex_count(); ++v) {
    if (ring_of_[v] == 0) continue;
    std::vector<Candidate> best;
    // Walk outwards in x until the x gap alone exceeds the kth distance.
    for (int dir : {-1, 1}) {
      for (int i = pos[v] + dir; i >= 0 && i < static_cast<int>(by_x.size()); i += dir) {
        const exact::i128 dx = g_.point(by_x[i]).X - g_.point(v).X;
        if (best.size() == kNearest && dx * dx > best.back().d2) break;
        consider(v, by_x[i], best);
      }
    }
    candidates.insert(candidates.end(), best.begin(), best.end());
  }
  std::sort(candidates.begin(), candidates.end(), shorter);
  return candidates;
}

// The admissible near candidates, shortest first, that join two groups (a spanning tree).
void HoleJoiner::join_nearest() {
  for (const Candidate& c : nearest_candidates()) {
    if (joined_.find(ring_of_[c.v]) == joined_.find(ring_of_[c.w]) || !admissible(c.v, c.w)) continue;
    joined_.unite(ring_of_[c.v], ring_of_[c.w]);
    cuts_.emplace_back(c.v, c.w);
  }
}

// Rare: every near candidate was blocked. Try all pairs from a separate group, shortest first.
Status HoleJoiner::join_remaining() {
  for (int r = 1; r < nr_; ++r) {
    if (joined_.find(r) == joined_.find(0)) continue;
    std::vector<Candidate> all;
    for (int v = 0; v < g_.vertex_count(); ++v) {
      if (joined_.find(ring_of_[v]) != joined_.find(r)) continue;
      for (int w = 0; w < g_.vertex_count(); ++w) {
        if (joined_.find(ring_of_[w]) != joined_.find(r))
          all.push_back({dist2(g_.point(v), g_.point(w)), v, w});
      }
    }
    std::sort(all.begin(), all.end(), shorter);
    bool done = false;
    for (const Candidate& c : all) {
      if (!admissible(c.v, c.w)) continue;
      joined_.unite(ring_of_[c.v], ring_of_[c.w]);
      cuts_.emplace_back(c.v, c.w);
      done = true;
      break;
    }
    if (!done) return Error{"", "a hole cannot be joined to the outline (inconsistent island)"};
    r = 0;  // groups merged: look again from ring 1
  }
  return ok_status();
}

// The cuts added to the graph, and its one face walked as the path.
Result<BridgedPath> HoleJoiner::walk_path() {
  for (const auto& [v, w] : cuts_) g_.add_chord(v, w);
  g_.freeze();
  std::vector<std::vector<int>> faces;
  if (!g_.faces(faces) || faces.size() != 1) {
    return Error{"", fmt::format("joining the holes left {} paths instead of one", faces.size())};
  }
  BridgedPath out;
  for (int h : faces[0]) {
    out.ring.push_back(g_.point(g_.half_edge(h).from));
    out.edges.push_back(g_.half_edge(h).kind);
  }
  out.cuts = static_cast<int>(cuts_.size());
  return out;
}

// Touching rings, then the nearest admissible cuts, then any admissible cut, then the path.
Result<BridgedPath> HoleJoiner::run() {
  join_touching();
  join_nearest();
  if (Status st = join_remaining(); !st) return st.error();
  return walk_path();
}

}  // namespace

Result<BridgedPath> bridge_holes(const Polygon& shape) { return HoleJoiner(shape).run(); }

}  // namespace tranche::geo
