// Boundary edges (material on their left) plus chords (cuts through material, one half-edge each
// way) as a planar graph, and the faces they bound. Coincident points share one vertex, so rings
// that touch at a point are handled at that point: walking a face, each arrival turns as tightly
// as possible to the left, which keeps regions that meet only at a point apart.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "geometry/core/geom.h"
#include "geometry/core/layer.h"

namespace tranche::geo {

class PlanarGraph {
 public:
  struct HalfEdge {
    int from = -1, to = -1;
    EdgeKind kind = EdgeKind::Real;
    int twin = -1;  // chords only
    bool removed = false;
  };

  // Adds the edges of a closed ring (last point != first); consecutive duplicates are skipped.
  // Preconditions for the faces to be meaningful: no two edges cross or overlap and no vertex
  // lies inside another edge (resolve.h guarantees this for islands).
  void add_ring(const Ring& ring);
  // Adds a chord between two vertices; returns the half-edge u -> v (its twin is v -> u).
  int add_chord(int u, int v);
  void set_removed(int chord, bool removed);  // a chord half-edge and its twin

  int vertex_count() const { return static_cast<int>(points_.size()); }
  int find_vertex(const Point& p) const;  // -1 when absent
  const Point& point(int v) const { return points_[v]; }
  const HalfEdge& half_edge(int h) const { return half_edges_[h]; }
  int half_edge_count() const { return static_cast<int>(half_edges_.size()); }
  // Boundary half-edges leaving (out) or entering (in) vertex v.
  const std::vector<int>& boundary_out(int v) const { return out_[v]; }
  const std::vector<int>& boundary_in(int v) const { return in_[v]; }

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
  struct Spoke {
    int other;  // the vertex at the far end
    int he;     // half-edge id
    bool out;   // leaves this vertex
  };
  int vertex_id(const Point& p);
  void add_spoke(int v, Spoke s);

  struct PointHash {
    size_t operator()(const Point& p) const {
      return std::hash<int64_t>()(p.X * 0x9E3779B97F4A7C15ULL ^ static_cast<uint64_t>(p.Y));
    }
  };
  std::vector<Point> points_;
  std::unordered_map<Point, int, PointHash> ids_;
  std::vector<HalfEdge> half_edges_;
  std::vector<std::vector<Spoke>> spokes_;  // per vertex, counter-clockwise by direction
  std::vector<std::vector<int>> out_, in_;
};

}  // namespace tranche::geo
