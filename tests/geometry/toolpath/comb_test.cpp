// Combing: travels routed inside the part around holes and notches.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "fixtures.h"
#include "geometry/toolpath/comb.h"
#include "geometry/toolpath/edge_grid.h"

using namespace tranche;
using namespace tranche::toolpath;
using geo::to_point;

namespace {

double length_mm(const geo::Point& a, const geo::Ring& via, const geo::Point& b) {
  double len = 0;
  geo::Point p = a;
  for (const auto& q : via) len += std::hypot(double(q.X - p.X), double(q.Y - p.Y)), p = q;
  len += std::hypot(double(b.X - p.X), double(b.Y - p.Y));
  return len * geo::kMmPerUnit;
}

// Every leg of the route stays inside `material`, at least `margin_mm` from its border (checked
// by sampling points on each leg against the material shrunk by a little less).
void check_inside(const geo::Rings& material, const geo::Point& a, const geo::Ring& via,
                  const geo::Point& b) {
  EdgeGrid border(material);
  geo::Ring pts{a};
  pts.insert(pts.end(), via.begin(), via.end());
  pts.push_back(b);
  for (size_t i = 1; i < pts.size(); ++i) {
    CHECK_FALSE(border.crosses(pts[i - 1], pts[i]));
    for (int k = 0; k <= 20; ++k) {
      double t = k / 20.0;
      geo::Point q(
          pts[i - 1].X + static_cast<geo::coord_t>(std::llround(t * double(pts[i].X - pts[i - 1].X))),
          pts[i - 1].Y + static_cast<geo::coord_t>(std::llround(t * double(pts[i].Y - pts[i - 1].Y))));
      CHECK(border.inside(q));
    }
  }
}

}  // namespace

TEST_CASE("comb: a travel across a hole goes around it, inside the part, in few moves") {
  // 30 × 20 plate with a 10 × 10 hole in the middle.
  geo::Rings plate{test::rect(0, 0, 30, 20), test::rect(10, 5, 20, 15, false)};
  Comber c(plate);
  auto a = to_point(5, 10), b = to_point(25, 10);
  CHECK_FALSE(c.direct(a, b));
  CHECK(c.inside(a));
  auto via = c.route(a, b);
  REQUIRE(via);
  CHECK(via->size() == 2);  // around two corners of the hole
  check_inside(plate, a, *via, b);
  // Around the hole's corners (0.1 mm margin): 2 × hypot(4.9, 5.1) + 10.2, well under 2 × 20.
  CHECK(length_mm(a, *via, b) == doctest::Approx(2 * std::hypot(4.9, 5.1) + 10.2).epsilon(0.01));
}

TEST_CASE("comb: an island given with its shrunk region (support) is routed along that region, not shrunk again") {
  // The plate with its hole as a ready island, its region 0.5 mm in; a separate square to shrink.
  geo::Rings plate{test::rect(0, 0, 30, 20), test::rect(10, 5, 20, 15, false)};
  geo::Rings inner{test::rect(0.5, 0.5, 29.5, 19.5), test::rect(9.5, 4.5, 20.5, 15.5, false)};
  geo::Rings square{test::rect(40, 0, 50, 10)};
  Comber c(square, plate, inner);
  auto a = to_point(5, 10), b = to_point(25, 10);
  CHECK(c.inside(a));
  CHECK_FALSE(c.direct(a, b));
  auto via = c.route(a, b);
  REQUIRE(via);
  check_inside(plate, a, *via, b);
  // Round the ready region's corners, 0.5 mm off the hole (not the 0.1 mm margin).
  CHECK(length_mm(a, *via, b) == doctest::Approx(2 * std::hypot(4.5, 5.5) + 11).epsilon(0.01));
  // The other island is shrunk by the margin as before: a travel inside it is routed (straight)...
  auto inside = c.route(to_point(41, 1), to_point(49, 9));
  REQUIRE(inside);
  CHECK(inside->empty());  // no detour
  CHECK_FALSE(c.route(to_point(40.05, 5), to_point(49, 9)));  // ...from within its margin, not
  CHECK_FALSE(c.route(a, to_point(45, 5)));  // and none between islands
}

TEST_CASE("comb: a straight travel inside the part needs no route") {
  geo::Rings plate{test::rect(0, 0, 30, 20), test::rect(10, 5, 20, 15, false)};
  Comber c(plate);
  CHECK(c.direct(to_point(1, 1), to_point(29, 2)));
  CHECK(c.direct(to_point(1, 1), to_point(1, 19)));
}

TEST_CASE("comb: a travel across a notch follows the notch's bottom") {
  // U shape: 30 wide, 20 tall, a 10 × 15 notch from the top.
  geo::Ring u{to_point(0, 0),  to_point(30, 0), to_point(30, 20), to_point(20, 20),
              to_point(20, 5), to_point(10, 5), to_point(10, 20), to_point(0, 20)};
  geo::Rings shape{u};
  Comber c(shape);
  auto a = to_point(5, 18), b = to_point(25, 18);
  CHECK_FALSE(c.direct(a, b));
  auto via = c.route(a, b);
  REQUIRE(via);
  CHECK(via->size() == 2);
  check_inside(shape, a, *via, b);
  for (const auto& q : *via) CHECK(geo::to_mm(q.Y) <= 5.0001);  // round the notch's bottom corners
}

TEST_CASE("comb: no route between islands, from outside, or when the detour is too long") {
  SUBCASE("two islands") {
    geo::Rings two{test::rect(0, 0, 10, 10), test::rect(20, 0, 30, 10)};
    Comber c(two);
    CHECK_FALSE(c.direct(to_point(5, 5), to_point(25, 5)));
    CHECK_FALSE(c.route(to_point(5, 5), to_point(25, 5)));
  }
  SUBCASE("an end outside the part, or within the margin of its border") {
    geo::Rings plate{test::rect(0, 0, 30, 20), test::rect(10, 5, 20, 15, false)};
    Comber c(plate);
    CHECK_FALSE(c.route(to_point(-2, 10), to_point(25, 10)));
    CHECK_FALSE(c.route(to_point(0.05, 10), to_point(25, 10)));
  }
  SUBCASE("a deep notch: going around is much longer than retracting") {
    // A notch 80 mm deep and 2 mm wide: the way around is ~160 mm for a 4 mm hop.
    geo::Ring u{to_point(0, 0),  to_point(10, 0), to_point(10, 100), to_point(6, 100),
                to_point(6, 20), to_point(4, 20), to_point(4, 100),  to_point(0, 100)};
    Comber c(geo::Rings{u});
    CHECK_FALSE(c.route(to_point(2, 99), to_point(8, 99)));
  }
}

TEST_CASE("comb: a travel crossing two holes is routed around both") {
  geo::Rings plate{test::rect(0, 0, 50, 20), test::rect(10, 5, 20, 15, false),
                   test::rect(30, 5, 40, 15, false)};
  Comber c(plate);
  auto a = to_point(5, 10), b = to_point(45, 10);
  auto via = c.route(a, b);
  REQUIRE(via);
  check_inside(plate, a, *via, b);
  CHECK(length_mm(a, *via, b) < 2 * 40);
}

TEST_CASE("edge grid: hits are sorted along the segment and name their ring and edge") {
  geo::Rings plate{test::rect(0, 0, 30, 20), test::rect(10, 5, 20, 15, false)};
  EdgeGrid g(plate);
  auto h = g.hits(to_point(5, 10), to_point(25, 10));
  REQUIRE(h.size() == 2);
  CHECK(h[0].t == doctest::Approx(0.25));
  CHECK(h[1].t == doctest::Approx(0.75));
  CHECK(h[0].ring == 1);
  CHECK(h[1].ring == 1);
  CHECK(h[0].edge != h[1].edge);
  CHECK(g.hits(to_point(1, 1), to_point(2, 2)).empty());
}

TEST_CASE("combing: the layer change steps in from a point just outside the layer") {
  Comber c(geo::Rings{test::rect(0, 0, 20, 20)});
  // Inside: the point itself.
  auto in = c.enter(to_point(5, 5), 0.45);
  REQUIRE(in);
  CHECK(*in == to_point(5, 5));
  // 0.2 mm outside the right side (the layer below's outer wall, where the wall slopes in): the
  // nearest point of the material shrunk by its margin, a little further in.
  auto near = c.enter(to_point(20.2, 10), 0.45);
  REQUIRE(near);
  CHECK(geo::to_mm(near->X) < 19.9);
  CHECK(geo::to_mm(near->X) > 19.89);
  CHECK(near->Y == to_point(0, 10).Y);
  EdgeGrid shrunk(geo::Rings{test::rect(0.1, 0.1, 19.9, 19.9)});
  CHECK(shrunk.inside(*near));
  // Further than the tolerance: nothing (the travel leaves the part and retracts).
  CHECK_FALSE(c.enter(to_point(21, 10), 0.45));
}

TEST_CASE("comb: a travel through a vertex of the route's ring still goes around the hole") {
  // A round hole of 64 sides centred on the travel's line: the shrunk material's ring has a vertex
  // exactly on the line (each of the circle's small turns is one mitre point), where the crossings
  // would be counted once for two edges. The route is found, as between two round holes of a plate.
  geo::Ring hole;
  for (int i = 0; i < 64; ++i) {
    const double t = -2 * std::numbers::pi * i / 64;  // clockwise: a hole
    hole.push_back(geo::Point(geo::to_units(20 + 3 * std::cos(t)), geo::to_units(20 + 3 * std::sin(t))));
  }
  geo::Rings plate{test::rect(0, 0, 40, 40), hole};
  Comber c(plate);
  auto a = to_point(20, 10), b = to_point(20, 30);
  CHECK_FALSE(c.direct(a, b));
  auto via = c.route(a, b);
  REQUIRE(via);
  check_inside(plate, a, *via, b);
  CHECK(length_mm(a, *via, b) < 20 + 3 * (std::numbers::pi - 2) + 1);
}
