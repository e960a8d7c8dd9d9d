// Travel: one retraction policy, in a layer and across a layer change.
#include <doctest/doctest.h>

#include "geometry/plan/travel.h"
#include "tests/support/print_fixture.h"

using namespace tranche;
using plan::TravelPolicy;

namespace {

// A ring-shaped part: a 20 mm square with a 10 mm hole in the middle.
toolpath::Comber ring_comber() {
  geo::Ring hole = test::square_mm(5, 5, 15, 15);
  ClipperLib::ReversePath(hole);
  return toolpath::Comber({test::square_mm(0, 0, 20, 20), hole});
}

TravelPolicy policy() {
  TravelPolicy p;
  p.retract_mm = 0.8;
  p.before_mm = 2;
  p.long_mm = 100;
  return p;
}

}  // namespace

TEST_CASE("travel: short travels never retract; long ones always; between, only when leaving the part") {
  const toolpath::Comber c = ring_comber();
  const TravelPolicy p = policy();
  auto t = plan::route_travel(&c, geo::to_point(1, 1), geo::to_point(2, 1), p);
  CHECK_FALSE(t.retract);
  CHECK(t.via.empty());
  // Across the hole: combed around it, inside the part, so no retraction.
  t = plan::route_travel(&c, geo::to_point(10, 2), geo::to_point(10, 18), p);
  CHECK_FALSE(t.retract);
  CHECK_FALSE(t.via.empty());
  CHECK(t.length_mm > 16);
  // Not combed (the skirt, a replaced island): it leaves the part.
  t = plan::route_travel(nullptr, geo::to_point(10, 2), geo::to_point(10, 18), p);
  CHECK(t.retract);
  CHECK(t.via.empty());
  TravelPolicy never = p;
  never.retract_mm = 0;
  CHECK_FALSE(plan::route_travel(nullptr, geo::to_point(10, 2), geo::to_point(10, 18), never).retract);
  TravelPolicy longer = p;
  longer.long_mm = 5;
  CHECK(plan::route_travel(&c, geo::to_point(10, 2), geo::to_point(10, 18), longer).retract);
}

TEST_CASE("travel: the layer change steps in from a point just outside the layer") {
  const toolpath::Comber c = ring_comber();
  const TravelPolicy p = policy();
  // From 0.3 mm outside the outer wall, across the hole: it steps in, then combs.
  auto t = plan::route_travel(&c, geo::to_point(10, -0.3), geo::to_point(10, 18), p, 0.45);
  CHECK_FALSE(t.retract);
  REQUIRE_FALSE(t.via.empty());
  CHECK(t.via.front() != geo::to_point(10, -0.3));
  // Farther out than the tolerance: it retracts.
  CHECK(plan::route_travel(&c, geo::to_point(10, -3), geo::to_point(10, 18), p, 0.45).retract);
}
