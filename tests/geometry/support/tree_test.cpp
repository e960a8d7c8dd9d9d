#include <doctest/doctest.h>

#include "tests/geometry/support/project_input.h"
#include "tests/geometry/toolpath/fixtures.h"
#include "geometry/support/tree.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/relations.h"

using namespace tranche;
using namespace tranche::support;
using test::rect;

namespace {

// A 4 mm stem (layers 0..39) under a 24 mm cap (layers 40..44), 0.2 mm layers.
std::vector<geo::Layer> mushroom() { return test::mushroom_stack(40, 5, rect(10, 10, 14, 14), rect(0, 0, 24, 24)); }


double area(const geo::Rings& r) { return toolpath::area_mm2(r); }

}  // namespace

TEST_CASE("tree: branches from tips under a cap merge on their way to the bed, clear of the stem") {
  auto layers = mushroom();
  ProjectInput in = test::project_input(layers);
  const geo::Rings cap = toolpath::difference({rect(0, 0, 24, 24)}, toolpath::offset({rect(10, 10, 14, 14)}, 0.2));
  in.contacts[36].push_back({cap, 0, false});
  TreeResult r = grow_trees(in, TreeSpec{});
  CHECK(r.tips >= 30);                       // a 4 mm grid over 560 mm²
  CHECK(r.trunks_on_bed >= 1);
  CHECK(r.trunks_on_bed < r.tips / 4);       // they merged
  REQUIRE(r.branches.size() == 45);
  CHECK(area(r.branches[36]) > 20);
  CHECK(area(r.branches[0]) > 3);
  CHECK(area(r.branches[0]) < 0.5 * area(cap));  // far less than a column under the cap
  for (size_t k = 37; k < 45; ++k) CHECK(r.branches[k].empty());
  const geo::Rings gap = toolpath::offset({rect(10, 10, 14, 14)}, 0.49);
  for (size_t k = 0; k <= 36; ++k) CHECK(area(toolpath::intersection(r.branches[k], gap)) < 1e-6);
}

TEST_CASE("tree: a branch that meets the part ends on it, or takes its tree with it on bed only") {
  // A 20 mm block (layers 0..9), a 4 mm post on it (layers 10..29), a 20 mm slab on top (30..32):
  // the slab's trees cannot reach the bed.
  auto layers = test::stack(33, 0.2, geo::Polygon{rect(0, 0, 20, 20), {}});
  for (size_t k = 10; k < 30; ++k) layers[k].islands[0].shape.outer = rect(8, 8, 12, 12);
  const geo::Rings slab = toolpath::difference({rect(0, 0, 20, 20)}, toolpath::offset({rect(8, 8, 12, 12)}, 0.2));
  {
    ProjectInput in = test::project_input(layers);
    in.contacts[27].push_back({slab, 0, false});
    TreeResult r = grow_trees(in, TreeSpec{});
    CHECK(area(r.branches[20]) > 3);
    CHECK(r.branches[10].empty());  // the z gap over the block's top
    for (size_t k = 0; k < 10; ++k) CHECK(r.branches[k].empty());
    CHECK(r.blocked_mm2 == 0);
  }
  {
    ProjectInput in = test::project_input(layers);
    in.contacts[27].push_back({slab, 0, true});
    TreeResult r = grow_trees(in, TreeSpec{});
    for (const auto& b : r.branches) CHECK(b.empty());
    CHECK(r.blocked_mm2 > 0);
  }
}

TEST_CASE("tree: a contact too small for the grid still gets a tip") {
  auto layers = test::stack(20, 0.2, geo::Polygon{rect(0, 0, 1, 1), {}});
  ProjectInput in = test::project_input(layers);
  in.contacts[15].push_back({{rect(5.1, 5.1, 6.9, 6.9)}, 0, false});
  TreeResult r = grow_trees(in, TreeSpec{});
  CHECK(r.tips == 1);
  CHECK(r.trunks_on_bed == 1);
  CHECK(area(r.branches[0]) > 1);
}
