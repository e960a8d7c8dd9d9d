#include "geometry/polygon/planar_graph.h"

#include <algorithm>

#include "geometry/polygon/exact.h"

namespace tranche::geo {
PlanarGraph::PlanarGraph(const Rings& rings, const FillDirection* sweep) {
  if (sweep) sweep_ = *sweep;
  // One sort of all points gives the vertex ids: equal keys are the same point.
  size_t n = 0;
  for (const Ring& r : rings) n += r.size();
  std::vector<std::pair<Key, uint32_t>> all;
  all.reserve(n);
  for (const Ring& r : rings) {
    for (const Point& p : r) all.emplace_back(key(p), static_cast<uint32_t>(all.size()));
  }
  std::sort(all.begin(), all.end());
  std::vector<int> id(n);
  points_.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    if (i == 0 || all[i].first != all[i - 1].first) points_.push_back(Point());
    id[all[i].second] = static_cast<int>(points_.size()) - 1;
  }
  size_t k = 0;
  for (const Ring& r : rings) {
    for (const Point& p : r) points_[id[k++]] = p;
  }
  half_edges_.reserve(n);
  k = 0;
  for (const Ring& ring : rings) {
    std::vector<int> ids;
    ids.reserve(ring.size());
    for (size_t i = 0; i < ring.size(); ++i) {
      const int v = id[k++];
      if (ids.empty() || ids.back() != v) ids.push_back(v);
    }
    while (ids.size() > 1 && ids.front() == ids.back()) ids.pop_back();
    if (ids.size() >= 2) {
      for (size_t i = 0; i < ids.size(); ++i) {
        half_edges_.push_back({ids[i], ids[(i + 1) % ids.size()], EdgeKind::Real, -1, false});
      }
    }
    rings_.push_back(std::move(ids));
  }
  freeze();
}

int PlanarGraph::find_vertex(const Point& p) const {
  const Key k = key(p);
  auto it = std::lower_bound(points_.begin(), points_.end(), k,
                             [&](const Point& a, const Key& b) { return key(a) < b; });
  return it != points_.end() && *it == p ? static_cast<int>(it - points_.begin()) : -1;
}

int PlanarGraph::add_chord(int u, int v) {
  const int h = static_cast<int>(half_edges_.size());
  half_edges_.push_back({u, v, EdgeKind::Artificial, h + 1, false});
  half_edges_.push_back({v, u, EdgeKind::Artificial, h, false});
  return h;
}

void PlanarGraph::freeze() {
  const int nv = vertex_count();
  first_.assign(nv + 1, 0);
  for (const HalfEdge& e : half_edges_) {
    ++first_[e.from + 1];
    ++first_[e.to + 1];
  }
  for (int v = 0; v < nv; ++v) first_[v + 1] += first_[v];
  spokes_.resize(first_[nv]);
  std::vector<int> fill(first_.begin(), first_.end() - 1);
  for (int h = 0; h < half_edge_count(); ++h) {
    const HalfEdge& e = half_edges_[h];
    spokes_[fill[e.from]++] = {e.to, h, true};
    spokes_[fill[e.to]++] = {e.from, h, false};
  }
  arrival_.assign(half_edges_.size(), -1);
  for (int v = 0; v < nv; ++v) {
    const Point& o = points_[v];
    auto b = spokes_.begin() + first_[v], e = spokes_.begin() + first_[v + 1];
    if (e - b > 2) {
      std::sort(b, e, [&](const Spoke& x, const Spoke& y) {
        return exact::angle_less(o, points_[x.other], points_[y.other]);
      });
    }
    for (int i = first_[v]; i < first_[v + 1]; ++i) {
      if (!spokes_[i].out) arrival_[spokes_[i].he] = i;
    }
  }
}

void PlanarGraph::set_removed(int chord, bool removed) {
  half_edges_[chord].removed = removed;
  half_edges_[half_edges_[chord].twin].removed = removed;
}

int PlanarGraph::next(int h) const {
  const HalfEdge& e = half_edges_[h];
  const int at = arrival_[h];
  if (at < 0) return -1;
  const int b = first_[e.to], n = first_[e.to + 1] - b;
  // Clockwise from the direction back to e.from: the first edge leaving is the tightest left turn.
  for (int k = 1; k < n; ++k) {
    const Spoke& s = spokes_[b + (at - b - k + n) % n];
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
  for (int v = 0; v < vertex_count(); ++v) {
    int last = -1, first = -1;
    for (const Spoke& s : spokes(v)) {
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
  // The nearest boundary spoke clockwise of q's direction must leave v (material on its left).
  const Spoke* best = nullptr;
  const Spoke* last = nullptr;
  for (const Spoke& s : spokes(v)) {
    if (half_edges_[s.he].kind != EdgeKind::Real) continue;
    const Point& d = points_[s.other];
    if (exact::orientation(o, d, q) == 0 && !exact::angle_less(o, d, q) && !exact::angle_less(o, q, d)) {
      return false;  // same direction as an edge
    }
    if (exact::angle_less(o, d, q)) best = &s;
    last = &s;
  }
  if (best == nullptr) best = last;  // wrap around
  return best != nullptr && best->out;
}

}  // namespace tranche::geo
