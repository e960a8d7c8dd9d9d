// bench_models: writes the benchmark models that are generated rather than downloaded.
//   bench_models plate OUT.stl          60 × 40 × 4 mm plate with a 6 × 4 grid of 4 mm holes
//   bench_models torus OUT.stl [M N]    torus R 40, r 15 mm of 2·M·N triangles (1280 × 320: 819 200)
//   bench_models bunny IN.stl OUT.stl   stl-models' bunny (metres, y up) in mm, z up, standing on its
//                                       base: the 0.4 mm below it (a 1.4 mm² sliver of a hole's rim,
//                                       which PrusaSlicer refuses as a first layer with nothing to
//                                       print) is cut off
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"

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

}  // namespace

int main(int argc, char** argv) {
  std::string_view cmd = argc > 1 ? argv[1] : "";
  if (cmd == "plate" && argc == 3) return write(argv[2], geo::plate_with_holes(60, 40, 4, 6, 4, 2, 48));
  if (cmd == "torus" && (argc == 3 || argc == 5)) {
    int m = argc == 5 ? std::atoi(argv[3]) : 1280, n = argc == 5 ? std::atoi(argv[4]) : 320;
    return write(argv[2], geo::translated(geo::torus(40, 15, m, n), {0, 0, 15}));
  }
  if (cmd == "bunny" && argc == 4) {
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
    return write(argv[3], cut);
  }
  std::fprintf(stderr, "usage: bench_models plate OUT.stl | torus OUT.stl [M N] | bunny IN.stl OUT.stl\n");
  return 2;
}
