#include "geometry/slice/topology.h"

#include <doctest/doctest.h>

#include "geometry/mesh/primitives.h"

using namespace tranche::geo;

TEST_CASE("topology of a closed mesh") {
  Mesh m = torus(10, 3, 24, 12);
  MeshTopology t = build_topology(m);
  CHECK(t.edges.size() == 3 * m.triangles.size() / 2);
  CHECK(t.boundary_edges == 0);
  CHECK(t.nonmanifold_edges == 0);
  CHECK(t.misoriented_edges == 0);
  for (size_t i = 0; i < m.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const auto& e = t.edges[t.triangles[i].edge[k]];
      uint32_t a = m.triangles[i][k], b = m.triangles[i][(k + 1) % 3];
      CHECK(e.v0 == std::min(a, b));
      CHECK(e.v1 == std::max(a, b));
      CHECK((e.t0 == i || e.t1 == i));
      CHECK(e.count == 2);
      const uint32_t other = e.t0 == i ? e.t1 : e.t0;
      CHECK(t.triangles[i].neighbor[k] == other);
      // The neighbour has the same edge, traversed the other way.
      const auto& o = m.triangles[other];
      bool reversed = false;
      for (int j = 0; j < 3; ++j) reversed = reversed || (o[j] == b && o[(j + 1) % 3] == a);
      CHECK(reversed);
    }
}

TEST_CASE("topology counts holes, flips, non-manifold edges and degenerate triangles") {
  Mesh m = box({1, 1, 1});
  m.triangles.pop_back();                           // a hole: 3 boundary edges
  std::swap(m.triangles[0][1], m.triangles[0][2]);  // a flipped triangle
  m.triangles.push_back({0, 0, 1});                 // degenerate
  MeshTopology t = build_topology(m);
  CHECK(t.boundary_edges == 3);
  CHECK(t.misoriented_edges >= 2);
  CHECK(t.degenerate_triangles == 1);
  CHECK(t.triangles.back().edge[0] == MeshTopology::kNone);
  // The triangles along the hole have no neighbour there.
  size_t without = 0;
  for (const auto& l : t.triangles)
    for (auto n : l.neighbor) without += n == MeshTopology::kNone;
  CHECK(without == 3 + 3);  // the hole's 3 sides and the degenerate triangle's (a flip keeps its neighbours)
  Mesh fin = box({1, 1, 1});
  fin.vertices.push_back({2, 0, 0});
  fin.triangles.push_back({0, 1, 8});  // a fin on the cube's bottom edge 0-1
  CHECK(build_topology(fin).nonmanifold_edges == 1);
}
