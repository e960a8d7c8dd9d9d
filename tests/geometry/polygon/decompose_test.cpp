#include <doctest/doctest.h>

#include <fmt/format.h>

#include <cmath>

#include "geometry/polygon/decompose.h"
#include "geometry/polygon/resolve.h"
#include "polygon_checks.h"

using namespace tranche;
using namespace tranche::geo;
using test::mm_ring;
using test::rect;
using test::reversed;

namespace {

Island island_of(const Rings& loops) {
  Report rep;
  auto r = resolve_islands(loops, {}, rep);
  REQUIRE(r.ok());
  REQUIRE(r->size() == 1);
  return (*r)[0];
}

// Decomposes and checks every property; returns the cell count.
int cells_for(const Island& is, double angle) {
  DecomposeStats st;
  auto cells = decompose(is.shape, angle, &st);
  REQUIRE_MESSAGE(cells.ok(), (cells.ok() ? "" : cells.error().to_string()));
  const std::string problem = test::cells_problem(is, *cells, angle);
  CHECK_MESSAGE(problem.empty(), fmt::format("{} at {}°", problem, angle));
  CHECK(st.cells == static_cast<int>(cells->size()));
  return static_cast<int>(cells->size());
}

Ring comb(int teeth, double tooth_w, double gap, double tooth_h, double base_h) {
  // Teeth pointing up (+y) from a base.
  Ring r;
  const double w = teeth * tooth_w + (teeth - 1) * gap;
  r.push_back(to_point(0, 0));
  r.push_back(to_point(w, 0));
  for (int i = teeth - 1; i >= 0; --i) {
    const double x0 = i * (tooth_w + gap);
    r.push_back(to_point(x0 + tooth_w, base_h + tooth_h));
    r.push_back(to_point(x0, base_h + tooth_h));
    if (i > 0) {
      r.push_back(to_point(x0, base_h));
      r.push_back(to_point(x0 - gap, base_h));
    }
  }
  return r;
}

}  // namespace

TEST_CASE("decompose: convex shapes are one cell at every angle") {
  const Island sq = island_of({mm_ring({{0, 0}, {10, 0}, {10, 10}, {0, 10}})});
  const Island diamond = island_of({mm_ring({{5, 0}, {10, 5}, {5, 10}, {0, 5}})});
  for (int a = 0; a < 360; a += 15) {
    CHECK(cells_for(sq, a) == 1);
    CHECK(cells_for(diamond, a) == 1);
  }
}

TEST_CASE("decompose: comb with teeth across and along the fill lines") {
  const Island c = island_of({comb(10, 2, 3, 20, 5)});
  // Fill lines across the teeth (horizontal): each tooth needs its own cell; the base joins one.
  CHECK(cells_for(c, 0) == 10);
  // Fill lines along the teeth (vertical): the whole comb is monotone.
  CHECK(cells_for(c, 90) == 1);
  for (int a : {30, 45, 60, 120, 135, 170}) CHECK(cells_for(c, a) >= 1);
}

TEST_CASE("decompose: a ring with a hole at every angle from 0 to 180") {
  const Island ring = island_of({mm_ring({{0, 0}, {40, 0}, {40, 30}, {0, 30}}),
                                 reversed(mm_ring({{10, 10}, {30, 10}, {30, 20}, {10, 20}}))});
  for (int a = 0; a <= 180; ++a) CHECK(cells_for(ring, a) == 2);
  std::mt19937_64 rng(1);
  const Ring outer = test::star(rng, 0, 0, 2e7, 2e7, 64);
  const Island round = island_of({outer, reversed(test::star(rng, 0, 0, 1e7, 1e7, 48))});
  for (int a = 0; a <= 180; ++a) CHECK(cells_for(round, a) == 2);
}

TEST_CASE("decompose: a plate with 100 holes") {
  Rings loops{rect(0, 0, 115000000, 115000000)};
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      const coord_t x = 5000000 + i * 11000000, y = 5000000 + j * 11000000;
      Ring hole;
      for (int k = 0; k < 24; ++k) {
        const double t = -2 * M_PI * k / 24;  // clockwise
        hole.emplace_back(x + 3000000 + std::llround(3000000 * std::cos(t)),
                          y + 3000000 + std::llround(3000000 * std::sin(t)));
      }
      loops.push_back(hole);
    }
  }
  const Island plate = island_of(loops);
  REQUIRE(plate.shape.holes.size() == 100);
  for (double a : {0.0, 45.0, 90.0, 135.0, 17.0}) {
    const int n = cells_for(plate, a);
    CHECK(n >= 11);   // a fill line through a row of holes meets 11 intervals
    CHECK(n <= 201);  // at most one cut down from each hole's bottom and up from its top
  }
}

TEST_CASE("decompose: spiral") {
  // A square spiral corridor, 1 mm wide, 6 turns.
  Ring inner, outer;
  double x = 0, y = 0, len = 2;
  std::vector<std::pair<double, double>> path{{0, 0}};
  for (int i = 0; i < 24; ++i) {
    const int d = i % 4;
    x += (d == 0 ? len : d == 2 ? -len : 0);
    y += (d == 1 ? len : d == 3 ? -len : 0);
    path.emplace_back(x, y);
    if (d % 2 == 1) len += 2;
  }
  ClipperLib::ClipperOffset off;
  Ring p;
  for (auto [px, py] : path) p.push_back(to_point(px, py));
  off.AddPath(p, ClipperLib::jtMiter, ClipperLib::etOpenButt);
  Rings out;
  off.Execute(out, 0.5e6);
  const Island s = island_of(out);
  for (int a = 0; a < 180; a += 10) CHECK(cells_for(s, a) >= 1);
}

TEST_CASE("decompose: thin slivers, collinear runs and edges parallel to the fill direction") {
  // 0.01 mm wide sliver, 20 mm long, at several angles.
  const Island sliver = island_of({Ring{{0, 0}, {20000000, 0}, {20000000, 10000}, {0, 10000}}});
  for (int a = 0; a < 180; a += 5) CHECK(cells_for(sliver, a) == 1);
  const Island run = island_of({mm_ring(
      {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 1}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 1}})});
  CHECK(cells_for(run, 0) == 2);
  CHECK(cells_for(run, 90) == 1);
  CHECK(cells_for(run, 45) >= 1);
  // Staircase whose treads are exactly parallel to the fill lines at 0° and whose risers are at 90°.
  Ring stairs{{0, 0}};
  for (int i = 0; i < 8; ++i) {
    stairs.push_back(to_point(i + 1, i));
    stairs.push_back(to_point(i + 1, i + 1));
  }
  stairs.push_back(to_point(0, 8));
  const Island st = island_of({stairs});
  CHECK(cells_for(st, 0) == 1);
  CHECK(cells_for(st, 90) == 1);
  CHECK(cells_for(st, 45) >= 1);
}

TEST_CASE("decompose: squares rotated so that vertices align with the sweep") {
  for (int a = 0; a < 180; a += 15) {
    const double r = a * M_PI / 180;
    Ring sq;
    for (int k = 0; k < 4; ++k) {
      const double t = r + k * M_PI / 2;
      sq.push_back(to_point(10 * std::cos(t), 10 * std::sin(t)));
    }
    const Island is = island_of({sq});
    for (int b : {0, 45, 90, 135, a, a + 45}) CHECK(cells_for(is, b) == 1);
  }
}

TEST_CASE("decompose: pinch points inside an island") {
  const Island c =
      island_of({mm_ring({{0, 0}, {10, 0}, {10, 10}, {0, 10}}), mm_ring({{5, 10}, {6, 8}, {5, 6}, {4, 8}})});
  REQUIRE(c.shape.holes.size() == 1);
  const Island holes =
      island_of({mm_ring({{0, 0}, {30, 0}, {30, 30}, {0, 30}}), mm_ring({{10, 10}, {10, 20}, {15, 15}}),
                 mm_ring({{15, 15}, {20, 20}, {20, 10}})});
  const Island side =
      island_of({mm_ring({{0, 0}, {10, 0}, {10, 10}, {0, 10}}), mm_ring({{0, 5}, {4, 7}, {6, 5}, {4, 3}})});
  for (int a = 0; a < 180; a += 5) {
    cells_for(c, a);
    cells_for(holes, a);
    cells_for(side, a);
  }
}

TEST_CASE("decompose: the island wrapper names the layer and island") {
  Report rep;
  Layer layer;
  layer.index = 7;
  layer.loops = {rect(0, 0, 10, 10), rect(20, 0, 30, 10)};
  REQUIRE(resolve_layer(layer, {}, rep).ok());
  auto c = decompose_island(layer, 1, 30);
  REQUIRE(c.ok());
  REQUIRE(c->size() == 1);
  CHECK((*c)[0].fill_angle_deg == 30);
  Layer far;
  far.index = 3;
  Island bad;
  bad.shape.outer = rect(0, 0, coord_t{1} << 40, coord_t{1} << 40);  // beyond the sweep's range
  far.islands.push_back(bad);
  auto e = decompose_island(far, 0, 45);
  REQUIRE_FALSE(e.ok());
  CHECK(e.error().where.rfind("layer 3 island 0", 0) == 0);
}
