// Edge adjacency of a welded mesh: which triangles share each edge. Slicing follows it to chain
// segments into loops without comparing coordinates.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "geometry/mesh/mesh.h"

namespace tranche::geo {

struct MeshTopology {
  static constexpr uint32_t kNone = UINT32_MAX;

  struct Edge {
    uint32_t v0 = 0, v1 = 0;          // vertex ids, v0 < v1
    uint32_t t0 = kNone, t1 = kNone;  // the first two triangles using the edge (t1 = kNone: boundary)
    uint32_t count = 0;               // triangles using it: 2 on a closed manifold, 1 on a boundary
  };

  // Per triangle, side k being the edge from vertex k to vertex (k + 1) % 3. Kept together so
  // that slicing reads one cache line per triangle.
  struct Links {
    std::array<uint32_t, 3> edge;      // edge ids; all kNone for a degenerate triangle (skipped)
    std::array<uint32_t, 3> neighbor;  // the other triangle when exactly two share the edge, else kNone
  };

  std::vector<Edge> edges;
  std::vector<Links> triangles;

  // Holes: the boundary edges grouped into rims (connected through shared vertices), so that
  // slicing joins a hole's crossings with each other. Sorted by id; empty for a closed mesh.
  std::vector<std::pair<uint32_t, uint32_t>> edge_rims;    // (boundary edge id, rim)
  std::vector<std::pair<uint32_t, uint32_t>> vertex_rims;  // (vertex id on a boundary edge, rim)
  // The rim of a boundary edge or vertex, kNone when it lies on no hole.
  uint32_t edge_rim(uint32_t edge) const { return find(edge_rims, edge); }
  uint32_t vertex_rim(uint32_t vertex) const { return find(vertex_rims, vertex); }

  size_t boundary_edges = 0;        // used by one triangle: the mesh has a hole there
  size_t nonmanifold_edges = 0;     // used by three or more triangles
  size_t misoriented_edges = 0;     // two triangles traversing the edge the same way (one is flipped)
  size_t degenerate_triangles = 0;  // a vertex id repeated

 private:
  static uint32_t find(const std::vector<std::pair<uint32_t, uint32_t>>& v, uint32_t id) {
    auto it = std::lower_bound(v.begin(), v.end(), std::pair<uint32_t, uint32_t>(id, 0));
    return it != v.end() && it->first == id ? it->second : kNone;
  }
};

// O(vertices + triangles) time and memory.
MeshTopology build_topology(const Mesh& mesh);

}  // namespace tranche::geo
