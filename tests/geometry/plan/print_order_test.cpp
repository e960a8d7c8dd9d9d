// Print order within a layer: where it starts, the island order, and an island's loops and
// zig-zags (infill first, seams, joins).
#include <doctest/doctest.h>

#include <set>

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

namespace {
// A 20 mm square island with two loops, perimeters first, seam mode `m`, its outer loop's start.
geo::Point outer_seam(schema::Seam m, const plan::SeamFrame& frame, double seam_x = 0, double seam_y = 0,
                      int island = 0) {
  IslandPlan ip = island_at(island, 0, 0, 20);
  ip.props[PropId::InfillFirst] = 0;
  ip.props[PropId::OuterFirst] = 1;
  ip.props[PropId::Seam] = static_cast<double>(m);
  ip.props[PropId::SeamX] = seam_x;
  ip.props[PropId::SeamY] = seam_y;
  geo::Ring outer;  // a square with a vertex every mm
  for (int i = 0; i < 20; ++i) outer.push_back(geo::to_point(i, 0));
  for (int i = 0; i < 20; ++i) outer.push_back(geo::to_point(20, i));
  for (int i = 20; i > 0; --i) outer.push_back(geo::to_point(i, 20));
  for (int i = 20; i > 0; --i) outer.push_back(geo::to_point(0, i));
  ip.paths = {loop(0, outer), loop(1, test::square_mm(0.6, 0.6, 19.4, 19.4))};
  geo::Point pos = geo::to_point(10, 30);
  plan::order_island(ip, {}, 0.2, pos, frame);
  REQUIRE(ip.paths.size() == 2);
  REQUIRE(ip.paths[0].perimeter == 0);
  CHECK(ip.paths[0].pts.front() == ip.paths[0].pts.back());
  return ip.paths[0].pts.front();
}
}  // namespace

TEST_CASE("print order: seam = point starts the loop at its vertex nearest (seam_x, seam_y) on the bed") {
  // The model sits 100 mm right and 50 mm back on the bed: the point (105, 45) is (5, -5) on it.
  const plan::SeamFrame frame{3, geo::to_point(100, 50)};
  CHECK(outer_seam(schema::Seam::Point, frame, 105, 45) == geo::to_point(5, 0));
  CHECK(outer_seam(schema::Seam::Point, frame, 130, 62.4) == geo::to_point(20, 12));
}

TEST_CASE("print order: seam = random is the same for the same layer and island, and moves between layers") {
  const geo::Point a = outer_seam(schema::Seam::Random, {5, {}});
  CHECK(outer_seam(schema::Seam::Random, {5, {}}) == a);
  std::set<std::pair<int64_t, int64_t>> seen;
  for (int layer = 0; layer < 20; ++layer) {
    geo::Point p = outer_seam(schema::Seam::Random, {layer, {}});
    seen.insert({p.X, p.Y});
  }
  CHECK(seen.size() >= 10);
  // Another island of the same layer gets its own.
  std::set<std::pair<int64_t, int64_t>> islands;
  for (int i = 0; i < 10; ++i) {
    geo::Point p = outer_seam(schema::Seam::Random, {5, {}}, 0, 0, i);
    islands.insert({p.X, p.Y});
  }
  CHECK(islands.size() >= 5);
}

TEST_CASE("print order: seam = random draws along the edges, not only at a coarse loop's vertices") {
  int off_corner = 0;
  for (int layer = 0; layer < 20; ++layer) {
    IslandPlan ip = island_at(0, 0, 0, 20);
    ip.props[PropId::InfillFirst] = 0;
    ip.props[PropId::Seam] = static_cast<double>(schema::Seam::Random);
    ip.paths = {loop(0, test::square_mm(0.2, 0.2, 19.8, 19.8))};
    geo::Point pos = geo::to_point(10, 30);
    plan::order_island(ip, {}, 0.2, pos, {layer, {}});
    REQUIRE(ip.paths.size() == 1);
    const auto& pts = ip.paths[0].pts;
    CHECK(pts.front() == pts.back());
    const geo::Point s = pts.front();
    // On the square's outline, and (nearly always) between its corners.
    const bool on_x = s.X == geo::to_point(0.2, 0).X || s.X == geo::to_point(19.8, 0).X;
    const bool on_y = s.Y == geo::to_point(0, 0.2).Y || s.Y == geo::to_point(0, 19.8).Y;
    CHECK((on_x || on_y));
    off_corner += !(on_x && on_y);
    // The same layer again: the same seam.
    IslandPlan again = island_at(0, 0, 0, 20);
    again.props = ip.props;
    again.paths = {loop(0, test::square_mm(0.2, 0.2, 19.8, 19.8))};
    geo::Point pos2 = geo::to_point(10, 30);
    plan::order_island(again, {}, 0.2, pos2, {layer, {}});
    CHECK(again.paths[0].pts.front() == s);
  }
  CHECK(off_corner >= 18);
}
