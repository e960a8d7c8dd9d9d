// Print order within a layer: where it starts, the island order, and an island's loops and
// zig-zags (infill first, seams, joins).
#include <doctest/doctest.h>

#include "geometry/plan/print_order.h"
#include "tests/support/print_fixture.h"

using namespace tranche;
using plan::IslandPlan;
using plan::PathPlan;
using schema::PathKind;
using schema::PropId;

namespace {

IslandPlan island_at(int index, double x0, double y0, double size) {
  IslandPlan ip;
  ip.index = index;
  ip.shape.push_back(test::square_mm(x0, y0, x0 + size, y0 + size));
  return ip;
}

PathPlan loop(int depth, const geo::Ring& ring) {
  PathPlan p;
  p.kind = depth == 0 ? PathKind::OuterPerimeter : PathKind::InnerPerimeter;
  p.perimeter = depth;
  p.closed = true;
  p.pts = ring;
  return p;
}

PathPlan line(double x0, double y0, double x1, double y1) {
  PathPlan p;
  p.kind = PathKind::Infill;
  p.pts = {geo::to_point(x0, y0), geo::to_point(x1, y1)};
  p.border = {schema::Border::None};
  p.props[PropId::InfillDensity] = 0.2;
  return p;
}

}  // namespace

TEST_CASE("print order: a layer starts at the middle of its rear edge") {
  std::vector<IslandPlan> islands{island_at(0, 0, 0, 10), island_at(1, 30, 20, 10)};
  CHECK(plan::layer_start(islands) == geo::to_point(20, 30));
  CHECK(plan::layer_start({}) == geo::Point(0, 0));
}

TEST_CASE("print order: islands nearest first from the start, each next one from the previous centre") {
  std::vector<IslandPlan> islands{island_at(0, 0, 0, 10), island_at(1, 100, 0, 10), island_at(2, 20, 0, 10)};
  const geo::Point start = geo::to_point(0, 50);
  CHECK(plan::island_order(islands, start, 0) == std::vector<size_t>{0, 2, 1});
  CHECK(plan::island_order(islands, start, 1) == std::vector<size_t>{1, 2, 0});  // odd layers backwards
}

TEST_CASE("print order: perimeters first puts loops innermost first, then the fill nearest first") {
  IslandPlan ip = island_at(0, 0, 0, 20);
  ip.props[PropId::InfillFirst] = 0;
  ip.props[PropId::OuterFirst] = 0;
  ip.props[PropId::Seam] = static_cast<double>(schema::Seam::Rear);
  ip.paths = {loop(0, test::square_mm(0.2, 0.2, 19.8, 19.8)), loop(1, test::square_mm(0.6, 0.6, 19.4, 19.4)),
              line(1, 1, 1, 19), line(10, 1, 10, 19)};
  geo::Point pos = geo::to_point(10, 30);
  plan::order_island(ip, {}, 0.2, pos);
  REQUIRE(ip.paths.size() == 4);
  CHECK(ip.paths[0].perimeter == 1);
  CHECK(ip.paths[1].perimeter == 0);
  CHECK(ip.paths[2].kind == PathKind::Infill);
  // Rear seam: the loop starts at its vertex of largest y, and is closed.
  CHECK(ip.paths[1].pts.front().Y == geo::to_point(0, 19.8).Y);
  CHECK(ip.paths[1].pts.front() == ip.paths[1].pts.back());
  for (size_t i = 0; i < ip.paths.size(); ++i) CHECK(ip.paths[i].index == static_cast<int>(i));
  CHECK(pos == ip.paths.back().pts.back());
}

TEST_CASE("print order: infill first runs the last zig-zag into the innermost loop") {
  IslandPlan ip = island_at(0, 0, 0, 20);
  ip.props[PropId::InfillFirst] = 1;
  ip.paths = {loop(0, test::square_mm(0.2, 0.2, 19.8, 19.8)), loop(1, test::square_mm(0.6, 0.6, 19.4, 19.4)),
              line(1, 1, 1, 19)};
  geo::Point pos = geo::to_point(1, 0);
  plan::order_island(ip, {}, 0.2, pos);
  REQUIRE(ip.paths.size() == 3);
  CHECK(ip.paths[0].kind == PathKind::Infill);
  CHECK(ip.paths[1].perimeter == 1);
  // The zig-zag ends 0.4 mm from the inner loop: it is extended to the loop's new seam there.
  CHECK(ip.paths[0].pts.back() == ip.paths[1].pts.front());
  CHECK(ip.paths[0].border.back() == schema::Border::Artificial);
}

TEST_CASE("print order: two zig-zags of one region ending next to each other are joined") {
  IslandPlan ip = island_at(0, 0, 0, 20);
  ip.props[PropId::InfillFirst] = 0;
  ip.paths = {line(1, 1, 1, 19), line(1.5, 19, 1.5, 1)};
  std::vector<plan::FillGrid> regions;
  regions.push_back({PathKind::Infill, toolpath::EdgeGrid({test::square_mm(0.5, 0.5, 19.5, 19.5)})});
  geo::Point pos = geo::to_point(1, 0);
  plan::order_island(ip, regions, 0.2, pos);
  REQUIRE(ip.paths.size() == 2);
  CHECK(ip.paths[1].pts.front() == ip.paths[0].pts.back());  // a short extrusion, not a travel
  // Without the region's edges (or across its border) they stay apart.
  IslandPlan apart = island_at(0, 0, 0, 20);
  apart.props[PropId::InfillFirst] = 0;
  apart.paths = {line(1, 1, 1, 19), line(1.5, 19, 1.5, 1)};
  pos = geo::to_point(1, 0);
  plan::order_island(apart, {}, 0.2, pos);
  CHECK(apart.paths[1].pts.size() == 2);
}
