#include <doctest/doctest.h>

#include "tests/geometry/support/project_input.h"
#include "tests/geometry/toolpath/fixtures.h"
#include "geometry/support/support.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/relations.h"

using namespace tranche;
using namespace tranche::support;
using doctest::Approx;
using test::rect;

namespace {

// A mushroom: a 4 mm stem (layers 0..9) under a 12 mm cap (layers 10..14), 0.2 mm layers.
std::vector<geo::Layer> mushroom() { return test::mushroom_stack(10, 5, rect(4, 4, 8, 8), rect(0, 0, 12, 12)); }

geo::Rings cap_overhang() { return toolpath::difference({rect(0, 0, 12, 12)}, toolpath::offset({rect(4, 4, 8, 8)}, 0.2)); }


double area(const geo::Rings& r) { return toolpath::area_mm2(r); }

}  // namespace

TEST_CASE("support: a column under a mushroom's cap, down to the bed, interface at its top") {
  auto layers = mushroom();
  ProjectInput in = test::project_input(layers);
  in.contacts[8].push_back({cap_overhang(), 2, false});  // layer 10's overhang, one layer of air below it
  ProjectResult r = project(in);
  REQUIRE(r.layers.size() == 15);
  for (size_t k = 9; k < 15; ++k) CHECK(r.layers[k].area_mm2 == 0);  // the z gap, and the cap itself
  // Interface on layers 7 and 8, base below.
  CHECK(area(r.layers[8].interface) > 100);
  CHECK(area(r.layers[7].interface) > 100);
  CHECK(r.layers[8].base.empty());
  CHECK(r.layers[6].interface.empty());
  CHECK(area(r.layers[0].base) > 100);
  // The column: the cap's footprint less the stem grown by the xy gap (5 x 5 mm).
  CHECK(r.layers[0].area_mm2 == Approx(144 - 25).epsilon(0.01));
  // Never within the xy gap of the part.
  for (const auto& s : r.layers)
    CHECK(area(toolpath::intersection(s.base, toolpath::offset({rect(4, 4, 8, 8)}, 0.49))) < 1e-6);
  CHECK(r.off_bed_mm2 == 0);
  CHECK(r.blocked_mm2 == 0);
}

TEST_CASE("support: a column stands on the part's top with a gap, or not at all on bed only") {
  // A 10 mm block (layers 0..4), air above its right half up to a shelf at layers 10..12.
  auto layers = test::stack(13, 0.2, geo::Polygon{rect(0, 0, 10, 10), {}});
  for (size_t k = 5; k < 10; ++k) layers[k].islands[0].shape.outer = rect(0, 0, 5, 10);
  for (size_t k = 10; k < 13; ++k) layers[k].islands[0].shape.outer = rect(0, 0, 10, 10);
  geo::Rings shelf = toolpath::difference({rect(0, 0, 10, 10)}, toolpath::offset({rect(0, 0, 5, 10)}, 0.2));
  {
    ProjectInput in = test::project_input(layers);
    in.contacts[8].push_back({shelf, 2, false});
    ProjectResult r = project(in);
    CHECK(r.layers[8].area_mm2 > 10);
    CHECK(r.layers[6].area_mm2 > 10);
    CHECK(r.layers[5].area_mm2 == 0);  // right on the block's top: the bottom gap
    for (size_t k = 0; k < 5; ++k) CHECK(r.layers[k].area_mm2 == 0);  // inside the block: none
  }
  {
    ProjectInput in = test::project_input(layers);
    in.contacts[8].push_back({shelf, 2, true});
    ProjectResult r = project(in);
    for (const auto& s : r.layers) CHECK(s.area_mm2 == 0);
    CHECK(r.blocked_mm2 == Approx(area(shelf)).epsilon(1e-3));
  }
}

TEST_CASE("support: off the bed it is cut, and said") {
  auto layers = mushroom();
  ProjectInput in = test::project_input(layers);
  in.contacts[8].push_back({cap_overhang(), 2, false});
  in.bed = bed_region(false, 0, 0, 6, 200, geo::Point(0, 0));  // a bed ending at x = 6 mm
  ProjectResult r = project(in);
  CHECK(r.off_bed_mm2 > 50);  // the cap's overhang beyond x = 6: about 6 x 12 mm less the stem's gap
  for (const auto& s : r.layers) {
    for (const auto* rs : {&s.base, &s.interface})
      for (const auto& ring : *rs)
        for (const auto& p : ring) CHECK(geo::to_mm(p.X) <= 6.0 + 1e-6);
  }
}

TEST_CASE("support: bed_region in model units, rectangle and circle") {
  auto rect_bed = bed_region(false, 0, 0, 200, 100, geo::to_point(100, 50));
  CHECK(toolpath::area_mm2(rect_bed) == Approx(20000));
  CHECK(geo::to_mm(toolpath::bbox(rect_bed).min_x) == Approx(-100));
  auto round = bed_region(true, -100, -100, 100, 100, geo::Point(0, 0));
  CHECK(toolpath::area_mm2(round) == Approx(3.14159 * 100 * 100).epsilon(0.002));
}
