#include "geometry/slice/slicer.h"

#include <doctest/doctest.h>

#include <atomic>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>

#include "geometry/mesh/primitives.h"
#include "geometry/slice/layer_heights.h"
#include "geometry/slice/simple_islands.h"

using namespace tranche;
using namespace tranche::geo;

namespace {

constexpr double kPi = std::numbers::pi;

// Merges exactly equal vertices, as the STL loader does.
Mesh welded(const Mesh& in) {
  Mesh out;
  std::map<std::tuple<double, double, double>, uint32_t> ids;
  std::vector<uint32_t> remap(in.vertices.size());
  for (size_t i = 0; i < in.vertices.size(); ++i) {
    const Vec3& v = in.vertices[i];
    auto [it, added] = ids.try_emplace({v.x, v.y, v.z}, static_cast<uint32_t>(out.vertices.size()));
    if (added) out.vertices.push_back(v);
    remap[i] = it->second;
  }
  for (const auto& t : in.triangles) out.triangles.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
  return out;
}

Mesh octahedron(const Vec3& c, double r) {
  Mesh m;
  m.vertices = {{c.x + r, c.y, c.z}, {c.x, c.y + r, c.z}, {c.x - r, c.y, c.z},
                {c.x, c.y - r, c.z}, {c.x, c.y, c.z + r}, {c.x, c.y, c.z - r}};
  for (uint32_t i = 0; i < 4; ++i) {
    uint32_t j = (i + 1) % 4;
    m.triangles.push_back({i, j, 4});
    m.triangles.push_back({j, i, 5});
  }
  return m;
}

struct Sliced {
  std::vector<Layer> layers;
  Report report;
  SliceStats stats;
};

// Plans (0.2 mm layers) from the mesh's bottom, slices and unions.
void slice_all(Mesh mesh, Sliced& out, double layer_height = 0.2) {
  const BBox3 b = mesh.bbox();
  mesh.transform(1.0, {0, 0, -b.min.z});
  LayerHeightParams p;
  p.first_layer_height = p.layer_height = layer_height;
  auto plan = plan_layer_heights(b.max.z - b.min.z, p);
  REQUIRE(plan.ok());
  out.layers = std::move(*plan);
  auto st = slice_mesh(mesh, out.layers, {}, out.report);
  REQUIRE_MESSAGE(st.ok(), (st.ok() ? "" : st.error().to_string()));
  out.stats = *st;
  REQUIRE(make_islands(out.layers).ok());
}

// One layer with its plane at exactly z (mm).
std::vector<Layer> layer_at(double z) {
  Layer l;
  l.z_bottom = z - 1;
  l.z_top = z + 1;
  return {l};
}

double layer_area(const Layer& l) {
  double a = 0;
  for (const auto& i : l.islands) a += i.area_mm2;
  return a;
}

double loops_area(const Layer& l) {
  double a = 0;
  for (const auto& r : l.loops) a += area_mm2(r);
  return a;
}

// A 30 × 30 × 10 box made of 1 mm squares (two triangles each), without the squares of two
// windows: A in the y = 0 wall at x 2..13, B in the x = 0 wall at y 3..28, both at z 2..8.
Mesh box_with_windows() {
  Mesh m;
  // A face of nu × nv unit squares from o along u and v, its outside towards u × v.
  auto face = [&](Vec3 o, Vec3 u, Vec3 v, int nu, int nv, auto window) {
    auto at = [&](int i, int j) {
      return Vec3{o.x + i * u.x + j * v.x, o.y + i * u.y + j * v.y, o.z + i * u.z + j * v.z};
    };
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j) {
        if (window(at(i, j), at(i + 1, j + 1))) continue;
        auto id = static_cast<uint32_t>(m.vertices.size());
        m.vertices.insert(m.vertices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        m.triangles.push_back({id, id + 1, id + 2});
        m.triangles.push_back({id, id + 2, id + 3});
      }
  };
  auto none = [](Vec3, Vec3) { return false; };
  auto in = [](double a, double b, double lo, double hi) {
    return std::min(a, b) >= lo && std::max(a, b) <= hi;
  };
  auto window_a = [&](Vec3 p, Vec3 q) { return in(p.x, q.x, 2, 13) && in(p.z, q.z, 2, 8); };
  auto window_b = [&](Vec3 p, Vec3 q) { return in(p.y, q.y, 3, 28) && in(p.z, q.z, 2, 8); };
  face({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, 30, 30, none);      // bottom, outside -z
  face({0, 0, 10}, {1, 0, 0}, {0, 1, 0}, 30, 30, none);     // top, +z
  face({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 30, 10, window_a);  // y = 0, -y
  face({0, 30, 0}, {0, 0, 1}, {1, 0, 0}, 10, 30, none);     // y = 30, +y
  face({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 10, 30, window_b);  // x = 0, -x
  face({30, 0, 0}, {0, 1, 0}, {0, 0, 1}, 30, 10, none);     // x = 30, +x
  return m;
}

}  // namespace

SCENARIO("a 10 mm cube with 0.2 mm layers") {
  Sliced s;
  slice_all(box({10, 10, 10}, {3, -4, 7}), s);
  THEN("50 layers of exactly 100 mm², one counter-clockwise loop each") {
    REQUIRE(s.layers.size() == 50);
    for (const auto& l : s.layers) {
      REQUIRE(l.loops.size() == 1);
      CHECK(area_mm2(l.loops[0]) > 0);
      CHECK(l.loops[0].size() >= 4);
      REQUIRE(l.islands.size() == 1);
      CHECK(l.islands[0].area_mm2 == doctest::Approx(100).epsilon(1e-8));
      CHECK(std::abs(l.islands[0].area_mm2 - 100) <= 1e-6);
      CHECK(l.islands[0].shape.holes.empty());
    }
    CHECK(s.report.empty());
    CHECK(s.stats.open_loops == 0);
    CHECK(s.stats.gaps_joined == 0);
  }
}

SCENARIO("planes through vertices and faces") {
  GIVEN("a cube cut exactly at its top face") {
    auto layers = layer_at(10);
    Report r;
    REQUIRE(slice_mesh(box({10, 10, 10}), layers, {}, r).ok());
    THEN("the side walls' edges in the plane make the square once") {
      REQUIRE(layers[0].loops.size() == 1);
      CHECK(area_mm2(layers[0].loops[0]) == doctest::Approx(100));
    }
  }
  GIVEN("a cube cut exactly at its bottom face") {
    auto layers = layer_at(0);
    Report r;
    REQUIRE(slice_mesh(box({10, 10, 10}), layers, {}, r).ok());
    THEN("nothing: on the plane counts as above") { CHECK(layers[0].loops.empty()); }
  }
  GIVEN("an octahedron cut through its four equator vertices") {
    auto layers = layer_at(0);
    Report r;
    REQUIRE(slice_mesh(octahedron({0, 0, 0}, 1), layers, {}, r).ok());
    THEN("each equator edge is counted once: the square of area 2") {
      REQUIRE(layers[0].loops.size() == 1);
      CHECK(layers[0].loops[0].size() == 4);
      CHECK(area_mm2(layers[0].loops[0]) == doctest::Approx(2).epsilon(1e-9));
      CHECK(r.empty());
    }
  }
  GIVEN("a bipyramid whose plane passes through two vertices with neighbours on both sides") {
    // Equator at z = 4, 5, 6, 5: the plane z = 5 passes through vertices 1 and 3.
    Mesh m;
    m.vertices = {{10, 0, 4}, {0, 10, 5}, {-10, 0, 6}, {0, -10, 5}, {0, 0, 10}, {0, 0, 0}};
    for (uint32_t i = 0; i < 4; ++i) {
      uint32_t j = (i + 1) % 4;
      m.triangles.push_back({i, j, 4});
      m.triangles.push_back({j, i, 5});
    }
    auto at = layer_at(5);
    auto near = layer_at(5 + 1e-7);
    Report r;
    REQUIRE(slice_mesh(m, at, {}, r).ok());
    REQUIRE(slice_mesh(m, near, {}, r).ok());
    THEN("one closed loop, with the area of the section just above") {
      REQUIRE(at[0].loops.size() == 1);
      CHECK(area_mm2(at[0].loops[0]) > 0);
      CHECK(area_mm2(at[0].loops[0]) == doctest::Approx(loops_area(near[0])).epsilon(1e-5));
      CHECK(r.empty());
    }
  }
}

SCENARIO("a cylinder's layers match the analytic area") {
  const double r = 12;
  const int n = 256;
  Sliced s;
  slice_all(cylinder(r, 7, n), s);
  REQUIRE(s.layers.size() == 35);
  const double ngon = 0.5 * n * r * r * std::sin(2 * kPi / n);
  for (const auto& l : s.layers) {
    REQUIRE(l.islands.size() == 1);
    CHECK(l.islands[0].area_mm2 == doctest::Approx(ngon).epsilon(1e-7));
    CHECK(l.islands[0].area_mm2 == doctest::Approx(kPi * r * r).epsilon(5e-3));
  }
}

SCENARIO("a torus's layers match the analytic cross-section") {
  // Torus (R, r) of m × n segments: the section at height z is the annulus between the minor
  // n-gon's outer and inner radius at z, revolved as an m-gon: (m/2) sin(2π/m) (ρ_out² − ρ_in²).
  const double R = 20, r = 8;
  const int m = 360, n = 144;
  Mesh t = torus(R, r, m, n);
  Sliced s;
  slice_all(t, s);
  const double z0 = -t.bbox().min.z;  // the torus was moved up by this much
  REQUIRE(s.layers.size() == 80);
  for (const auto& l : s.layers) {
    const double z = l.z_slice() - z0;
    double rho_out = -1, rho_in = 1e9;
    for (int j = 0; j < n; ++j) {
      double a0 = 2 * kPi * j / n, a1 = 2 * kPi * (j + 1) / n;
      double z_a = r * std::sin(a0), z_b = r * std::sin(a1);
      if ((z_a - z) * (z_b - z) > 0 || z_a == z_b) continue;
      double u = (z - z_a) / (z_b - z_a);
      double rho = R + r * (std::cos(a0) + u * (std::cos(a1) - std::cos(a0)));
      rho_out = std::max(rho_out, rho);
      rho_in = std::min(rho_in, rho);
    }
    const double exact = 0.5 * m * std::sin(2 * kPi / m) * (rho_out * rho_out - rho_in * rho_in);
    REQUIRE(l.islands.size() == 1);
    CHECK(l.islands[0].shape.holes.size() == 1);
    CHECK(layer_area(l) == doctest::Approx(exact).epsilon(1e-5));
    // And the true torus, where the n-gon is close to its circle (not at the very top and bottom).
    if (std::abs(z) < 0.9 * r)
      CHECK(layer_area(l) == doctest::Approx(4 * kPi * R * std::sqrt(r * r - z * z)).epsilon(5e-3));
  }
  CHECK(s.report.empty());
}

SCENARIO("shells touching or overlapping") {
  GIVEN("two cubes sharing a vertical edge (welded: the edge has four triangles)") {
    Mesh m = box({10, 10, 10});
    append(m, box({10, 10, 10}, {10, 10, 0}));
    Mesh w = welded(m);
    CHECK(build_topology(w).nonmanifold_edges == 1);
    Sliced s;
    slice_all(w, s);
    THEN("every layer has both squares and no warning") {
      REQUIRE(s.layers.size() == 50);
      for (const auto& l : s.layers) CHECK(layer_area(l) == doctest::Approx(200));
      CHECK(s.report.empty());
    }
  }
  GIVEN("two octahedra sharing a vertex, cut through it") {
    Mesh m = octahedron({0, 0, 0}, 1);
    append(m, octahedron({2, 0, 0}, 1));
    Mesh w = welded(m);
    CHECK(w.vertices.size() == 11);
    auto layers = layer_at(0);
    Report r;
    REQUIRE(slice_mesh(w, layers, {}, r).ok());
    REQUIRE(make_islands(layers).ok());
    THEN("both squares, joined at the vertex") {
      CHECK(loops_area(layers[0]) == doctest::Approx(4));
      CHECK(layer_area(layers[0]) == doctest::Approx(4));
      CHECK(r.empty());
    }
  }
  GIVEN("two cubes touching at a single vertex") {
    Mesh m = box({10, 10, 10});
    append(m, box({10, 10, 10}, {10, 10, 10}));
    Sliced s;
    slice_all(welded(m), s);
    THEN("every layer has one square") {
      REQUIRE(s.layers.size() == 100);
      for (const auto& l : s.layers) CHECK(layer_area(l) == doctest::Approx(100));
      CHECK(s.report.empty());
    }
  }
  GIVEN("two overlapping cubes") {
    Mesh m = box({10, 10, 10});
    append(m, box({10, 10, 10}, {5, 5, 0}));
    Sliced s;
    slice_all(m, s);
    THEN("the nonzero union has the area of the union") {
      for (const auto& l : s.layers) {
        CHECK(l.loops.size() == 2);
        REQUIRE(l.islands.size() == 1);
        CHECK(layer_area(l) == doctest::Approx(175));
      }
    }
  }
  GIVEN("a cube inside a bigger cube, inside out (a cavity)") {
    Mesh m = box({10, 10, 10});
    Mesh inner = box({4, 4, 4}, {3, 3, 3});
    for (auto& t : inner.triangles) std::swap(t[1], t[2]);
    append(m, inner);
    Sliced s;
    slice_all(m, s);
    THEN("layers through the cavity have a hole") {
      const Layer& mid = s.layers[25];
      REQUIRE(mid.islands.size() == 1);
      CHECK(mid.islands[0].shape.holes.size() == 1);
      CHECK(layer_area(mid) == doctest::Approx(84));
      CHECK(layer_area(s.layers[5]) == doctest::Approx(100));
    }
  }
}

SCENARIO("an open mesh still yields every layer") {
  GIVEN("a cube with its +x face removed") {
    Mesh m = box({10, 10, 10});
    std::vector<std::array<uint32_t, 3>> kept;
    for (const auto& t : m.triangles) {
      bool on_px = true;
      for (auto v : t) on_px = on_px && m.vertices[v].x == 10;
      if (!on_px) kept.push_back(t);
    }
    REQUIRE(kept.size() == 10);
    m.triangles = kept;
    CHECK(build_topology(m).boundary_edges == 4);
    Sliced s;
    slice_all(m, s);
    THEN("every layer is closed across the hole, with an open-loop warning naming layer and place") {
      REQUIRE(s.layers.size() == 50);
      for (const auto& l : s.layers) CHECK(layer_area(l) == doctest::Approx(100));
      CHECK(s.stats.open_loops == 50);
      REQUIRE(s.report.count("open-loop") == 50);
      auto w = s.report.warnings();
      CHECK(w[0].where.rfind("layer 0 at (10.000, ", 0) == 0);
      CHECK(w[49].where.rfind("layer 49 at (", 0) == 0);
      CHECK(w[0].message.find("a 10.000 mm gap") != std::string::npos);
    }
  }
  GIVEN("a box with both its +x and -x faces removed") {
    Mesh m = box({10, 10, 10});
    std::vector<std::array<uint32_t, 3>> kept;
    for (const auto& t : m.triangles) {
      bool on_x = true;
      for (auto v : t) on_x = on_x && m.vertices[v].x == m.vertices[t[0]].x;
      if (!on_x) kept.push_back(t);
    }
    REQUIRE(kept.size() == 8);
    m.triangles = kept;
    Sliced s;
    slice_all(m, s);
    THEN("each layer's two walls are bridged to each other across both holes, not each on itself") {
      REQUIRE(s.layers.size() == 50);
      for (const auto& l : s.layers) {
        CHECK(l.loops.size() == 1);
        CHECK(layer_area(l) == doctest::Approx(100));
      }
      CHECK(s.report.count("open-loop") == 100);
    }
  }
  GIVEN("a 30 × 30 × 10 box with two windows whose nearest ends belong to different windows") {
    // The Stanford bunny's open base in miniature: window A in the y = 0 wall (x 2..13) and
    // window B in the x = 0 wall (y 3..28), both z 2..8. Across a layer, the wall ends at the two
    // windows' corners (0, 3) and (2, 0) are only 3.6 mm apart, nearer than either window's own
    // pair of ends (11 and 25 mm): closing nearest-first cuts the box's corner off with a
    // diagonal across the part.
    Mesh m = welded(box_with_windows());
    auto topo = build_topology(m);
    CHECK(topo.boundary_edges == 2 * (11 + 6) + 2 * (25 + 6));
    CHECK(topo.edge_rims.size() == topo.boundary_edges);
    CHECK(topo.vertex_rim(topo.edges[topo.edge_rims.front().first].v0) == topo.edge_rims.front().second);
    Sliced s;
    slice_all(m, s);
    THEN("each window's ends are joined to each other: every layer is the whole square") {
      REQUIRE(s.layers.size() == 50);
      for (const auto& l : s.layers) {
        CHECK(l.islands.size() == 1);
        CHECK(layer_area(l) == doctest::Approx(900));
      }
      CHECK(s.report.count("open-loop") == 2 * 30);
    }
  }
  GIVEN("a cube whose +x face is detached by a 0.1 mm crack") {
    Mesh m = box({10, 10, 10});
    std::vector<std::array<uint32_t, 3>> tris;
    std::map<uint32_t, uint32_t> moved;
    for (auto t : m.triangles) {
      bool on_px = true;
      for (auto v : t) on_px = on_px && m.vertices[v].x == 10;
      if (on_px)
        for (auto& v : t) {
          auto [it, added] = moved.try_emplace(v, static_cast<uint32_t>(m.vertices.size() + moved.size()));
          v = it->second;
        }
      tris.push_back(t);
    }
    std::vector<Vec3> extra(moved.size());
    for (auto [from, to] : moved)
      extra[to - m.vertices.size()] = {10.1, m.vertices[from].y, m.vertices[from].z};
    m.vertices.insert(m.vertices.end(), extra.begin(), extra.end());
    m.triangles = tris;
    Sliced s;
    slice_all(m, s);
    THEN("the gaps are within tolerance: joined silently, nearest first") {
      REQUIRE(s.layers.size() == 50);
      CHECK(s.report.empty());
      CHECK(s.stats.gaps_joined == 100);
      for (const auto& l : s.layers) {
        REQUIRE(l.loops.size() == 1);
        CHECK(layer_area(l) == doctest::Approx(101));
      }
    }
  }
}

TEST_CASE("slicing reports bad coordinates instead of crashing") {
  Mesh m = box({1, 1, 1});
  m.vertices[3].x = std::nan("");
  auto layers = layer_at(0.5);
  Report r;
  auto st = slice_mesh(m, layers, {}, r);
  REQUIRE(!st.ok());
  CHECK(st.error().where == "vertex 3");
}

TEST_CASE("progress is called once per layer") {
  auto plan = plan_layer_heights(10, {});
  REQUIRE(plan.ok());
  std::atomic<size_t> calls{0}, max_seen{0};
  SliceParams p;
  p.progress = [&](size_t done) {
    ++calls;
    size_t m = max_seen.load();
    while (done > m && !max_seen.compare_exchange_weak(m, done)) {
    }
  };
  Report r;
  REQUIRE(slice_mesh(box({10, 10, 10}), *plan, p, r).ok());
  CHECK(calls == 50);
  CHECK(max_seen == 50);
}

TEST_CASE("the union of nothing, or of loops without area, is empty") {
  CHECK(union_nonzero({}).ok());
  CHECK(union_nonzero({}).value().empty());
  Rings flat{{{0, 0}, {5, 0}, {10, 0}}};
  auto u = union_nonzero(flat);
  REQUIRE(u.ok());
  CHECK(u->empty());
}

SCENARIO("a flipped triangle in a fine mesh") {
  const int n = 64;
  Mesh m = cylinder(3, 5, n);  // sides 0.29 mm wide: under the 0.4 mm gap tolerance
  size_t flipped = 0;
  for (auto& t : m.triangles) {
    if (m.vertices[t[0]].z != m.vertices[t[1]].z || m.vertices[t[1]].z != m.vertices[t[2]].z) {
      std::swap(t[1], t[2]);
      ++flipped;
      break;
    }
  }
  REQUIRE(flipped == 1);
  CHECK(build_topology(m).misoriented_edges == 3);
  Sliced s;
  slice_all(m, s);
  THEN("the outline is mended across it: full area, no open loop") {
    const double ngon = 0.5 * n * 9 * std::sin(2 * kPi / n);
    REQUIRE(s.layers.size() == 25);
    for (const auto& l : s.layers) CHECK(layer_area(l) == doctest::Approx(ngon).epsilon(1e-6));
    CHECK(s.report.empty());
  }
}

SCENARIO("an unwelded triangle soup") {
  // Every triangle has its own three vertices: no edge is shared, topology chains nothing.
  Mesh welded_torus = torus(20, 8, 64, 32);
  auto soup = [&](double jitter) {
    Mesh m;
    uint32_t k = 0;
    for (const auto& t : welded_torus.triangles) {
      for (auto v : t) {
        Vec3 p = welded_torus.vertices[v];
        p.x += jitter * (static_cast<int>(k * 7919 % 13) - 6) / 6.0;  // deterministic, up to ±jitter
        p.y += jitter * (static_cast<int>(k * 104729 % 11) - 5) / 5.0;
        m.vertices.push_back(p);
        ++k;
      }
      m.triangles.push_back({k - 3, k - 2, k - 1});
    }
    return m;
  };
  Sliced ref;
  slice_all(welded_torus, ref);
  GIVEN("exact coordinates") {
    Sliced s;
    slice_all(soup(0), s);
    THEN("the zero-length gaps are joined: the same areas, no warning") {
      REQUIRE(s.layers.size() == ref.layers.size());
      for (size_t i = 0; i < s.layers.size(); ++i)
        CHECK(layer_area(s.layers[i]) == doctest::Approx(layer_area(ref.layers[i])).epsilon(1e-9));
      CHECK(s.report.empty());
      CHECK(s.stats.gaps_joined == 0);
    }
  }
  GIVEN("vertices jittered by up to 0.01 mm") {
    Sliced s;
    slice_all(soup(0.01), s);
    THEN("the gaps are under the tolerance: joined silently, areas within the jitter") {
      REQUIRE(s.layers.size() == ref.layers.size());
      for (size_t i = 0; i < s.layers.size(); ++i)
        CHECK(layer_area(s.layers[i]) == doctest::Approx(layer_area(ref.layers[i])).epsilon(2e-3));
      CHECK(s.report.count("open-loop") == 0);
      CHECK(s.stats.gaps_joined > 0);
    }
  }
}
