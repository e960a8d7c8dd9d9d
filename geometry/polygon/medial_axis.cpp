#include "geometry/polygon/medial_axis.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include <boost/polygon/point_data.hpp>
#include <boost/polygon/segment_data.hpp>
#include <boost/polygon/voronoi.hpp>

namespace tranche::geo {

namespace {

namespace bp = boost::polygon;
using Diagram = bp::voronoi_diagram<double>;
using Segment = bp::segment_data<int32_t>;
using Vertex = Diagram::vertex_type;
using Edge = Diagram::edge_type;
using Cell = Diagram::cell_type;

struct P2 {
  double x = 0, y = 0;
};

// The region's border as segments in a frame shifted to the region's corner (Boost's builder
// wants 32-bit coordinates; nm within ±1073 mm of that corner fit).
struct Input {
  std::vector<Segment> segs;
  coord_t ox = 0, oy = 0;
  Point to_point(const P2& p) const { return Point(ox + std::llround(p.x), oy + std::llround(p.y)); }
};

bool make_input(const Rings& region, Input& in) {
  BBox2 b;
  for (const auto& r : region)
    for (const auto& p : r) b.add(p);
  if (b.empty()) return false;
  constexpr coord_t kMax = std::numeric_limits<int32_t>::max() / 2;
  if (b.max_x - b.min_x > kMax || b.max_y - b.min_y > kMax) return false;
  in.ox = b.min_x;
  in.oy = b.min_y;
  for (const auto& r : region) {
    if (r.size() < 3) continue;
    for (size_t i = 0; i < r.size(); ++i) {
      const Point& a = r[i];
      const Point& c = r[(i + 1) % r.size()];
      if (a == c) continue;
      in.segs.emplace_back(bp::point_data<int32_t>(static_cast<int32_t>(a.X - in.ox), static_cast<int32_t>(a.Y - in.oy)),
                           bp::point_data<int32_t>(static_cast<int32_t>(c.X - in.ox), static_cast<int32_t>(c.Y - in.oy)));
    }
  }
  return in.segs.size() >= 3;
}

P2 pt(const bp::point_data<int32_t>& p) { return {double(p.x()), double(p.y())}; }
P2 pt(const Vertex& v) { return {v.x(), v.y()}; }

// The site a cell belongs to: a whole segment, or one of its end points.
P2 cell_point(const Cell& c, const Input& in) {
  const Segment& s = in.segs[c.source_index()];
  return c.source_category() == bp::SOURCE_CATEGORY_SEGMENT_START_POINT ? pt(s.low()) : pt(s.high());
}

double dist_to_segment(const P2& p, const P2& a, const P2& b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

// Distance from `p` (a point of the cell's boundary) to the cell's site, in units.
double site_dist(const Cell& c, const Input& in, const P2& p) {
  if (c.contains_segment()) {
    const Segment& s = in.segs[c.source_index()];
    return dist_to_segment(p, pt(s.low()), pt(s.high()));
  }
  const P2 q = cell_point(c, in);
  return std::hypot(p.x - q.x, p.y - q.y);
}

// Signed distance of `p` to the left of segment `s` (the region lies on the left of its border).
double left_of(const Segment& s, const P2& p) {
  const P2 a = pt(s.low()), b = pt(s.high());
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double l = std::hypot(dx, dy);
  return l > 0 ? (dx * (p.y - a.y) - dy * (p.x - a.x)) / l : 0;
}

bool inside_region(const Rings& region, const Input& in, const P2& p) {
  const Point q = in.to_point(p);
  int winding = 0;
  for (const auto& r : region) {
    if (r.size() < 3) continue;
    const int at = ClipperLib::PointInPolygon(q, r);
    if (at == -1) return true;  // on the border
    if (at != 0) winding += ClipperLib::Orientation(r) ? 1 : -1;
  }
  return winding > 0;
}

// Whether a (finite, primary) edge lies inside the region: on the left of the segment whose cell
// it bounds, or (between two point sites) by a winding test of its middle.
bool edge_inside(const Edge& e, const Rings& region, const Input& in) {
  const P2 a = pt(*e.vertex0()), b = pt(*e.vertex1());
  for (const Cell* c : {e.cell(), e.twin()->cell()})
    if (c->contains_segment()) {
      const Segment& s = in.segs[c->source_index()];
      return left_of(s, a) + left_of(s, b) > 0;
    }
  return inside_region(region, in, {(a.x + b.x) / 2, (a.y + b.y) / 2});
}

// Points of an edge from vertex0 to vertex1 with their distances to the border: its ends, and
// for a curved edge (a parabola between a corner and a segment) samples every `step` units.
void edge_points(const Edge& e, const Input& in, double step, std::vector<P2>& pts, std::vector<double>& rad) {
  const Cell& c = *e.cell();
  const P2 a = pt(*e.vertex0()), b = pt(*e.vertex1());
  pts.assign({a});
  rad.assign({site_dist(c, in, a)});
  if (e.is_curved()) {
    const Cell& pc = c.contains_point() ? c : *e.twin()->cell();
    const Cell& sc = c.contains_point() ? *e.twin()->cell() : c;
    const P2 f = cell_point(pc, in);
    const Segment& s = in.segs[sc.source_index()];
    const P2 s0 = pt(s.low()), s1 = pt(s.high());
    const double len = std::hypot(s1.x - s0.x, s1.y - s0.y);
    if (len > 0) {
      const P2 u{(s1.x - s0.x) / len, (s1.y - s0.y) / len}, n{-u.y, u.x};
      auto along = [&](const P2& p) { return (p.x - s0.x) * u.x + (p.y - s0.y) * u.y; };
      const double tf = along(f), yf = (f.x - s0.x) * n.x + (f.y - s0.y) * n.y;
      const double ta = along(a), tb = along(b);
      const int k = static_cast<int>(std::ceil(std::abs(tb - ta) / step));
      if (std::abs(yf) > 1e-9 && k > 1 && k < 100000)
        for (int i = 1; i < k; ++i) {
          const double t = ta + (tb - ta) * i / k;
          const double y = ((t - tf) * (t - tf) + yf * yf) / (2 * yf);
          const P2 p{s0.x + u.x * t + n.x * y, s0.y + u.y * t + n.y * y};
          pts.push_back(p);
          rad.push_back(std::hypot(p.x - f.x, p.y - f.y));
        }
    }
  }
  pts.push_back(b);
  rad.push_back(site_dist(c, in, b));
}

struct GEdge {
  int a = 0, b = 0;  // nodes
  std::vector<P2> pts;  // from a to b
  std::vector<double> rad;
  double length = 0;
  bool alive = true;
};

struct Graph {
  std::vector<double> node_r;
  std::vector<std::vector<int>> adj;  // edge indices per node
  std::vector<GEdge> edges;

  int degree(int n) const {
    int d = 0;
    for (int e : adj[static_cast<size_t>(n)]) d += edges[static_cast<size_t>(e)].alive ? 1 : 0;
    return d;
  }
  int other(int e, int n) const {
    const GEdge& g = edges[static_cast<size_t>(e)];
    return g.a == n ? g.b : g.a;
  }
  int next_edge(int n, int from) const {
    for (int e : adj[static_cast<size_t>(n)])
      if (e != from && edges[static_cast<size_t>(e)].alive) return e;
    return -1;
  }
};

// Prunes the branches that run from a junction into a corner of the border (see AxisOptions).
// The branches of one round are chosen before any is removed, so that the corners of a bar's
// end are both pruned whichever is seen first.
void prune_corners(Graph& g, double factor) {
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<int> doomed;
    for (int n = 0; n < static_cast<int>(g.adj.size()); ++n) {
      if (g.degree(n) != 1) continue;
      std::vector<int> walk;
      double len = 0;
      int cur = n, e = g.next_edge(n, -1);
      while (e >= 0) {
        walk.push_back(e);
        len += g.edges[static_cast<size_t>(e)].length;
        cur = g.other(e, cur);
        if (g.degree(cur) != 2 || cur == n) break;
        e = g.next_edge(cur, e);
      }
      if (g.degree(cur) < 3) continue;  // the whole component is one chain: keep it
      if (len + g.node_r[static_cast<size_t>(n)] >= factor * g.node_r[static_cast<size_t>(cur)]) continue;
      doomed.insert(doomed.end(), walk.begin(), walk.end());
    }
    for (int w : doomed) {
      changed = changed || g.edges[static_cast<size_t>(w)].alive;
      g.edges[static_cast<size_t>(w)].alive = false;
    }
  }
}

void append(AxisPath& out, const Input& in, const GEdge& e, bool forward, double units_per_mm) {
  const size_t n = e.pts.size();
  for (size_t k = 0; k < n; ++k) {
    const size_t i = forward ? k : n - 1 - k;
    const Point p = in.to_point(e.pts[i]);
    if (!out.pts.empty() && out.pts.back() == p) continue;
    out.pts.push_back(p);
    out.radius_mm.push_back(e.rad[i] / units_per_mm);
  }
}

std::vector<AxisPath> chains(Graph& g, const Input& in) {
  std::vector<AxisPath> out;
  std::vector<char> used(g.edges.size(), 0);
  auto walk_from = [&](int start, int e, bool closed) {
    AxisPath path;
    path.closed = closed;
    int cur = start;
    while (e >= 0 && !used[static_cast<size_t>(e)]) {
      used[static_cast<size_t>(e)] = 1;
      const GEdge& ge = g.edges[static_cast<size_t>(e)];
      append(path, in, ge, ge.a == cur, kUnitsPerMm);
      cur = g.other(e, cur);
      if (g.degree(cur) != 2) break;
      e = g.next_edge(cur, e);
    }
    if (!closed) {
      path.free_start = g.degree(start) == 1;
      path.free_end = g.degree(cur) == 1;
    }
    if (closed && path.pts.size() > 1 && path.pts.front() != path.pts.back()) {
      path.pts.push_back(path.pts.front());
      path.radius_mm.push_back(path.radius_mm.front());
    }
    if (path.pts.size() >= 2) out.push_back(std::move(path));
  };
  for (int n = 0; n < static_cast<int>(g.adj.size()); ++n) {
    if (g.degree(n) == 2) continue;
    for (int e : g.adj[static_cast<size_t>(n)])
      if (g.edges[static_cast<size_t>(e)].alive && !used[static_cast<size_t>(e)]) walk_from(n, e, false);
  }
  for (int e = 0; e < static_cast<int>(g.edges.size()); ++e)
    if (g.edges[static_cast<size_t>(e)].alive && !used[static_cast<size_t>(e)])
      walk_from(g.edges[static_cast<size_t>(e)].a, e, true);
  return out;
}

}  // namespace

std::vector<AxisPath> medial_axis(const Rings& region, const AxisOptions& opt) {
  Input in;
  if (!make_input(region, in)) return {};
  Diagram vd;
  bp::construct_voronoi(in.segs.begin(), in.segs.end(), &vd);
  Graph g;
  std::unordered_map<const Vertex*, int> node_of;
  auto node = [&](const Vertex* v, double r) {
    auto [it, added] = node_of.emplace(v, static_cast<int>(g.adj.size()));
    if (added) {
      g.adj.emplace_back();
      g.node_r.push_back(r);
    }
    return it->second;
  };
  const double step = std::max(opt.sample_mm, 1e-3) * kUnitsPerMm;
  std::vector<P2> pts;
  std::vector<double> rad;
  for (const Edge& e : vd.edges()) {
    if (!e.is_primary() || !e.is_finite() || &e > e.twin()) continue;
    if (!edge_inside(e, region, in)) continue;
    edge_points(e, in, step, pts, rad);
    bool finite = true;
    for (size_t i = 0; i < pts.size(); ++i)
      finite = finite && std::isfinite(pts[i].x) && std::isfinite(pts[i].y) && std::isfinite(rad[i]);
    if (!finite) continue;
    GEdge ge;
    ge.a = node(e.vertex0(), rad.front());
    ge.b = node(e.vertex1(), rad.back());
    for (size_t i = 1; i < pts.size(); ++i) ge.length += std::hypot(pts[i].x - pts[i - 1].x, pts[i].y - pts[i - 1].y);
    ge.pts = pts;
    ge.rad = rad;
    const int id = static_cast<int>(g.edges.size());
    g.adj[static_cast<size_t>(ge.a)].push_back(id);
    if (ge.b != ge.a) g.adj[static_cast<size_t>(ge.b)].push_back(id);
    g.edges.push_back(std::move(ge));
  }
  prune_corners(g, opt.corner_prune);
  return chains(g, in);
}

}  // namespace tranche::geo
