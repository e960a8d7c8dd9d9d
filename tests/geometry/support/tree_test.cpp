#include <doctest/doctest.h>

#include "tests/geometry/support/project_input.h"
#include "tests/geometry/toolpath/fixtures.h"
#include "geometry/support/overhang.h"
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

size_t islands(const geo::Rings& r) { return components(r).size(); }

// The 24 mm cap's contact, 0.2 mm beside the stem, tips on layer 36.
ProjectInput under_cap(const std::vector<geo::Layer>& layers) {
  ProjectInput in = test::project_input(layers);
  in.contacts[36].push_back(
      {toolpath::difference({rect(0, 0, 24, 24)}, toolpath::offset({rect(10, 10, 14, 14)}, 0.2)), 0, false});
  return in;
}

}  // namespace

TEST_CASE("tree: branches from tips under a cap merge on their way to the bed, clear of the stem") {
  auto layers = mushroom();
  ProjectInput in = test::project_input(layers);
  const geo::Rings cap = toolpath::difference({rect(0, 0, 24, 24)}, toolpath::offset({rect(10, 10, 14, 14)}, 0.2));
  in.contacts[36].push_back({cap, 0, false});
  TreeResult r = grow_trees(in, TreeSpec{});
  CHECK(r.tips >= 12);                       // a 7 mm grid over 560 mm²
  CHECK(r.trunks_on_bed >= 1);
  CHECK(r.trunks_on_bed < r.tips / 2);       // they merged
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

TEST_CASE("tree: the tips under one cap start as one island, and every layer has fewer islands than without bars") {
  auto layers = mushroom();
  const ProjectInput in = under_cap(layers);
  TreeSpec apart;
  apart.link_mm = 0;
  const TreeResult joined = grow_trees(in, TreeSpec{}), alone = grow_trees(in, apart);
  REQUIRE(joined.tips == alone.tips);
  CHECK(islands(joined.branches[36]) == 1);           // the bars join every tip of the cap
  CHECK(islands(alone.branches[36]) == size_t(alone.tips));  // each tip its own island
  size_t with = 0, without = 0;
  for (size_t k = 0; k <= 36; ++k) {
    CHECK(islands(joined.branches[k]) <= islands(alone.branches[k]));
    with += islands(joined.branches[k]);
    without += islands(alone.branches[k]);
  }
  CHECK(with * 2 < without);
  // The bars hold the interface: more of the cap stands on the tips' layer than on the discs alone.
  CHECK(area(joined.branches[36]) > 1.5 * area(alone.branches[36]));
  // Still clear of the stem by the xy gap, and still far less than a column under the cap.
  const geo::Rings gap = toolpath::offset({rect(10, 10, 14, 14)}, 0.49);
  for (size_t k = 0; k <= 36; ++k) CHECK(area(toolpath::intersection(joined.branches[k], gap)) < 1e-6);
  CHECK(area(joined.branches[0]) < 0.5 * area(in.contacts[36][0].region));
}

TEST_CASE("tree: every island of every layer stands on the layer below, down to the bed") {
  auto layers = mushroom();
  for (double link : {0.0, 14.0}) {
    TreeSpec spec;
    spec.link_mm = link;
    const TreeResult r = grow_trees(under_cap(layers), spec);
    CHECK(!r.branches[0].empty());
    for (size_t k = 1; k <= 36; ++k)
      for (const geo::Rings& piece : components(r.branches[k])) {
        INFO("link " << link << " layer " << k);
        CHECK(area(toolpath::intersection(piece, r.branches[k - 1])) > 0.5 * area(piece));
      }
  }
}

TEST_CASE("tree: a branch or bar leaves support_z_gap's layers of air over the part's top") {
  // A low wall (layers 0..9) between two tips 10 mm apart (layer 20): their bar passes over the
  // wall's top, the tips' branches come down beside it. A far speck stands for the rest of the part.
  const geo::Ring wall = rect(8, 0, 12, 20);
  auto layers = test::stack(30, 0.2, geo::Polygon{rect(40, 40, 41, 41), {}});
  for (size_t k = 0; k < 10; ++k) layers[k].islands[0].shape.outer = wall;
  for (int gap : {1, 2}) {
    ProjectInput in = test::project_input(layers);
    in.bottom_gap_layers = gap;
    in.contacts[20].push_back({{rect(4.5, 9.5, 5.5, 10.5)}, 0, false});
    in.contacts[20].push_back({{rect(14.5, 9.5, 15.5, 10.5)}, 0, false});
    const TreeResult r = grow_trees(in, TreeSpec{});
    REQUIRE(r.tips == 2);
    CHECK(islands(r.branches[20]) == 1);  // the bar joins them
    CHECK(area(toolpath::intersection(r.branches[10 + size_t(gap)], {wall})) > 1);  // the bar, above the gap
    for (size_t k = 10; k < 10 + size_t(gap); ++k) {
      INFO("gap " << gap << " layer " << k);
      CHECK(area(toolpath::intersection(r.branches[k], {wall})) < 1e-6);
      CHECK(area(r.branches[k]) > 1);  // the branches beside the wall go on
    }
  }
}

TEST_CASE("tree: no branch right under the part of the layer above, but where a tip touches it") {
  // Tips on layer 39, right under the cap of layer 40: with no gap and no interface they touch it
  // (support_z_gap 0); said to keep a gap, nothing of them lies under the cap (what remains is
  // the tips' discs past the cap's edge).
  auto layers = mushroom();
  const geo::Rings cap = toolpath::difference({rect(0, 0, 24, 24)}, toolpath::offset({rect(10, 10, 14, 14)}, 0.2));
  const geo::Rings above = toolpath::material(layers[40]);
  ProjectInput touching = test::project_input(layers);
  touching.contacts[39].push_back({cap, 0, false, true});
  CHECK(area(toolpath::intersection(grow_trees(touching, TreeSpec{}).branches[39], above)) > 3);
  ProjectInput gapped = test::project_input(layers);
  gapped.contacts[39].push_back({cap, 0, false, false});
  const TreeResult g = grow_trees(gapped, TreeSpec{});
  CHECK(area(toolpath::intersection(g.branches[39], above)) < 1e-6);
  CHECK(area(g.branches[38]) > 3);  // the branches below go on
}
