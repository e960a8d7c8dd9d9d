#include "geometry/toolpath/lightning.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <unordered_map>

#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/edge_grid.h"
#include "geometry/toolpath/relations.h"

namespace tranche::toolpath {

namespace {

using geo::coord_t;

// Points in bed units, as doubles: the trees move their nodes by fractions of a unit.
struct P {
  double x, y;
};
double dist(P a, P b) { return std::hypot(a.x - b.x, a.y - b.y); }
P of(const geo::Point& q) { return {static_cast<double>(q.X), static_cast<double>(q.Y)}; }
geo::Point to_pt(P p) { return geo::Point(std::llround(p.x), std::llround(p.y)); }
P nearest_on(P a, P b, P p) {
  const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
  const double t = l2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / l2, 0.0, 1.0) : 0.0;
  return {a.x + t * dx, a.y + t * dy};
}
uint64_t cell_key(int64_t ix, int64_t iy) {
  return (static_cast<uint64_t>(ix) << 32) ^ static_cast<uint64_t>(static_cast<uint32_t>(iy));
}
int64_t cell_of(double v, double cell) { return static_cast<int64_t>(std::floor(v / cell)); }

constexpr double kGrounded = 5000;  // units (5 µm): a root this near the border stands on the walls
constexpr double kNudge = 2000;     // units: roots sit this far inside the border, off its edges
constexpr double kCollinear = 10000;  // units: a chain node this near the line of its neighbours goes
constexpr double kMerged = 1000;      // units: a node this near its parent is merged into it

// The nearest point of a region's border, over a uniform grid of its edges.
class BorderIndex {
 public:
  BorderIndex(const geo::Rings& rings, double min_cell) {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (const geo::Ring& r : rings)
      for (size_t i = 0; i < r.size(); ++i) {
        edges_.push_back({of(r[i]), of(r[(i + 1) % r.size()])});
        x0 = std::min(x0, edges_.back().a.x), x1 = std::max(x1, edges_.back().a.x);
        y0 = std::min(y0, edges_.back().a.y), y1 = std::max(y1, edges_.back().a.y);
      }
    if (edges_.empty()) return;
    // About two edges a cell, never finer than min_cell (the trees' radius).
    cell_ = std::max({min_cell, std::sqrt((x1 - x0) * (y1 - y0) / static_cast<double>(edges_.size()) * 2), 1e3});
    x0_ = x0, y0_ = y0;
    nx_ = static_cast<int64_t>((x1 - x0) / cell_) + 1, ny_ = static_cast<int64_t>((y1 - y0) / cell_) + 1;
    cells_.assign(static_cast<size_t>(nx_ * ny_), {});
    for (uint32_t k = 0; k < edges_.size(); ++k) {
      const auto& e = edges_[k];
      const int64_t ax = cx(std::min(e.a.x, e.b.x)), bx = cx(std::max(e.a.x, e.b.x));
      const int64_t ay = cy(std::min(e.a.y, e.b.y)), by = cy(std::max(e.a.y, e.b.y));
      for (int64_t ix = ax; ix <= bx; ++ix)
        for (int64_t iy = ay; iy <= by; ++iy) cells_[static_cast<size_t>(iy * nx_ + ix)].push_back(k);
    }
  }

  // The border's point nearest to p, and its distance; false when there is no border.
  bool nearest(P p, P& at, double& d) const {
    if (edges_.empty()) return false;
    d = std::numeric_limits<double>::infinity();
    const int64_t px = static_cast<int64_t>(std::floor((p.x - x0_) / cell_));
    const int64_t py = static_cast<int64_t>(std::floor((p.y - y0_) / cell_));
    // Rings of cells round p's; a cell r rings out is more than (r − 1) cells away.
    const int64_t far = std::max({std::abs(px), std::abs(px - nx_), std::abs(py), std::abs(py - ny_)}) + 1;
    for (int64_t r = 0; r <= far; ++r) {
      if (static_cast<double>(r - 1) * cell_ > d) break;
      for (int64_t ix = px - r; ix <= px + r; ++ix)
        for (int64_t iy = py - r; iy <= py + r; ++iy) {
          if (std::max(std::abs(ix - px), std::abs(iy - py)) != r) continue;
          if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_) continue;
          for (uint32_t k : cells_[static_cast<size_t>(iy * nx_ + ix)]) {
            const P q = nearest_on(edges_[k].a, edges_[k].b, p);
            const double dq = dist(p, q);
            if (dq < d) d = dq, at = q;
          }
        }
    }
    return std::isfinite(d);
  }

 private:
  int64_t cx(double x) const { return std::clamp<int64_t>(static_cast<int64_t>((x - x0_) / cell_), 0, nx_ - 1); }
  int64_t cy(double y) const { return std::clamp<int64_t>(static_cast<int64_t>((y - y0_) / cell_), 0, ny_ - 1); }
  struct Edge {
    P a, b;
  };
  std::vector<Edge> edges_;
  double cell_ = 1, x0_ = 0, y0_ = 0;
  int64_t nx_ = 0, ny_ = 0;
  std::vector<std::vector<uint32_t>> cells_;
};

// A forest: each node's position and parent (-1: a root).
struct Node {
  P p;
  int parent;
};
using Forest = std::vector<Node>;

std::vector<std::vector<int>> children_of(const Forest& f) {
  std::vector<std::vector<int>> kids(f.size());
  for (size_t i = 0; i < f.size(); ++i)
    if (f[i].parent >= 0) kids[static_cast<size_t>(f[i].parent)].push_back(static_cast<int>(i));
  return kids;
}

// Drops the nodes not `keep`; the kept ones' parents must be kept (or -1).
void compact(Forest& f, const std::vector<char>& keep) {
  std::vector<int> at(f.size(), -1);
  Forest out;
  for (size_t i = 0; i < f.size(); ++i)
    if (keep[i]) at[i] = static_cast<int>(out.size()), out.push_back(f[i]);
  for (Node& n : out)
    if (n.parent >= 0) n.parent = at[static_cast<size_t>(n.parent)];
  f = std::move(out);
}

// Nodes on a hash grid, for the nearest node to a point.
class NodeGrid {
 public:
  explicit NodeGrid(double cell) : cell_(cell) {}
  void add(const Forest& f, int id) { m_[key(f[static_cast<size_t>(id)].p)].push_back(id); }
  // The node minimising cost(id, distance) among those whose cost is below `limit`, within
  // `within` of p, for which ok(id) holds: -1 if none. cost must be at least the distance less
  // `slack`.
  template <class Cost, class Ok>
  int best(const Forest& f, P p, double limit, Cost&& cost, Ok&& ok, double slack = 0,
           double within = std::numeric_limits<double>::infinity()) const {
    const int64_t px = cell_of(p.x, cell_), py = cell_of(p.y, cell_);
    const auto reach = static_cast<int64_t>(std::ceil(std::min(limit + slack, within) / cell_)) + 1;
    int found = -1;
    double best = limit;
    for (int64_t r = 0; r <= reach; ++r) {
      if (static_cast<double>(r - 1) * cell_ >= best + slack) break;
      for (int64_t ix = px - r; ix <= px + r; ++ix)
        for (int64_t iy = py - r; iy <= py + r; ++iy) {
          if (std::max(std::abs(ix - px), std::abs(iy - py)) != r) continue;
          auto it = m_.find(cell_key(ix, iy));
          if (it == m_.end()) continue;
          for (int id : it->second) {
            const double d = dist(p, f[static_cast<size_t>(id)].p);
            if (d >= best + slack || d > within) continue;
            const double c = cost(id, d);
            if (c < best && ok(id)) best = c, found = id;
          }
        }
    }
    return found;
  }

 private:
  uint64_t key(P p) const { return cell_key(cell_of(p.x, cell_), cell_of(p.y, cell_)); }
  double cell_;
  std::unordered_map<uint64_t, std::vector<int>> m_;
};

// Carried down to a layer whose sparse region is `grid`'s: nodes outside it go, and edges
// that leave it are cut (the child a root to ground again).
void realign(Forest& f, const EdgeGrid& grid) {
  std::vector<char> keep(f.size());
  for (size_t i = 0; i < f.size(); ++i) keep[i] = grid.inside(to_pt(f[i].p));
  for (size_t i = 0; i < f.size(); ++i) {
    Node& n = f[i];
    if (!keep[i] || n.parent < 0) continue;
    const auto par = static_cast<size_t>(n.parent);
    if (!keep[par] || grid.crosses(to_pt(n.p), to_pt(f[par].p))) n.parent = -1;
  }
  compact(f, keep);
}

// A new root on the border at `b`, moved kNudge towards p (inside).
int add_root(Forest& f, P b, P p, double db) {
  const double t = db > 0 ? std::min(kNudge, 0.5 * db) / db : 0;
  f.push_back({{b.x + (p.x - b.x) * t, b.y + (p.y - b.y) * t}, -1});
  return static_cast<int>(f.size()) - 1;
}

// Whether node `a` lies in the tree under `root` (walking up from a).
bool under(const Forest& f, int a, int root) {
  for (int v = a; v >= 0; v = f[static_cast<size_t>(v)].parent)
    if (v == root) return true;
  return false;
}

// What a layer grows on: its sparse region (edges for crossings, border for nearest points).
struct LayerGround {
  const EdgeGrid& grid;
  const BorderIndex& border;
  double radius, wall;  // units: the supporting radius, the walls' (h·tan(angle))
};

// The cost of joining a new leaf or a root that left the border to node id at distance d,
// against the border's (its distance): as PrusaSlicer's lightning (Node::getWeightedDistance),
// a node with one to three edges counts kBoost radii nearer, so that leaves and roots join a
// tree a little further away rather than the walls, and trees grow long and branch.
constexpr double kBoost = 4;
// How far beyond the border's distance nodes are looked for: as far as the bonus reaches
// (kBoost radii), at most kReachCap. PrusaSlicer looks in the cells of its 4 mm node grid round
// the border's distance, 0 to 4 mm beyond it; 2.5 mm gives its plastic at 20 % on the bench's
// models (bench/bench_infill.sh). The reach must not shrink to a radius: at high densities (a
// radius of 0.5 mm at 95 %) the bonus then never counted, new leaves near the walls started
// trees of their own, short and pruned away within a few layers, and the infill's plastic fell
// above 65 % (tests/geometry/toolpath/lightning_test.cpp, "a dome's branch length").
constexpr double kReachCap = 2.5 * geo::kUnitsPerMm;
double reach(double radius) { return std::min(kBoost * radius, kReachCap); }
double join_cost(const Forest& f, const std::vector<int>& nkids, int id, double d, double radius) {
  const auto k = static_cast<size_t>(id);
  const int valence = (f[k].parent >= 0 ? 1 : 0) + nkids[k];
  return valence > 0 && valence < 4 ? d - kBoost * radius : d;
}

// Roots that no longer stand on the border: joined to another tree or to the border.
void reground(Forest& f, const LayerGround& L) {
  NodeGrid nodes(L.radius);
  std::vector<int> nkids(f.size(), 0);
  for (size_t i = 0; i < f.size(); ++i) {
    nodes.add(f, static_cast<int>(i));
    if (f[i].parent >= 0) ++nkids[static_cast<size_t>(f[i].parent)];
  }
  const size_t n = f.size();
  for (size_t i = 0; i < n; ++i) {
    if (f[i].parent >= 0) continue;
    const P p = f[i].p;
    P b{0, 0};
    double db = 0;
    if (!L.border.nearest(p, b, db) || db <= kGrounded) continue;
    int to = -1;
    if (db >= L.wall) {
      const int self = static_cast<int>(i);
      to = nodes.best(
          f, p, db, [&](int id, double d) { return join_cost(f, nkids, id, d, L.radius); },
          [&](int id) { return !under(f, id, self) && !L.grid.crosses(to_pt(p), to_pt(f[static_cast<size_t>(id)].p)); },
          kBoost * L.radius, db + reach(L.radius));
    }
    if (to < 0) {
      to = add_root(f, b, p, db);
      nkids.push_back(0);
    }
    f[i].parent = to;
    ++nkids[static_cast<size_t>(to)];
  }
}

// Points of `need` on a lattice of pitch g (bed-fixed), by scanlines.
struct Lattice {
  double g;
  int64_t x0 = 0, x1 = -1, y0 = 0, y1 = -1;  // the points' index range
  std::vector<P> pts;
  std::vector<char> held;
  std::unordered_map<uint64_t, int> at;

  Lattice(const geo::Rings& need, double pitch) : g(pitch) {
    const EdgeGrid grid(need);
    const geo::BBox2 b = bbox(need);
    if (b.empty()) return;
    const double lx = static_cast<double>(b.min_x) - 1e3, rx = static_cast<double>(b.max_x) + 1e3;
    for (int64_t iy = cell_of(static_cast<double>(b.min_y), g); iy <= cell_of(static_cast<double>(b.max_y), g); ++iy) {
      const double y = (static_cast<double>(iy) + 0.5) * g;
      const geo::Point a = to_pt({lx, y}), c = to_pt({rx, y});
      const auto hits = grid.hits(a, c);
      for (size_t h = 0; h + 1 < hits.size(); ++h) {
        const double t0 = hits[h].t, t1 = hits[h + 1].t;
        if (t1 - t0 < 1e-12) continue;
        const double xm = lx + 0.5 * (t0 + t1) * (rx - lx);
        if (!grid.inside(to_pt({xm, y}))) continue;
        const double xa = lx + t0 * (rx - lx), xb = lx + t1 * (rx - lx);
        for (int64_t ix = static_cast<int64_t>(std::ceil(xa / g - 0.5)); (static_cast<double>(ix) + 0.5) * g <= xb; ++ix)
          add(ix, iy);
      }
    }
  }
  void add(int64_t ix, int64_t iy) {
    if (!at.emplace(cell_key(ix, iy), static_cast<int>(pts.size())).second) return;
    pts.push_back({(static_cast<double>(ix) + 0.5) * g, (static_cast<double>(iy) + 0.5) * g});
    held.push_back(0);
    if (pts.size() == 1) x0 = x1 = ix, y0 = y1 = iy;
    x0 = std::min(x0, ix), x1 = std::max(x1, ix), y0 = std::min(y0, iy), y1 = std::max(y1, iy);
  }
  // Marks the points within r of segment ab as held.
  void hold(P a, P b, double r) {
    const int64_t ax = std::max(x0, cell_of(std::min(a.x, b.x) - r, g) - 1);
    const int64_t bx = std::min(x1, cell_of(std::max(a.x, b.x) + r, g) + 1);
    const int64_t ay = std::max(y0, cell_of(std::min(a.y, b.y) - r, g) - 1);
    const int64_t by = std::min(y1, cell_of(std::max(a.y, b.y) + r, g) + 1);
    for (int64_t ix = ax; ix <= bx; ++ix)
      for (int64_t iy = ay; iy <= by; ++iy) {
        auto it = at.find(cell_key(ix, iy));
        if (it == at.end()) continue;
        const auto k = static_cast<size_t>(it->second);
        if (!held[k] && dist(pts[k], nearest_on(a, b, pts[k])) <= r) held[k] = 1;
      }
  }
};

uint32_t mix(uint64_t v) {
  v ^= v >> 33;
  v *= 0xff51afd7ed558ccdULL;
  v ^= v >> 33;
  return static_cast<uint32_t>(v);
}

// New leaves for the points of `need`, as PrusaSlicer's lightning grows them: nearest the
// border first (in bands one radius wide, in a scattered order within a band), each point not
// yet within a radius of a leaf becomes one, holding the points within a radius of it; it joins
// the tree node or the border of least join_cost (the border's: its distance).
void grow(Forest& f, const geo::Rings& need, const LayerGround& L) {
  if (need.empty()) return;
  // A sixth of the radius (PrusaSlicer's distance field's cells) at every density: a floor
  // (0.2 mm) sampled the tops of high densities coarser than the radius they are held at, and
  // laid fewer leaves.
  Lattice lat(need, L.radius / 6);
  if (lat.pts.empty()) return;
  struct Todo {
    size_t k;
    P b;
    double db;
    int64_t band;
    uint32_t order;
  };
  std::vector<Todo> todo;
  for (size_t k = 0; k < lat.pts.size(); ++k) {
    if (lat.held[k]) continue;
    P b{0, 0};
    double db = 0;
    if (!L.border.nearest(lat.pts[k], b, db)) continue;
    const P q = lat.pts[k];
    todo.push_back({k, b, db, static_cast<int64_t>(db / L.radius), mix(cell_key(cell_of(q.x, lat.g), cell_of(q.y, lat.g)))});
  }
  std::sort(todo.begin(), todo.end(), [](const Todo& a, const Todo& b) {
    return a.band != b.band ? a.band < b.band : a.order != b.order ? a.order < b.order : a.k < b.k;
  });
  NodeGrid nodes(L.radius);
  std::vector<int> nkids(f.size(), 0);
  for (size_t i = 0; i < f.size(); ++i) {
    nodes.add(f, static_cast<int>(i));
    if (f[i].parent >= 0) ++nkids[static_cast<size_t>(f[i].parent)];
  }
  for (const Todo& t : todo) {
    if (lat.held[t.k]) continue;
    const P p = lat.pts[t.k];
    if (t.db <= kGrounded) {
      lat.held[t.k] = 1;
      continue;
    }
    // Nodes up to reach() beyond the border's distance.
    int to = nodes.best(
        f, p, t.db, [&](int id, double d) { return join_cost(f, nkids, id, d, L.radius); },
        [&](int id) { return !L.grid.crosses(to_pt(p), to_pt(f[static_cast<size_t>(id)].p)); }, kBoost * L.radius,
        t.db + reach(L.radius));
    if (to < 0) {
      to = add_root(f, t.b, p, t.db);
      nkids.push_back(0);
      nodes.add(f, to);
    }
    f.push_back({p, to});
    nkids.push_back(0);
    ++nkids[static_cast<size_t>(to)];
    nodes.add(f, static_cast<int>(f.size()) - 1);
    lat.hold(p, p, L.radius);
    lat.held[t.k] = 1;
  }
}

// Roots with nothing to hold go.
void drop_lone_roots(Forest& f) {
  std::vector<char> keep(f.size(), 0);
  for (size_t i = 0; i < f.size(); ++i)
    if (f[i].parent >= 0) keep[i] = 1, keep[static_cast<size_t>(f[i].parent)] = 1;
  compact(f, keep);
}

// Nodes in an order where every parent comes before its children.
std::vector<int> top_down(const Forest& f, const std::vector<std::vector<int>>& kids) {
  std::vector<int> order;
  order.reserve(f.size());
  for (size_t i = 0; i < f.size(); ++i)
    if (f[i].parent < 0) order.push_back(static_cast<int>(i));
  for (size_t k = 0; k < order.size(); ++k)
    for (int c : kids[static_cast<size_t>(order[k])]) order.push_back(c);
  return order;
}

// Every leaf shortened by `length` (a leaf whose edge is shorter goes, and its parent is
// shortened by the rest once all its children are gone); trees left without an edge go.
void prune(Forest& f, double length) {
  if (length <= 0 || f.empty()) return;
  const auto kids = children_of(f);
  const std::vector<int> order = top_down(f, kids);
  std::vector<double> pruned(f.size(), 0);  // how far the node's subtree was pruned
  std::vector<char> keep(f.size(), 1);
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    const auto v = static_cast<size_t>(*it);
    double most = 0;
    for (int c : kids[v]) {
      const auto k = static_cast<size_t>(c);
      if (!keep[k]) continue;
      const double dc = pruned[k];
      if (dc >= length) {
        most = std::max(most, dc);
        continue;
      }
      const double len = dist(f[v].p, f[k].p);
      if (dc + len <= length) {
        keep[k] = 0;  // its children are gone already
        most = std::max(most, dc + len);
      } else {
        const double t = (length - dc) / len;
        f[k].p = {f[k].p.x + (f[v].p.x - f[k].p.x) * t, f[k].p.y + (f[v].p.y - f[k].p.y) * t};
        most = length;
      }
    }
    pruned[v] = most;
  }
  compact(f, keep);
  drop_lone_roots(f);
}

// Chains of nodes with one child each pulled towards the straight line between the chain's
// ends (each node by at most `step`, to its place in proportion to the length along the
// chain), then nodes left on the line of their neighbours, or on their parent, removed.
void straighten(Forest& f, double step) {
  if (f.empty()) return;
  const auto kids = children_of(f);
  for (size_t s = 0; s < f.size(); ++s) {
    if (f[s].parent >= 0 && kids[s].size() == 1) continue;  // inside a chain
    for (int c : kids[s]) {
      std::vector<size_t> chain{s};
      auto v = static_cast<size_t>(c);
      while (kids[v].size() == 1) chain.push_back(v), v = static_cast<size_t>(kids[v][0]);
      chain.push_back(v);
      if (chain.size() < 3) continue;
      std::vector<double> along(chain.size(), 0);
      for (size_t k = 1; k < chain.size(); ++k) along[k] = along[k - 1] + dist(f[chain[k - 1]].p, f[chain[k]].p);
      const double total = along.back();
      if (total <= 0) continue;
      const P a = f[chain.front()].p, b = f[chain.back()].p;
      for (size_t k = 1; k + 1 < chain.size(); ++k) {
        const double t = along[k] / total;
        const P target{a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t};
        P& p = f[chain[k]].p;
        const double d = dist(p, target);
        const double u = d <= step ? 1.0 : step / d;
        p = {p.x + (target.x - p.x) * u, p.y + (target.y - p.y) * u};
      }
    }
  }
  // Removal: a node with one child whose position is within kCollinear of the segment from its
  // parent to its child, or any node within kMerged of its parent (its children move up).
  std::vector<char> keep(f.size(), 1);
  const auto order = top_down(f, kids);
  std::vector<int> up(f.size());  // the kept node standing for each node
  for (size_t i = 0; i < f.size(); ++i) up[i] = static_cast<int>(i);
  for (int vi : order) {
    const auto v = static_cast<size_t>(vi);
    if (f[v].parent < 0) continue;
    f[v].parent = up[static_cast<size_t>(f[v].parent)];
    const P par = f[static_cast<size_t>(f[v].parent)].p;
    bool drop = dist(f[v].p, par) < kMerged;
    if (!drop && kids[v].size() == 1) {
      const P child = f[static_cast<size_t>(kids[v][0])].p;
      drop = dist(f[v].p, nearest_on(par, child, f[v].p)) < kCollinear;
    }
    if (drop) keep[v] = 0, up[v] = f[v].parent;
  }
  compact(f, keep);
}

// The forest's edges as open polylines: from each root, a node's first child continuing its
// polyline, each other child starting one at the node.
geo::Rings polylines(const Forest& f) {
  geo::Rings out;
  const auto kids = children_of(f);
  std::vector<std::pair<size_t, size_t>> stack;  // (node, the polyline it ends)
  for (size_t r = 0; r < f.size(); ++r) {
    if (f[r].parent >= 0 || kids[r].empty()) continue;
    out.push_back({to_pt(f[r].p)});
    stack.push_back({r, out.size() - 1});
    while (!stack.empty()) {
      const auto [v, line] = stack.back();
      stack.pop_back();
      const auto& ks = kids[v];
      for (size_t j = 1; j < ks.size(); ++j) {
        out.push_back({to_pt(f[v].p)});
        const auto k = static_cast<size_t>(ks[j]);
        const geo::Point q = to_pt(f[k].p);
        if (q != out.back().back()) out.back().push_back(q);
        stack.push_back({k, out.size() - 1});
      }
      if (!ks.empty()) {
        const auto k = static_cast<size_t>(ks[0]);
        const geo::Point q = to_pt(f[k].p);
        if (q != out[line].back()) out[line].push_back(q);
        stack.push_back({k, line});
      }
    }
  }
  std::erase_if(out, [](const geo::Ring& l) { return l.size() < 2; });
  return out;
}

double tan_of(double deg) { return std::tan(std::clamp(deg, 0.0, 89.0) * std::numbers::pi / 180); }

}  // namespace

LightningAreas lightning_areas(std::span<const geo::Layer> layers, const LightningSpec& spec) {
  const int n = static_cast<int>(layers.size()), T = std::max(spec.top_layers, 0);
  LightningAreas a;
  a.outline.resize(layers.size());
  a.need.resize(layers.size());
  std::vector<geo::Rings> mat(layers.size());
  for (int i = 0; i < n; ++i) mat[static_cast<size_t>(i)] = union_of(material(layers[static_cast<size_t>(i)]));
  const double inset = std::isfinite(spec.inset_mm) ? std::max(spec.inset_mm, 0.0) : 0.0;
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<size_t>(i);
    if (mat[k].empty() || i + T >= n) continue;
    geo::Rings o = inset > 0 ? offset(mat[k], -inset) : mat[k];
    for (int j = i + 1; j <= i + T && !o.empty(); ++j) o = intersection(o, mat[static_cast<size_t>(j)]);
    a.outline[k] = std::move(o);
  }
  const double t = std::isfinite(spec.angle_deg) ? tan_of(spec.angle_deg) : 0.0;
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<size_t>(i);
    if (a.outline[k].empty()) continue;
    const geo::Rings above = i + 1 < n ? a.outline[k + 1] : geo::Rings{};
    if (difference(a.outline[k], above).empty()) continue;
    a.need[k] = difference(offset(a.outline[k], -layers[k].height() * t), above);
  }
  return a;
}

std::vector<geo::Rings> lightning_trees(std::span<const geo::Layer> layers, const LightningSpec& spec) {
  std::vector<geo::Rings> out(layers.size());
  if (!(spec.radius_mm > 0) || !std::isfinite(spec.radius_mm) || !std::isfinite(spec.angle_deg)) return out;
  const LightningAreas areas = lightning_areas(layers, spec);
  const double radius = spec.radius_mm * geo::kUnitsPerMm, t = tan_of(spec.angle_deg);
  Forest f;
  for (size_t i = layers.size(); i-- > 0;) {
    if (areas.outline[i].empty()) {
      f.clear();
      continue;
    }
    const EdgeGrid grid(areas.outline[i]);
    const BorderIndex border(areas.outline[i], radius);
    const LayerGround L{grid, border, radius, layers[i].height() * t * geo::kUnitsPerMm};
    realign(f, grid);
    reground(f, L);
    grow(f, areas.need[i], L);
    drop_lone_roots(f);
    out[i] = polylines(f);
    if (i > 0) {
      const double step = layers[i].height() * t * geo::kUnitsPerMm;
      prune(f, step);
      straighten(f, step);
    }
  }
  return out;
}

const geo::Rings& LightningCache::lines(std::span<const geo::Layer> layers, int index,
                                        const LightningSpec& spec) const {
  static const geo::Rings kNone;
  const auto um = [](double mm) { return std::isfinite(mm) ? std::llround(mm * 1000) : -1LL; };
  const auto key = std::make_tuple(spec.top_layers, um(spec.radius_mm), um(spec.inset_mm), um(spec.angle_deg));
  std::lock_guard<std::mutex> lock(mu_);
  auto it = by_spec_.find(key);
  if (it == by_spec_.end()) it = by_spec_.emplace(key, lightning_trees(layers, spec)).first;
  const auto& v = it->second;
  return index >= 0 && static_cast<size_t>(index) < v.size() ? v[static_cast<size_t>(index)] : kNone;
}

}  // namespace tranche::toolpath
