#include "geometry/slice/topology.h"

#include <algorithm>

#include <tbb/parallel_for.h>

namespace tranche::geo {

namespace {

// Union-find over the vertices of boundary edges: each connected set of them is one rim.
void find_rims(MeshTopology& topo) {
  std::vector<uint32_t> verts;
  for (const auto& e : topo.edges)
    if (e.count == 1) verts.push_back(e.v0), verts.push_back(e.v1);
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  auto index = [&](uint32_t v) {
    return static_cast<uint32_t>(std::lower_bound(verts.begin(), verts.end(), v) - verts.begin());
  };
  std::vector<uint32_t> parent(verts.size());
  for (uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
  auto root = [&](uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const auto& e : topo.edges)
    if (e.count == 1) {
      uint32_t a = root(index(e.v0)), b = root(index(e.v1));
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  // Rims numbered by their lowest vertex, in order.
  std::vector<uint32_t> rim(verts.size(), MeshTopology::kNone);
  uint32_t rims = 0;
  topo.vertex_rims.reserve(verts.size());
  for (uint32_t i = 0; i < verts.size(); ++i) {
    uint32_t r = root(i);
    if (rim[r] == MeshTopology::kNone) rim[r] = rims++;
    topo.vertex_rims.emplace_back(verts[i], rim[r]);
  }
  for (uint32_t id = 0; id < topo.edges.size(); ++id)
    if (topo.edges[id].count == 1) topo.edge_rims.emplace_back(id, rim[root(index(topo.edges[id].v0))]);
}

}  // namespace

MeshTopology build_topology(const Mesh& mesh) {
  MeshTopology topo;
  const size_t nv = mesh.vertices.size(), nt = mesh.triangles.size();
  constexpr uint32_t kNone = MeshTopology::kNone;
  topo.triangles.assign(nt, {{kNone, kNone, kNone}, {kNone, kNone, kNone}});

  // Counting sort of the half-edges by their lower vertex id, then a small sort per vertex by the
  // upper id: equal (lower, upper) pairs become one edge.
  std::vector<uint32_t> start(nv + 1, 0);
  for (const auto& t : mesh.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++topo.degenerate_triangles;
      continue;
    }
    for (int k = 0; k < 3; ++k) ++start[std::min(t[k], t[(k + 1) % 3]) + 1];
  }
  for (size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  struct Half {
    uint32_t upper;
    uint32_t half;  // triangle * 3 + k
  };
  std::vector<Half> halves(start[nv]);
  {
    std::vector<uint32_t> cursor(start.begin(), start.end() - 1);
    for (size_t t = 0; t < nt; ++t) {
      const auto& tri = mesh.triangles[t];
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;
      for (uint32_t k = 0; k < 3; ++k) {
        uint32_t a = tri[k], b = tri[(k + 1) % 3];
        halves[cursor[std::min(a, b)]++] = {std::max(a, b), static_cast<uint32_t>(t * 3 + k)};
      }
    }
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nv, 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t v = r.begin(); v != r.end(); ++v)
      std::sort(halves.begin() + start[v], halves.begin() + start[v + 1], [](const Half& x, const Half& y) {
        return x.upper < y.upper || (x.upper == y.upper && x.half < y.half);
      });
  });

  topo.edges.reserve(halves.size() / 2 + 1);
  for (size_t v = 0; v < nv; ++v) {
    for (uint32_t i = start[v], end = start[v + 1]; i < end;) {
      uint32_t j = i;
      while (j < end && halves[j].upper == halves[i].upper) ++j;
      const auto id = static_cast<uint32_t>(topo.edges.size());
      MeshTopology::Edge e;
      e.v0 = static_cast<uint32_t>(v);
      e.v1 = halves[i].upper;
      e.count = j - i;
      e.t0 = halves[i].half / 3;
      if (j - i >= 2) e.t1 = halves[i + 1].half / 3;
      for (uint32_t h = i; h < j; ++h) topo.triangles[halves[h].half / 3].edge[halves[h].half % 3] = id;
      if (j - i == 2) {
        topo.triangles[halves[i].half / 3].neighbor[halves[i].half % 3] = e.t1;
        topo.triangles[halves[i + 1].half / 3].neighbor[halves[i + 1].half % 3] = e.t0;
      }
      if (e.count == 1) ++topo.boundary_edges;
      if (e.count > 2) ++topo.nonmanifold_edges;
      if (e.count == 2) {
        // Same direction in both triangles: the first vertex of the half-edge is the same.
        auto from = [&](uint32_t half) { return mesh.triangles[half / 3][half % 3]; };
        if (from(halves[i].half) == from(halves[i + 1].half)) ++topo.misoriented_edges;
      }
      topo.edges.push_back(e);
      i = j;
    }
  }
  if (topo.boundary_edges > 0) find_rims(topo);
  return topo;
}

}  // namespace tranche::geo
