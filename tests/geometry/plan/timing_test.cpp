// Timing: one time model for the layer, its slowdown and the layer change.
#include <doctest/doctest.h>

#include "geometry/plan/timing.h"
#include "geometry/plan/travel.h"
#include "geometry/toolpath/flow.h"
#include "tests/support/print_fixture.h"

using namespace tranche;
using plan::TravelPolicy;
using schema::PathKind;
using schema::PropId;

namespace {

TravelPolicy policy() {
  TravelPolicy p;
  p.retract_mm = 0.8;
  p.before_mm = 2;
  p.long_mm = 100;
  return p;
}

}  // namespace

TEST_CASE("timing: one straight extrusion takes its trapezoid; the clamp never goes below min speed") {
  plan::LayerPlan lp;
  lp.height = 0.2;
  plan::IslandPlan ip;
  plan::PathPlan path;
  path.kind = PathKind::Infill;
  path.pts = {geo::to_point(0, 0), geo::to_point(100, 0)};
  path.pieces = {{50, 1}};
  ip.paths.push_back(path);
  lp.islands.push_back(ip);
  toolpath::MotionLimits m;
  m.print_accel = 1000;
  const auto t = plan::layer_time(lp, m, policy(), 0.2);
  CHECK(t.total_s == doctest::Approx(toolpath::trapezoid_time(100, 50, 0, 0, 1000)));
  CHECK(t.extrude_s == doctest::Approx(t.total_s));  // it was 0: an extrusion counted the move before it
  CHECK(t.volume_mm3 == doctest::Approx(100 * toolpath::bead_area_mm2(0.45, 0.2)));
  CHECK(plan::slowed(50, 0.5, 10) == 25);
  CHECK(plan::slowed(50, 0.1, 10) == 10);  // not below min_print_speed
  CHECK(plan::slowed(8, 0.5, 10) == 8);    // unless it already was
}

TEST_CASE("timing: min_layer_time slows a fast layer down to it") {
  // One 100 mm line at 50 mm/s (about 2 s); min_layer_time 20 s. The slowdown used to see no
  // extruding time on such a layer (each move's time was credited to the move after it) and left
  // it at 2 s.
  plan::LayerPlan lp;
  lp.height = 0.2;
  lp.props[PropId::MinLayerTime] = 20;
  plan::IslandPlan ip;
  plan::PathPlan path;
  path.pts = {geo::to_point(0, 0), geo::to_point(100, 0)};
  path.pieces = {{50, 1}};
  ip.paths.push_back(path);
  lp.islands.push_back(ip);
  plan::time_and_slow_down(lp, {}, policy(), 1);
  CHECK(lp.slowed);
  CHECK(lp.islands[0].paths[0].pieces[0].speed == doctest::Approx(5).epsilon(0.05));
  CHECK(lp.time_s == doctest::Approx(20).epsilon(0.05));
  // Not below min_print_speed: 10 mm/s gives 10 s, short of 20.
  plan::LayerPlan capped = lp;
  capped.islands[0].paths[0].pieces[0].speed = 50;
  plan::time_and_slow_down(capped, {}, policy(), 10);
  CHECK(capped.islands[0].paths[0].pieces[0].speed == 10);
}

TEST_CASE("timing: the layer change counts retract, z and travel") {
  const TravelPolicy p = policy();
  toolpath::MotionLimits m;
  const geo::Point a = geo::to_point(0, 0), b = geo::to_point(30, 0);
  const double plain = plan::layer_change_time(&a, {}, b, false, 0.2, m, p);
  CHECK(plain == doctest::Approx(0.2 / m.z_speed +
                                 toolpath::trapezoid_time(30, p.travel_speed, 0, 0, m.travel_accel)));
  CHECK(plan::layer_change_time(&a, {}, b, true, 0.2, m, p) == doctest::Approx(plain + p.retract_time_s()));
  CHECK(plan::layer_change_time(nullptr, {}, b, false, 0.2, m, p) == doctest::Approx(0.2 / m.z_speed));
}
