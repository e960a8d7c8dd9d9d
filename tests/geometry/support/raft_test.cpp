#include <doctest/doctest.h>

#include "tests/geometry/toolpath/fixtures.h"
#include "geometry/support/raft.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/relations.h"

using namespace tranche;
using namespace tranche::support;
using doctest::Approx;
using test::rect;

TEST_CASE("raft: the part's layers are renumbered and lifted onto the raft's") {
  auto layers = test::stack(4, 0.2, geo::Polygon{rect(0, 0, 10, 10), {}});
  RaftSpec spec;
  spec.layers = 3;
  spec.first_height = 0.3;
  spec.height = 0.2;
  spec.gap = 0.15;
  lift_onto_raft(layers, spec);
  REQUIRE(layers.size() == 7);
  for (size_t k = 0; k < layers.size(); ++k) CHECK(layers[k].index == static_cast<int>(k));
  for (int k = 0; k < 3; ++k) CHECK(layers[static_cast<size_t>(k)].islands.empty());
  CHECK(layers[0].z_bottom == Approx(0));
  CHECK(layers[0].z_top == Approx(0.3));
  CHECK(layers[2].z_top == Approx(0.7));
  CHECK(layers[3].z_bottom == Approx(0.85));  // the gap: 0.15 mm of air
  CHECK(layers[3].z_top == Approx(1.05));
  CHECK(layers[3].height() == Approx(0.2));
  CHECK(layers[6].z_top == Approx(1.65));
  CHECK(layers[3].islands.size() == 1);

  auto same = test::stack(2, 0.2, geo::Polygon{rect(0, 0, 10, 10), {}});
  lift_onto_raft(same, RaftSpec{});  // no raft: nothing moves
  CHECK(same.size() == 2);
  CHECK(same[1].z_top == Approx(0.4));
}

TEST_CASE("raft: the sheet is the footprint grown, holes filled, clipped to the bed") {
  // A frame (a 20 mm square with a 16 mm hole) and a separate 2 mm square 1 mm beside it.
  geo::Ring hole = rect(2, 2, 18, 18, false);
  geo::Rings foot{rect(0, 0, 20, 20), hole, rect(21, 0, 23, 2)};
  geo::Rings sheet = raft_region(foot, 1.5, {});
  CHECK(sheet.size() == 1);  // one sheet: the hole is rafted over, the square joined
  CHECK(toolpath::area_mm2(sheet) > 23 * 23);
  CHECK(toolpath::area_mm2(sheet) < 26 * 23);
  const geo::BBox2 box = toolpath::bbox(sheet);
  CHECK(geo::to_mm(box.min_x) == Approx(-1.5).epsilon(0.01));
  CHECK(geo::to_mm(box.max_y) == Approx(21.5).epsilon(0.01));
  // A bed that ends at x = 10 cuts it there.
  geo::Rings clipped = raft_region(foot, 1.5, {rect(-100, -100, 10, 100)});
  CHECK(geo::to_mm(toolpath::bbox(clipped).max_x) == Approx(10).epsilon(0.001));
  CHECK(raft_region({}, 1.5, {}).empty());
}

TEST_CASE("raft: its first and top layers are dense, those between sparse") {
  CHECK(raft_layer_dense(0, 1));
  CHECK(raft_layer_dense(0, 3));
  CHECK_FALSE(raft_layer_dense(1, 3));
  CHECK(raft_layer_dense(2, 3));
  CHECK(raft_layer_dense(1, 2));
}
