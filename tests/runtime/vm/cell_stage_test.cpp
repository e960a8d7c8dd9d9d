// fill_angle decided twice: per island without the rules that read `cell.*`, then per cell with
// every rule, last match winning as usual, from what the rules started from at the island.
#include <doctest/doctest.h>

#include "tests/compiler/vm_helpers.h"

using namespace tranche;
using schema::FieldId;
using schema::Level;
using schema::PropId;
using schema::Stage;

namespace {

ctx::Context island_ctx(int layer) {
  ctx::Context c;
  c.clear_from(Level::Layer);
  c.set(FieldId::LayerIndex, layer);
  c.clear_from(Level::Island);
  c.set(FieldId::IslandArea, 100);
  return c;
}

void enter_cell(ctx::Context& c, double area, bool solid) {
  c.clear_from(Level::Cell);
  c.set(FieldId::CellArea, area);
  c.set(FieldId::CellSolid, solid ? 1 : 0);
}

}  // namespace

TEST_CASE("vm: a fill_angle rule reading cell fields decides per cell, not per island") {
  auto rs = test::rules(R"(
rule "island" when island.area > 50 mm2 { fill_angle = 30 deg }
rule "small cells" when cell.area < 20 mm2 { fill_angle = 0 deg }
)");
  CHECK(rs->varies_at(Stage::Island) == Level::Island);
  CHECK(rs->varies_at(Stage::Cell) == Level::Cell);
  auto c = island_ctx(3);
  auto base = ctx::PropertyValues::schema_defaults();
  base[PropId::FillAngle] = 45;  // what the built-in defaults and a script give
  auto island = test::decide(*rs, Stage::Island, c, base);
  CHECK(island[PropId::FillAngle] == 30);  // the cell rule takes no part (cell fields are unknown)
  enter_cell(c, 10, false);
  CHECK(test::decide(*rs, Stage::Cell, c, island)[PropId::FillAngle] == 0);
  enter_cell(c, 40, false);
  CHECK(test::decide(*rs, Stage::Cell, c, island)[PropId::FillAngle] == 30);
}

TEST_CASE("vm: per cell, a later per-island rule still wins, and no rule gives back the base") {
  auto rs = test::rules(R"(
rule "sparse cells" when not cell.solid { fill_angle = 0 deg }
rule "later" when island.area > 50 mm2 { fill_angle = 90 deg }
)");
  auto c = island_ctx(3);
  auto base = ctx::PropertyValues::schema_defaults();
  base[PropId::FillAngle] = 135;
  auto island = test::decide(*rs, Stage::Island, c, base);
  CHECK(island[PropId::FillAngle] == 90);
  enter_cell(c, 10, false);
  CHECK(test::decide(*rs, Stage::Cell, c, island)[PropId::FillAngle] == 90);
  c.set(FieldId::IslandArea, 10);  // a small island: "later" does not match
  island = test::decide(*rs, Stage::Island, c, base);
  CHECK(island[PropId::FillAngle] == 135);
  enter_cell(c, 10, false);
  CHECK(test::decide(*rs, Stage::Cell, c, island)[PropId::FillAngle] == 0);
  enter_cell(c, 10, true);
  CHECK(test::decide(*rs, Stage::Cell, c, island)[PropId::FillAngle] == 135);
}

TEST_CASE("vm: without a rule reading cell fields, nothing is decided per cell") {
  auto rs = test::rules("rule when island.area > 50 mm2 { fill_angle = 30 deg }\n");
  CHECK(rs->varies_at(Stage::Cell) == Level::Print);
  auto c = island_ctx(0);
  auto island = test::decide(*rs, Stage::Island, c);
  enter_cell(c, 10, false);
  auto cell = test::decide(*rs, Stage::Cell, c, island);
  CHECK(cell[PropId::FillAngle] == 30);
}
