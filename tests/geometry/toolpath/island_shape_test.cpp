// Island shape measures on constructed shapes: a square, an L, a thin bar, a dumbbell (a neck
// between two wide parts), a square with a hole near its side (a thin wall), a disc.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "fixtures.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/island_shape.h"

using namespace tranche;
using namespace tranche::toolpath;
using tranche::test::rect;

namespace {

geo::Rings L_shape() {  // arms 2 mm wide, 10 mm long
  return {geo::Ring{geo::to_point(0, 0), geo::to_point(10, 0), geo::to_point(10, 2), geo::to_point(2, 2),
                    geo::to_point(2, 10), geo::to_point(0, 10)}};
}

geo::Rings disc(double r, int n = 180) {
  geo::Ring ring;
  for (int i = 0; i < n; ++i) {
    double a = 2 * std::numbers::pi * i / n;
    ring.push_back(geo::to_point(r * std::cos(a), r * std::sin(a)));
  }
  return {ring};
}

geo::Rings turned(geo::Rings rings, double deg) {
  const double a = deg * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
  for (auto& r : rings)
    for (auto& p : r) {
      const double x = static_cast<double>(p.X), y = static_cast<double>(p.Y);
      p = geo::Point(std::llround(c * x - s * y), std::llround(s * x + c * y));
    }
  return rings;
}

}  // namespace

TEST_CASE("min_width: the width of the narrowest part") {
  CHECK(min_width_mm({rect(0, 0, 10, 10)}) == doctest::Approx(10).epsilon(0.002));
  CHECK(min_width_mm(L_shape()) == doctest::Approx(2).epsilon(0.005));
  CHECK(min_width_mm({rect(0, 0, 20, 0.8)}) == doctest::Approx(0.8).epsilon(0.01));
  CHECK(min_width_mm(disc(5)) == doctest::Approx(10).epsilon(0.005));
  // Two 6 mm squares joined by a 1 mm neck: the neck, not the squares.
  geo::Rings dumbbell = union_of({rect(0, 0, 6, 6), rect(6, 2.5, 12, 3.5), rect(12, 0, 18, 6)});
  CHECK(min_width_mm(dumbbell) == doctest::Approx(1).epsilon(0.01));
  // A 20 mm square with a hole leaving a 0.6 mm wall on one side: the wall.
  geo::Rings walled{rect(0, 0, 20, 20), rect(0.6, 5, 10, 15, false)};
  CHECK(min_width_mm(walled) == doctest::Approx(0.6).epsilon(0.02));
  // A 1 mm tab on a 10 mm square.
  CHECK(min_width_mm(union_of({rect(0, 0, 10, 10), rect(10, 4.5, 15, 5.5)})) == doctest::Approx(1).epsilon(0.01));
  // A 10° spike is thinner than anything; a right-angled triangle is not.
  geo::Ring spike{geo::to_point(0, 0), geo::to_point(20, 0), geo::to_point(20, 20 * std::tan(10 * std::numbers::pi / 180))};
  CHECK(min_width_mm({spike}) < 0.1);
  geo::Ring right{geo::to_point(0, 0), geo::to_point(10, 0), geo::to_point(0, 10)};
  CHECK(min_width_mm({right}) > 5);
  CHECK(min_width_mm({}) == 0);
}

TEST_CASE("longest_edge_angle: the direction of the outline's longest straight stretch") {
  CHECK(longest_edge_angle_deg({rect(0, 0, 20, 5)}) == doctest::Approx(0).epsilon(1e-6));
  CHECK(longest_edge_angle_deg({rect(0, 0, 5, 20)}) == doctest::Approx(90));
  CHECK(longest_edge_angle_deg(turned({rect(0, 0, 20, 5)}, 30)) == doctest::Approx(30).epsilon(1e-4));
  CHECK(longest_edge_angle_deg(turned({rect(0, 0, 20, 5)}, 120)) == doctest::Approx(120).epsilon(1e-4));
  // The long side split in three by vertices on it is still one edge, longer than the 12 mm side.
  geo::Ring split{geo::to_point(0, 0),  geo::to_point(5, 0),  geo::to_point(10, 0), geo::to_point(15, 0),
                  geo::to_point(15, 12), geo::to_point(0, 12)};
  CHECK(longest_edge_angle_deg({turned({split}, 10)}) == doctest::Approx(10).epsilon(1e-4));
  // The L's longest stretches are its 10 mm outer sides; the first (along x) wins the tie.
  CHECK(longest_edge_angle_deg(L_shape()) == doctest::Approx(0).epsilon(1e-6));
}

TEST_CASE("convex: no hole and no dent") {
  CHECK(is_convex({rect(0, 0, 10, 10)}));
  CHECK(is_convex(disc(4)));
  CHECK(is_convex({rect(0, 0, 20, 0.8)}));
  CHECK_FALSE(is_convex(L_shape()));
  CHECK_FALSE(is_convex({rect(0, 0, 20, 20), rect(5, 5, 10, 10, false)}));
  // A vertex 5 µm inside the hull is noise; 0.1 mm is a dent.
  geo::Ring noisy{geo::to_point(0, 0), geo::to_point(10, 0), geo::to_point(10, 10), geo::to_point(5, 9.995),
                  geo::to_point(0, 10)};
  CHECK(is_convex({noisy}));
  geo::Ring dented{geo::to_point(0, 0), geo::to_point(10, 0), geo::to_point(10, 10), geo::to_point(5, 9.9),
                   geo::to_point(0, 10)};
  CHECK_FALSE(is_convex({dented}));
}

TEST_CASE("island_under: the island of the layer below that overlaps most") {
  geo::Layer below;
  auto add = [&](geo::Ring r) {
    geo::Island i;
    i.shape.outer = std::move(r);
    below.islands.push_back(i);
  };
  add(rect(0, 0, 4, 10));
  add(rect(5, 0, 20, 10));
  add(rect(30, 0, 40, 10));
  CHECK(island_under({rect(3, 2, 8, 8)}, below) == 1);   // 1×6 on the first, 3×6 on the second
  CHECK(island_under({rect(0, 2, 4.5, 8)}, below) == 0);
  CHECK(island_under({rect(22, 0, 28, 10)}, below) == -1);
}
