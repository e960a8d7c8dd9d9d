// The layer loop on constructed prints: what it plans for an island (kinds, cells, print order),
// that every decision comes from the cascade (built-in defaults, rules, --set), and the
// replacers it runs.
#include <doctest/doctest.h>

#include <algorithm>

#include "geometry/plan/replace.h"
#include "tests/support/print_fixture.h"

using namespace tranche;
using schema::PathKind;
using schema::PropId;
using test::PrintFixture;
using test::prism_layers;
using test::square_mm;

namespace {

std::vector<PathKind> kinds(const plan::IslandPlan& ip) {
  std::vector<PathKind> out;
  for (const auto& p : ip.paths) out.push_back(p.kind);
  return out;
}

}  // namespace

TEST_CASE("layer loop: a square's middle layer is infill, then the loops innermost first") {
  PrintFixture f(prism_layers(12, {square_mm(0, 0, 20, 20)}), {}, {{"skirt_loops", "0"}});
  auto plan = f.plan(6);
  CHECK(plan.index == 6);
  CHECK(plan.z == doctest::Approx(1.4));
  CHECK(plan.height == doctest::Approx(0.2));
  REQUIRE(plan.islands.size() == 1);
  const auto& ip = plan.islands[0];
  CHECK(ip.area == doctest::Approx(400));
  CHECK(ip.props[PropId::FillAngle] == 45);  // even layer: the built-in default
  const auto k = kinds(ip);
  REQUIRE(k.size() >= 3);
  CHECK(k.front() == PathKind::Infill);
  CHECK(k[k.size() - 2] == PathKind::InnerPerimeter);
  CHECK(k.back() == PathKind::OuterPerimeter);
  for (size_t i = 0; i < ip.paths.size(); ++i) CHECK(ip.paths[i].index == static_cast<int>(i));
  // Each cell is one zig-zag; its index is the cell's.
  for (const auto& p : ip.paths)
    if (p.kind == PathKind::Infill) {
      REQUIRE(p.cell >= 0);
      CHECK(ip.cells[static_cast<size_t>(p.cell)].fill_angle_deg == 45);
      CHECK_FALSE(ip.cells[static_cast<size_t>(p.cell)].solid);
    }
  // Speeds by kind (built-in defaults), decided once per path.
  for (const auto& p : ip.paths) {
    REQUIRE(p.pieces.size() == 1);
    if (p.kind == PathKind::OuterPerimeter) CHECK(p.pieces[0].speed == 25);
    if (p.kind == PathKind::Infill) CHECK(p.pieces[0].speed == 80);
  }
  CHECK(plan.time_s > 0);
  CHECK(plan.extruded_mm3 > 0);
  CHECK(plan.comber != nullptr);
}

TEST_CASE("layer loop: the first and last layers are solid; layer 0 is bottom, the top is top solid") {
  PrintFixture f(prism_layers(10, {square_mm(0, 0, 20, 20)}), {}, {{"skirt_loops", "0"}});
  auto bottom = f.plan(0), top = f.plan(9);
  auto has = [](const plan::LayerPlan& lp, PathKind k) {
    const auto v = kinds(lp.islands[0]);
    return std::find(v.begin(), v.end(), k) != v.end();
  };
  CHECK(has(bottom, PathKind::BottomSolid));
  CHECK_FALSE(has(bottom, PathKind::Infill));
  CHECK(has(top, PathKind::TopSolid));
  CHECK(top.islands[0].props[PropId::FillAngle] == 135);  // odd layer
}

TEST_CASE("layer loop: decisions come from the cascade: rules over the defaults, --set over the rules") {
  PrintFixture f(prism_layers(8, {square_mm(0, 0, 20, 20)}),
                 "rule \"slow walls\" when path.kind == outer_perimeter { speed = 12 mm/s }\n"
                 "rule when layer.index >= 3 { fill_angle = 30 deg; perimeters = 3 }\n",
                 {{"skirt_loops", "0"}, {"perimeters", "1"}});
  auto lp = f.plan(4);
  const auto& ip = lp.islands[0];
  CHECK(ip.props[PropId::FillAngle] == 30);
  CHECK(ip.props[PropId::Perimeters] == 1);  // --set wins over the rule
  int loops = 0;
  for (const auto& p : ip.paths) {
    if (p.closed) ++loops;
    if (p.kind == PathKind::OuterPerimeter) CHECK(p.pieces[0].speed == 12);
  }
  CHECK(loops == 1);
  for (const auto& c : ip.cells) CHECK(c.fill_angle_deg == 30);
}

TEST_CASE("layer loop: two islands nearest first, odd layers backwards") {
  PrintFixture f(prism_layers(4, {square_mm(0, 0, 10, 10), square_mm(30, 0, 40, 10)}), {}, {{"skirt_loops", "0"}});
  auto even = f.plan(2), odd = f.plan(3);
  REQUIRE(even.islands.size() == 2);
  REQUIRE(odd.islands.size() == 2);
  CHECK(even.islands[0].index == odd.islands[1].index);
  CHECK(even.islands[1].index == odd.islands[0].index);
}

TEST_CASE("layer loop: the skirt on layer 0 only, around the first layer") {
  PrintFixture f(prism_layers(3, {square_mm(0, 0, 10, 10)}), {}, {{"skirt_loops", "2"}});
  auto l0 = f.plan(0), l1 = f.plan(1);
  REQUIRE(l0.skirt.size() == 2);
  CHECK(l1.skirt.empty());
  for (const auto& s : l0.skirt) {
    CHECK(s.kind == PathKind::Skirt);
    CHECK(s.pts.front() == s.pts.back());  // opened at its seam, still a loop
  }
}

TEST_CASE("layer loop: a path replacer's moves and text become the path's ops, speed from the decision") {
  PrintFixture f(prism_layers(3, {square_mm(0, 0, 10, 10)}),
                 "rule when path.kind == outer_perimeter {\n"
                 "  replace path { gcode \"M117 wall\"\n default\n move to (1 mm, 2 mm) }\n"
                 "}\n",
                 {{"skirt_loops", "0"}});
  auto lp = f.plan(1);
  const plan::PathPlan* outer = nullptr;
  for (const auto& p : lp.islands[0].paths)
    if (p.kind == PathKind::OuterPerimeter) outer = &p;
  REQUIRE(outer);
  CHECK(outer->replaced);
  REQUIRE(outer->ops.size() == 3);
  CHECK(outer->ops[0].kind == plan::Op::Kind::Text);
  CHECK(outer->ops[0].text == "M117 wall");
  CHECK(outer->ops[1].kind == plan::Op::Kind::Default);
  CHECK(outer->ops[2].kind == plan::Op::Kind::Extrude);
  CHECK(outer->ops[2].speed == outer->pieces[0].speed);  // no explicit speed: the decided one
  CHECK(outer->ops[2].to == plan::to_model(plan::Nest(*f.setup, *f.cascade), 1, 2));
  CHECK(outer->retract);  // the travel into a replaced path retracts
}

TEST_CASE("layer loop: an island replacer's offset shrinks the island and decides it again") {
  PrintFixture f(prism_layers(3, {square_mm(0, 0, 10, 10)}),
                 "rule when layer.index == 1 { replace island { offset -1 mm\n default } }\n"
                 "rule when island.area < 70 mm2 { perimeters = 1 }\n",
                 {{"skirt_loops", "0"}});
  auto lp = f.plan(1);
  const auto& ip = lp.islands[0];
  CHECK(ip.replaced);
  CHECK(ip.area == doctest::Approx(64).epsilon(0.01));
  CHECK(ip.props[PropId::Perimeters] == 1);  // decided on the altered island
  REQUIRE(ip.ops.size() == 1);
  CHECK(ip.ops[0].kind == plan::Op::Kind::Default);
  CHECK_FALSE(ip.paths.empty());
  auto untouched = f.plan(2);
  CHECK(untouched.islands[0].props[PropId::Perimeters] == 2);
}

TEST_CASE("layer loop: islands know their object, so rules set per-object values") {
  auto layers = prism_layers(3, {square_mm(0, 0, 10, 10), square_mm(30, 0, 40, 10)});
  for (auto& l : layers) l.islands[1].object = 1;
  PrintFixture f(layers, "rule \"lid\" when object.index == 1 { perimeters = 3; infill_density = 40% }\n",
                 {{"skirt_loops", "0"}});
  auto lp = f.plan(1);
  REQUIRE(lp.islands.size() == 2);
  for (const auto& ip : lp.islands) {
    CHECK(ip.props[PropId::Perimeters] == (ip.object == 1 ? 3 : 2));
    CHECK(ip.props[PropId::InfillDensity] == doctest::Approx(ip.object == 1 ? 0.4 : 0.2));
  }
}

TEST_CASE("layer loop: island shape and the island under it, measured when a rule reads them") {
  // Layers 0-1: a 20 mm square and a 4 × 30 mm bar beside it; layers 2-3: the bar only, and a
  // square over the square's corner.
  auto layers = prism_layers(4, {square_mm(0, 0, 20, 20), square_mm(30, 0, 34, 30)});
  for (int i = 2; i < 4; ++i) layers[static_cast<size_t>(i)].islands[0].shape.outer = square_mm(10, 10, 25, 25);
  const char* rules =
      "rule when island.min_width < 5 mm and island.convex { perimeters = 1 }\n"
      "rule when island.below_area > 300 mm2 and island.below_supported > 90% { infill_density = 50% }\n"
      "rule when island.longest_edge_angle > 45 deg { top_layers = 5 }\n";
  PrintFixture f(layers, rules, {{"skirt_loops", "0"}});
  auto lp = f.plan(2);
  REQUIRE(lp.islands.size() == 2);
  for (const auto& ip : lp.islands) {
    const bool bar = ip.area < 200;  // 120 mm², the square 225
    CHECK(ip.min_width == doctest::Approx(bar ? 4 : 15).epsilon(0.01));
    CHECK(ip.convex);
    CHECK(ip.longest_edge_angle == doctest::Approx(bar ? 90 : 0));
    // Under the bar, the bar (120 mm²); under the square, the 20 mm square (400 mm²), on layer 0.
    CHECK(ip.below_area == doctest::Approx(bar ? 120 : 400).epsilon(1e-6));
    CHECK(ip.below_supported == doctest::Approx(1));
    CHECK(ip.props[PropId::Perimeters] == (bar ? 1 : 2));
    CHECK(ip.props[PropId::InfillDensity] == doctest::Approx(bar ? 0.2 : 0.5));
    CHECK(ip.props[PropId::TopLayers] == (bar ? 5 : 3));
  }
  // On layer 0 nothing is under an island; without rules reading them nothing is measured.
  for (const auto& ip : f.plan(0).islands) CHECK(ip.below_area == 0);
  PrintFixture plain(layers, "", {{"skirt_loops", "0"}});
  for (const auto& ip : plain.plan(2).islands) CHECK((ip.min_width == 0 && !ip.convex && ip.below_area == 0));
}

TEST_CASE("layer loop: piece.overhang measured and speed decided per piece only on the paths whose rules read it") {
  // Layers 0-1: a 20 mm square; layers 2-3: a 20 mm square shifted 5 mm out over the air.
  auto layers = prism_layers(4, {square_mm(0, 0, 20, 20)});
  for (int i = 2; i < 4; ++i) layers[static_cast<size_t>(i)].islands[0].shape.outer = square_mm(5, 0, 25, 20);
  const char* rules =
      "rule when path.kind == outer_perimeter and piece.overhang > 50% { speed = min(speed, 9 mm/s) }\n"
      "rule when path.kind == infill { speed = min(speed, 70 mm/s) }\n";
  // The walls stay loops over the air (not bridge lines), so that one runs over it.
  PrintFixture f(layers, rules, {{"skirt_loops", "0"}, {"perimeters", "1"}, {"overhang_walls", "loops"}});
  auto lp = f.plan(2);
  REQUIRE(lp.islands.size() == 1);
  int walls = 0, fills = 0;
  for (const auto& p : lp.islands[0].paths) {
    if (p.kind == PathKind::OuterPerimeter) {
      ++walls;
      // Measured per piece; the piece over the air (x > 20) slowed, the others not.
      CHECK(p.overhang.size() == p.piece_count());
      CHECK(p.pieces.size() == p.piece_count());
      auto slow = std::count_if(p.pieces.begin(), p.pieces.end(), [](const auto& pc) { return pc.speed == 9; });
      CHECK(slow >= 1);
      CHECK(slow < static_cast<long>(p.pieces.size()));
    } else if (p.kind == PathKind::Infill || p.kind == PathKind::SolidInfill) {
      ++fills;
      // No rule in play reads a piece field: one decision, nothing measured.
      CHECK(p.overhang.empty());
      CHECK(p.pieces.size() == 1);
    }
  }
  CHECK(walls == 1);
  CHECK(fills > 0);
  // A hook reading the pieces' overhang needs it on every path.
  PrintFixture hooked(layers, std::string(rules) + "rule { after path { for pc in path.pieces { if pc.overhang > 99% { comment \"air\" } } } }\n",
                      {{"skirt_loops", "0"}, {"perimeters", "1"}, {"overhang_walls", "loops"}});
  for (const auto& p : hooked.plan(2).islands[0].paths)
    if (p.piece_count() > 0) CHECK(p.overhang.size() == p.piece_count());
}
