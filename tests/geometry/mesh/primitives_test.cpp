#include "geometry/mesh/primitives.h"

#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <tuple>
#include <utility>

using namespace tranche::geo;

namespace {

constexpr double kPi = std::numbers::pi;

// Area of a regular n-gon inscribed in a circle of radius r (mm²).
double ngon_area(double r, int n) { return 0.5 * n * r * r * std::sin(2 * kPi / n); }

// Every directed edge appears once and its reverse once: closed, manifold, consistently oriented.
void check_closed_and_oriented(const Mesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (const auto& t : m.triangles) {
    REQUIRE(t[0] != t[1]);
    REQUIRE(t[1] != t[2]);
    REQUIRE(t[0] != t[2]);
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  size_t bad = 0;
  for (const auto& [e, n] : directed) {
    auto rev = directed.find({e.second, e.first});
    if (n != 1 || rev == directed.end() || rev->second != 1) ++bad;
  }
  CHECK(bad == 0);
  // Welded: no two vertex ids at the same place.
  std::set<std::tuple<double, double, double>> seen;
  for (const auto& v : m.vertices) seen.insert({v.x, v.y, v.z});
  CHECK(seen.size() == m.vertices.size());
  // Every vertex is used.
  std::set<uint32_t> used;
  for (const auto& t : m.triangles) used.insert(t.begin(), t.end());
  CHECK(used.size() == m.vertices.size());
}

}  // namespace

TEST_CASE("box: volume and closed orientation") {
  Mesh m = box({10, 20, 30}, {-5, 1, 2});
  CHECK(m.triangles.size() == 12);
  CHECK(m.volume() == doctest::Approx(6000).epsilon(1e-12));
  check_closed_and_oriented(m);
  BBox3 b = m.bbox();
  CHECK(b.min.x == -5);
  CHECK(b.max.z == 32);
}

TEST_CASE("cylinder: volume of the inscribed prism") {
  for (int n : {3, 7, 64}) {
    Mesh m = cylinder(5, 12, n);
    CHECK(m.triangles.size() == static_cast<size_t>(4 * n));
    CHECK(m.volume() == doctest::Approx(ngon_area(5, n) * 12).epsilon(1e-12));
    check_closed_and_oriented(m);
  }
}

TEST_CASE("cone and frustum: volume") {
  const int n = 40;
  Mesh pointed = cone(6, 0, 9, n);
  CHECK(pointed.volume() == doctest::Approx(ngon_area(6, n) * 9 / 3).epsilon(1e-12));
  check_closed_and_oriented(pointed);
  Mesh frustum = cone(6, 2, 9, n);
  double a1 = ngon_area(6, n), a2 = ngon_area(2, n);
  CHECK(frustum.volume() == doctest::Approx(9.0 / 3 * (a1 + a2 + std::sqrt(a1 * a2))).epsilon(1e-12));
  check_closed_and_oriented(frustum);
}

TEST_CASE("sphere: volume converges to 4/3 pi r^3") {
  Mesh coarse = sphere(10, 16, 8);
  Mesh fine = sphere(10, 128, 64);
  check_closed_and_oriented(coarse);
  check_closed_and_oriented(fine);
  const double exact = 4.0 / 3 * kPi * 1000;
  CHECK(fine.volume() < exact);  // inscribed
  CHECK(fine.volume() == doctest::Approx(exact).epsilon(2e-3));
  CHECK(std::abs(exact - fine.volume()) < std::abs(exact - coarse.volume()));
}

TEST_CASE("torus: Pappus volume of the polyhedral torus and 800k triangles") {
  // Each wedge of the revolved n-gon has planar faces: V = m sin(2π/m) R A_ngon (exact).
  const double R = 20, r = 6;
  for (auto [m, n] : {std::pair{12, 6}, std::pair{96, 48}}) {
    Mesh t = torus(R, r, m, n);
    CHECK(t.triangles.size() == static_cast<size_t>(2 * m * n));
    CHECK(t.volume() == doctest::Approx(m * std::sin(2 * kPi / m) * R * ngon_area(r, n)).epsilon(1e-10));
    check_closed_and_oriented(t);
  }
  Mesh big = torus(30, 10, 1280, 320);
  CHECK(big.triangles.size() >= 800000);
  CHECK(big.volume() == doctest::Approx(2 * kPi * kPi * 30 * 100).epsilon(1e-3));
}

TEST_CASE("plate with holes: volume and welding across cells") {
  const int seg = 16;
  Mesh all = plate_with_holes(30, 20, 2, 3, 2, 3, seg);
  CHECK(all.volume() == doctest::Approx(2 * (600 - 6 * ngon_area(3, seg))).epsilon(1e-9));
  check_closed_and_oriented(all);
  Mesh some = plate_with_holes(30, 20, 2, 3, 2, 3, seg, {true, false, false, true, false, true});
  CHECK(some.volume() == doctest::Approx(2 * (600 - 3 * ngon_area(3, seg))).epsilon(1e-9));
  check_closed_and_oriented(some);
  Mesh none = plate_with_holes(10, 10, 1, 1, 1, 2, 4, {false});
  CHECK(none.volume() == doctest::Approx(100).epsilon(1e-12));
  check_closed_and_oriented(none);
}

TEST_CASE("append and translated keep shells separate") {
  Mesh m = box({1, 1, 1});
  append(m, translated(box({2, 2, 2}), {5, 0, 0}));
  CHECK(m.triangles.size() == 24);
  CHECK(m.volume() == doctest::Approx(9));
  check_closed_and_oriented(m);
  CHECK(m.bbox().max.x == 7);
}

TEST_CASE("demo model: closed shells under 2k triangles") {
  Mesh m = demo_model();
  CHECK(m.triangles.size() < 2000);
  CHECK(m.triangles.size() > 500);
  check_closed_and_oriented(m);
  BBox3 b = m.bbox();
  CHECK(b.min.z == 0);
  CHECK(b.max.x == doctest::Approx(40));
  CHECK(b.max.z == doctest::Approx(15));
  CHECK(m.volume() > 40 * 40 * 3 * 0.8);
}
