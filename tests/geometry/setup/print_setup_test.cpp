// Print setup: facts measured once, placement on the bed, the layer table from the layers the
// loop reads, the resolved index of each island, the skirt's hull and the print hooks' context.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

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

TEST_CASE("setup: outer walls follow the outlines at the print's resolution, the rest at 0.025 mm or coarser") {
  // A disc of radius 10 mm as a 2000-gon with a round hole: its chords lie 1.2 µm inside the circle.
  auto circle = [](double r, bool ccw) {
    geo::Ring ring;
    for (int k = 0; k < 2000; ++k) {
      const double a = (ccw ? 2 : -2) * M_PI * k / 2000;
      ring.push_back(geo::to_point(50 + r * std::cos(a), 50 + r * std::sin(a)));
    }
    return ring;
  };
  const geo::Ring disc = circle(10, true), hole = circle(4, false);
  geo::Layer layer;
  geo::Island island;
  island.shape.outer = disc;
  island.shape.holes = {hole};
  layer.islands = {island};
  layer.z_top = 0.2;
  const std::vector<geo::Layer> layers{layer};
  // The farthest any vertex of `of` lies from `r`.
  auto deviation = [&](const geo::Ring& of, const geo::Ring& r) {
    double worst = 0;
    for (const auto& p : of) {
      double best = 1e300;
      for (size_t i = 0; i < r.size(); ++i) {
        const geo::Point &a = r[i], &b = r[(i + 1) % r.size()];
        const double ex = double(b.X - a.X), ey = double(b.Y - a.Y), len2 = ex * ex + ey * ey;
        const double t = std::clamp((ex * double(p.X - a.X) + ey * double(p.Y - a.Y)) / len2, 0.0, 1.0);
        best = std::min(best, std::hypot(double(a.X) + t * ex - double(p.X), double(a.Y) + t * ey - double(p.Y)));
      }
      worst = std::max(worst, best);
    }
    return geo::to_mm(static_cast<geo::coord_t>(std::llround(worst)));
  };
  size_t last = disc.size() + 1;
  for (const char* res : {"0", "0.0125", "0.025", "0.1"}) {
    INFO("resolution = " << res);
    const double r = std::stod(res), inner = std::max(r, 0.025);
    test::PrintFixture f(layers, {}, {{"resolution", res}});
    REQUIRE(f.setup->layers[0].islands.size() == 1);
    const geo::Polygon& shape = f.setup->layers[0].islands[0].shape;
    REQUIRE(shape.holes.size() == 1);
    CHECK(deviation(disc, shape.outer) <= inner + 1e-6);
    CHECK(deviation(hole, shape.holes[0]) <= inner + 1e-6);
    if (r < inner) {
      REQUIRE(f.setup->wall_outlines.size() == 1);
      REQUIRE(f.setup->wall_outlines[0].size() == 1);
      const geo::Rings& wall = f.setup->wall_outlines[0][0];
      REQUIRE(wall.size() == 2);
      CHECK(deviation(disc, wall[0]) <= r + 1e-6);
      CHECK(deviation(hole, wall[1]) <= r + 1e-6);
      CHECK(wall[0].size() < last);  // coarser keeps fewer vertices
      CHECK(wall[0].size() > shape.outer.size());
      last = wall[0].size();
    } else {
      CHECK(f.setup->wall_outlines.empty());  // the walls follow the island itself
      CHECK(shape.outer.size() < last);
      last = shape.outer.size();
    }
  }
  // The default is PrusaSlicer's 0.0125 mm for the walls.
  test::PrintFixture f(layers);
  REQUIRE(f.setup->wall_outlines.size() == 1);
  CHECK(deviation(disc, f.setup->wall_outlines[0][0][0]) <= 0.0125 + 1e-6);
  CHECK(deviation(disc, f.setup->wall_outlines[0][0][0]) > 0.005);
}
