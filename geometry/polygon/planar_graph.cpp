#include "geometry/polygon/planar_graph.h"

#include <algorithm>

#include "geometry/polygon/exact.h"

namespace tranche::geo {

int PlanarGraph::vertex_id(const Point& p) {
  auto [it, inserted] = ids_.try_emplace(p, static_cast<int>(points_.size()));
  if (inserted) {
    points_.push_back(p);
    spokes_.emplace_back();
    out_.emplace_back();
    in_.emplace_back();
  }
  return it->second;
}

int PlanarGraph::find_vertex(const Point& p) const {
  auto it = ids_.find(p);
  return it == ids_.end() ? -1 : it->second;
}

void PlanarGraph::add_spoke(int v, Spoke s) {
  auto& sp = spokes_[v];
  const Point& o = points_[v];
  const Point& q = points_[s.other];
  auto pos = std::upper_bound(sp.begin(), sp.end(), q, [&](const Point& a, const Spoke& b) {
    return exact::angle_less(o, a, points_[b.other]);
  });
  sp.insert(pos, s);
}

void PlanarGraph::add_ring(const Ring& ring) {
  std::vector<int> ids;
  ids.reserve(ring.size());
  for (const Point& p : ring) {
    const int v = vertex_id(p);
    if (ids.empty() || ids.back() != v) ids.push_back(v);
  }
  while (ids.size() > 1 && ids.front() == ids.back()) ids.pop_back();
  if (ids.size() < 2) return;
  for (size_t i = 0; i < ids.size(); ++i) {
    const int u = ids[i], v = ids[(i + 1) % ids.size()];
    const int h = static_cast<int>(half_edges_.size());
    half_edges_.push_back({u, v, EdgeKind::Real, -1, false});
    add_spoke(u, {v, h, true});
    add_spoke(v, {u, h, false});
    out_[u].push_back(h);
    in_[v].push_back(h);
  }
}

int PlanarGraph::add_chord(int u, int v) {
  const int h = static_cast<int>(half_edges_.size());
  half_edges_.push_back({u, v, EdgeKind::Artificial, h + 1, false});
  half_edges_.push_back({v, u, EdgeKind::Artificial, h, false});
  add_spoke(u, {v, h, true});
  add_spoke(v, {u, h, false});
  add_spoke(v, {u, h + 1, true});
  add_spoke(u, {v, h + 1, false});
  return h;
}

void PlanarGraph::set_removed(int chord, bool removed) {
  half_edges_[chord].removed = removed;
  half_edges_[half_edges_[chord].twin].removed = removed;
}

int PlanarGraph::next(int h) const {
  const HalfEdge& e = half_edges_[h];
  const auto& sp = spokes_[e.to];
  const int n = static_cast<int>(sp.size());
  int at = -1;
  for (int i = 0; i < n; ++i) {
    if (sp[i].he == h && !sp[i].out) at = i;
  }
  if (at < 0) return -1;
  // Clockwise from the direction back to e.from: the first outgoing edge is the tightest left turn.
  for (int k = 1; k < n; ++k) {
    const Spoke& s = sp[(at - k + n) % n];
    if (!s.out || half_edges_[s.he].removed || s.other == e.from) continue;
    return s.he;
  }
  return -1;
}

std::vector<int> PlanarGraph::face(int h) const {
  std::vector<int> out;
  int e = h;
  do {
    out.push_back(e);
    e = next(e);
    if (e < 0 || out.size() > half_edges_.size()) return {};
  } while (e != h);
  return out;
}

bool PlanarGraph::faces(std::vector<std::vector<int>>& out) const {
  std::vector<char> seen(half_edges_.size(), 0);
  for (int h = 0; h < half_edge_count(); ++h) {
    if (seen[h] || half_edges_[h].removed) continue;
    std::vector<int> f = face(h);
    if (f.empty()) return false;
    for (int e : f) {
      if (seen[e]) return false;  // two faces claim one half-edge: the walk is inconsistent
      seen[e] = 1;
    }
    out.push_back(std::move(f));
  }
  return true;
}

bool PlanarGraph::boundary_alternates() const {
  for (const auto& sp : spokes_) {
    int last = -1, first = -1;
    for (const Spoke& s : sp) {
      if (half_edges_[s.he].kind != EdgeKind::Real) continue;
      if (s.out == last) return false;
      if (first < 0) first = s.out;
      last = s.out;
    }
    if (first >= 0 && first == last) return false;
  }
  return true;
}

bool PlanarGraph::points_into_material(int v, const Point& q) const {
  const Point& o = points_[v];
  if (q == o) return false;
  const auto& sp = spokes_[v];
  // Last boundary spoke at or clockwise of q's direction.
  int best = -1;
  for (int i = 0; i < static_cast<int>(sp.size()); ++i) {
    if (half_edges_[sp[i].he].kind != EdgeKind::Real) continue;
    const Point& d = points_[sp[i].other];
    if (exact::orientation(o, d, q) == 0 && exact::angle_less(o, d, q) == exact::angle_less(o, q, d)) {
      return false;  // same direction as an edge
    }
    if (exact::angle_less(o, d, q)) best = i;
  }
  if (best < 0) {  // wrap around: the last boundary spoke overall
    for (int i = static_cast<int>(sp.size()) - 1; i >= 0 && best < 0; --i) {
      if (half_edges_[sp[i].he].kind == EdgeKind::Real) best = i;
    }
  }
  return best >= 0 && sp[best].out;
}

}  // namespace tranche::geo
