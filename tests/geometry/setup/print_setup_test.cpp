// Print setup: facts measured once, placement on the bed, the layer table from the layers the
// loop reads, the resolved index of each island, the skirt's hull and the print hooks' context.
#include <doctest/doctest.h>

#include "tests/support/print_fixture.h"

using namespace tranche;
using schema::FieldId;
using schema::PropId;

TEST_CASE("setup: the print context and the model centred on the bed") {
  setup::PrintFacts facts;
  facts.height = 12.5;
  facts.volume = 1000;
  facts.box.add(geo::to_point(10, 20));
  facts.box.add(geo::to_point(30, 60));
  ctx::Context c = setup::print_context(facts);
  CHECK(c.get(FieldId::PrintHeight) == 12.5);
  CHECK(c.get(FieldId::PrintSizeX) == 20);
  CHECK(c.get(FieldId::PrintSizeY) == 40);
  CHECK(c.get(FieldId::PrintVolume) == 1000);

  auto cascade = ctx::Cascade::create({{"bed_size_x", "250"}});
  REQUIRE(cascade.ok());
  auto props = (*cascade)->print_props(c);
  REQUIRE(props.ok());
  auto layers = test::prism_layers(3, {test::square_mm(10, 20, 30, 60)});
  Report report;
  auto s = setup::make_setup(layers, facts, c, *props, **cascade, "m.stl", report);
  REQUIRE(s.ok());
  // Centre of the box (20, 40) to the bed's centre (125, 100).
  CHECK((*s)->shift == geo::Point(geo::to_units(105), geo::to_units(60)));
  CHECK(report.empty());
  CHECK((*s)->print_ctx.get(FieldId::PrintLayers) == 3);
  CHECK((*s)->print_ctx.layer(2, FieldId::LayerZ) == doctest::Approx(0.6));
  CHECK((*s)->table.get(1, FieldId::LayerArea) == doctest::Approx(800));
  // The print's hooks read layer 0: the first layer's temperatures, decided once.
  CHECK((*s)->hook_ctx.get(FieldId::LayerIndex) == 0);
  CHECK((*s)->hook_props[PropId::NozzleTemp] == 210);
  REQUIRE((*s)->skirt_around.size() == 1);
  CHECK(geo::area_mm2((*s)->skirt_around[0]) == doctest::Approx(800));
}

TEST_CASE("setup: a model larger than the bed is a warning naming it") {
  setup::PrintFacts facts;
  facts.height = 1;
  facts.box.add(geo::to_point(0, 0));
  facts.box.add(geo::to_point(300, 10));
  auto cascade = ctx::Cascade::create({});
  REQUIRE(cascade.ok());
  ctx::Context c = setup::print_context(facts);
  auto props = (*cascade)->print_props(c);
  Report report;
  auto layers = test::prism_layers(1, {test::square_mm(0, 0, 300, 10)});
  REQUIRE(setup::make_setup(layers, facts, c, *props, **cascade, "big.stl", report).ok());
  REQUIRE(report.count("bed-size") == 1);
  CHECK(report.warnings()[0].where == "big.stl");
}

TEST_CASE("setup: a speck narrower than the simplification is dropped; the others keep their resolved index") {
  // Islands: a 10 mm square, a 5 nm speck, another square.
  const geo::coord_t x = geo::to_units(20);
  geo::Ring speck{geo::Point(x, 0), geo::Point(x + 5, 0), geo::Point(x + 5, 5), geo::Point(x, 5)};
  auto layers = test::prism_layers(2, {test::square_mm(0, 0, 10, 10), speck, test::square_mm(40, 0, 50, 10)});
  test::PrintFixture f(layers);
  REQUIRE(f.setup->layers[0].islands.size() == 2);
  CHECK(f.setup->resolved_index[0] == std::vector<uint32_t>{0, 2});
  CHECK(f.setup->table.get(0, FieldId::LayerIslands) == 2);  // what the loop sees
}
