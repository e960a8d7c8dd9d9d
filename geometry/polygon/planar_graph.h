// Boundary edges (material on their left) plus chords (cuts through material, one half-edge each
// way) as a planar graph, and the faces they bound: the regions of material between them.
// Coincident points share one vertex, so rings that touch at a point are handled at that point:
// walking a face, each arrival turns as tightly as possible to the left, which keeps regions that
// meet only at a point apart.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "geometry/core/geom.h"
#include "geometry/core/layer.h"
#include "geometry/polygon/monotone.h"

namespace tranche::geo {

class PlanarGraph {
 public:
  struct HalfEdge {
    int from = -1, to = -1;
    EdgeKind kind = EdgeKind::Real;
    int twin = -1;  // chords only
    bool removed = false;
  };
  // An edge end at a vertex, kept in counter-clockwise order of direction around the vertex.
  struct Spoke {
    int other;  // the vertex at the far end
    int he;     // half-edge id
    bool out;   // the half-edge leaves this vertex
  };

  // The edges of closed rings (last point != first; consecutive duplicates are skipped). For the
  // faces to mean anything no two edges may cross or overlap and no vertex may lie inside another
  // edge (resolve.h guarantees this for islands). Vertex ids follow the sweep order of `sweep`
  // when given (vertex 0 is swept first), else the (x, y) order.
  explicit PlanarGraph(const Rings& rings, const FillDirection* sweep = nullptr);
  PlanarGraph() = default;

  // Adds a chord between two vertices; returns the half-edge u -> v (its twin is v -> u). Chords
  // take part in the walks once freeze() has run again.
  int add_chord(int u, int v);
  void freeze();                              // orders the spokes; needed after add_chord
  void set_removed(int chord, bool removed);  // a chord half-edge and its twin

  int vertex_count() const { return static_cast<int>(points_.size()); }
  int find_vertex(const Point& p) const;  // -1 when absent
  const Point& point(int v) const { return points_[v]; }
  const HalfEdge& half_edge(int h) const { return half_edges_[h]; }
  int half_edge_count() const { return static_cast<int>(half_edges_.size()); }
  std::span<const Spoke> spokes(int v) const {
    return {spokes_.data() + first_[v], static_cast<size_t>(first_[v + 1] - first_[v])};
  }
  // Vertex ids of each ring given to the constructor, in ring order (duplicates skipped).
  const std::vector<std::vector<int>>& ring_vertices() const { return rings_; }

  // The half-edge that follows h along its face (-1 if the graph is inconsistent there).
  int next(int h) const;
  // Half-edges of the face through h, in order; empty if the walk does not close.
  std::vector<int> face(int h) const;
  // Every face, each as its half-edges in order; false if some walk did not close.
  bool faces(std::vector<std::vector<int>>& out) const;
  // True when around every vertex the boundary edges alternate leaving / entering: the rings
  // may touch at vertices but never cross there.
  bool boundary_alternates() const;
  // Whether the direction from vertex v toward q lies strictly inside material at v, judged by
  // the boundary edges alone (a direction along an edge is not inside).
  bool points_into_material(int v, const Point& q) const;

 private:
  using Key = std::pair<int64_t, int64_t>;
  Key key(const Point& p) const { return sweep_ ? Key{-sweep_->across(p), sweep_->along(p)} : Key{p.X, p.Y}; }
  std::optional<FillDirection> sweep_;
  std::vector<Point> points_;  // ascending key: find_vertex is a binary search
  std::vector<HalfEdge> half_edges_;
  std::vector<std::vector<int>> rings_;
  std::vector<int> first_;  // spokes of vertex v: spokes_[first_[v] .. first_[v + 1])
  std::vector<Spoke> spokes_;
  std::vector<int> arrival_;  // index in spokes_ of each half-edge's end at its `to` vertex
};

}  // namespace tranche::geo
