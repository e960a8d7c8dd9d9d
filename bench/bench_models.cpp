// bench_models: writes the benchmark models that are generated rather than downloaded.
//   bench_models plate OUT.stl          60 × 40 × 4 mm plate with a 6 × 4 grid of 4 mm holes
//   bench_models torus OUT.stl [M N]    torus R 40, r 15 mm of 2·M·N triangles (1280 × 320: 819 200)
//   bench_models bunny IN.stl OUT.stl   stl-models' bunny (metres, y up) in mm, z up, standing on its
//                                       base: the 0.4 mm below it (a 1.4 mm² sliver of a hole's rim,
//                                       which PrusaSlicer refuses as a first layer with nothing to
//                                       print) is cut off
//   bench_models bunny_closed IN.stl OUT.stl  the same, with its holes capped: every boundary loop
//                                       (the cut base and the scan's holes underneath) closed by
//                                       a fan from its centroid, so that any slicer, and gcheck,
//                                       reads one solid (the open one leaves each to its own guess)
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "geometry/mesh/weld.h"

using namespace tranche;

namespace {
int write(const std::string& path, const geo::Mesh& m) {
  auto s = geo::write_stl_binary(path, m);
  if (!s) {
    std::fprintf(stderr, "bench_models: %s\n", s.error().to_string().c_str());
    return 1;
  }
  std::printf("wrote %s (%zu triangles)\n", path.c_str(), m.triangles.size());
  return 0;
}
// The part of the mesh at z ≥ c (mm), as a triangle soup (STL welds it again on loading): a
// triangle across the plane is clipped, each crossing computed from its edge's lower vertex to
// its upper one so that both triangles sharing the edge get the same point.
geo::Mesh cut_below(const geo::Mesh& m, double c) {
  geo::Mesh out;
  out.name = m.name;
  for (const auto& t : m.triangles) {
    std::vector<geo::Vec3> poly;
    for (int k = 0; k < 3; ++k) {
      const geo::Vec3 &p = m.vertices[t[k]], &q = m.vertices[t[(k + 1) % 3]];
      if (p.z >= c) poly.push_back(p);
      if ((p.z >= c) != (q.z >= c)) {
        const geo::Vec3 &lo = p.z < q.z ? p : q, &hi = p.z < q.z ? q : p;
        double f = (c - lo.z) / (hi.z - lo.z);
        poly.push_back({lo.x + f * (hi.x - lo.x), lo.y + f * (hi.y - lo.y), c});
      }
    }
    for (size_t i = 1; i + 1 < poly.size(); ++i) {
      auto id = static_cast<uint32_t>(out.vertices.size());
      out.vertices.insert(out.vertices.end(), {poly[0], poly[i], poly[i + 1]});
      out.triangles.push_back({id, id + 1, id + 2});
    }
  }
  return out;
}

// Welds a triangle soup (geo::Welder, as STL loading does) and closes every boundary loop by a
// fan from its centroid. A boundary edge u -> v (no triangle has v -> u) gets the cap triangle
// v, u, c.
geo::Mesh capped(const geo::Mesh& soup) {
  geo::Mesh m;
  m.name = soup.name;
  std::vector<float> corners;
  corners.reserve(9 * soup.triangles.size());
  for (const auto& t : soup.triangles)
    for (uint32_t id : t) {
      const geo::Vec3& v = soup.vertices[id];
      corners.insert(corners.end(), {float(v.x), float(v.y), float(v.z)});
    }
  std::vector<uint8_t> dropped(soup.triangles.size());
  geo::Welder welder(soup.triangles.size());
  welder.add(corners.data(), soup.triangles.size(), dropped.data());
  welder.finish(m);
  auto key = [](uint32_t u, uint32_t v) { return (uint64_t(u) << 32) | v; };
  std::unordered_map<uint64_t, int> edges;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++edges[key(t[k], t[(k + 1) % 3])];
  std::unordered_map<uint32_t, uint32_t> next;  // boundary edges, u -> v
  for (const auto& [e, count] : edges) {
    uint32_t u = uint32_t(e >> 32), v = uint32_t(e & 0xffffffffu);
    if (!edges.count(key(v, u))) next[u] = v;
  }
  size_t loops = 0;
  while (!next.empty()) {
    std::vector<uint32_t> loop{next.begin()->first};
    while (true) {
      auto it = next.find(loop.back());
      if (it == next.end()) break;
      uint32_t v = it->second;
      next.erase(it);
      if (v == loop.front()) break;
      loop.push_back(v);
    }
    if (loop.size() < 3) continue;
    geo::Vec3 c{0, 0, 0};
    for (uint32_t v : loop) c = {c.x + m.vertices[v].x, c.y + m.vertices[v].y, c.z + m.vertices[v].z};
    const double n = static_cast<double>(loop.size());
    auto ci = static_cast<uint32_t>(m.vertices.size());
    m.vertices.push_back({c.x / n, c.y / n, c.z / n});
    for (size_t i = 0; i < loop.size(); ++i)
      m.triangles.push_back({loop[(i + 1) % loop.size()], loop[i], ci});
    ++loops;
  }
  std::printf("capped %zu holes\n", loops);
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  std::string_view cmd = argc > 1 ? argv[1] : "";
  if (cmd == "plate" && argc == 3) return write(argv[2], geo::plate_with_holes(60, 40, 4, 6, 4, 2, 48));
  if (cmd == "torus" && (argc == 3 || argc == 5)) {
    int m = argc == 5 ? std::atoi(argv[3]) : 1280, n = argc == 5 ? std::atoi(argv[4]) : 320;
    return write(argv[2], geo::translated(geo::torus(40, 15, m, n), {0, 0, 15}));
  }
  if ((cmd == "bunny" || cmd == "bunny_closed") && argc == 4) {
    Report report;
    auto mesh = geo::load_stl(argv[2], report);
    if (!mesh) {
      std::fprintf(stderr, "bench_models: %s\n", mesh.error().to_string().c_str());
      return 1;
    }
    for (auto& v : mesh->vertices) v = {v.x * 1000, -v.z * 1000, v.y * 1000};  // a rotation: winding kept
    const double base = mesh->bbox().min.z + 0.4;
    geo::Mesh cut = cut_below(*mesh, base);
    cut.transform(1.0, {0, 0, -base});
    return write(argv[3], cmd == "bunny" ? cut : capped(cut));
  }
  // Overhangs of every kind, for bench_support.sh.
  if (cmd == "mushroom" && argc == 3) {  // a cap on a stem
    geo::Mesh m = geo::box({8, 8, 15}, {11, 11, 0});
    geo::append(m, geo::box({30, 30, 3}, {0, 0, 15}));
    return write(argv[2], m);
  }
  if (cmd == "ledge" && argc == 3) {  // a bracket: a shelf out of a wall
    geo::Mesh m = geo::box({30, 5, 25}, {0, 0, 0});
    geo::append(m, geo::box({30, 15, 3}, {0, 5, 20}));
    return write(argv[2], m);
  }
  if (cmd == "span" && argc == 3) {  // a slab on two pillars 30 mm apart: too long to bridge
    geo::Mesh m = geo::box({5, 10, 15}, {0, 0, 0});
    geo::append(m, geo::box({5, 10, 15}, {35, 0, 0}));
    geo::append(m, geo::box({40, 10, 3}, {0, 0, 15}));
    return write(argv[2], m);
  }
  if (cmd == "slope" && argc == 3)  // a funnel: walls 53° from vertical
    return write(argv[2], geo::cone(5, 25, 15, 128));
  std::fprintf(
      stderr,
      "usage: bench_models plate OUT.stl | torus OUT.stl [M N] | bunny|bunny_closed IN.stl OUT.stl | "
      "mushroom|ledge|span|slope OUT.stl\n");
  return 2;
}
