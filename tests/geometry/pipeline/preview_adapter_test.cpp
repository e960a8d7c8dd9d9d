// --export-preview: what the preview shows of a planned layer, and the provenance chains the
// layer loop records when asked (and only then).
#include <doctest/doctest.h>

#include "geometry/pipeline/preview_adapter.h"
#include "tests/support/print_fixture.h"

using namespace tranche;
using preview::SourceKind;
using schema::PathKind;
using schema::PropId;

namespace {

const preview::SlotChain* slot(const preview::PreviewPath& p, PropId prop) {
  if (!p.provenance) return nullptr;
  for (const auto& s : p.provenance->slots)
    if (s.prop == prop) return &s;
  return nullptr;
}

const char* kRules =
    "rule \"bridges\" when path.kind == outer_perimeter { speed = 15 mm/s }\n"
    "rule \"small islands\" when island.area < 500 mm2 { speed = speed * 50% }\n"
    "rule \"pa\" when path.kind == outer_perimeter { before path { gcode \"M900 K0.045\" } }\n";

}  // namespace

TEST_CASE("preview: each path's speed chain names the default, the built-in and each rule with file:line") {
  test::PrintFixture f(test::prism_layers(6, {test::square_mm(0, 0, 20, 20)}), kRules,
                       {{"skirt_loops", "0"}, {"min_layer_time", "0"}});
  f.setup->provenance = true;
  auto lp = f.plan(3);
  auto text = gcode::format_layer(*f.setup, f.cascade->executors(), lp);
  REQUIRE(text.ok());
  auto layer = pipeline::preview_layer(*f.setup, lp, &*text, f.rules.get());
  CHECK(layer.index == 3);
  CHECK(layer.z == doctest::Approx(0.8));
  const preview::PreviewPath* outer = nullptr;
  for (const auto& p : layer.paths)
    if (p.kind == PathKind::OuterPerimeter) outer = &p;
  REQUIRE(outer);
  CHECK(outer->speed == std::vector<float>{7.5f});
  CHECK(outer->points.front().x == doctest::Approx(geo::to_mm(lp.islands[0].paths.back().pts[0].X + f.setup->shift.X)));
  REQUIRE(outer->provenance);
  const auto* speed = slot(*outer, PropId::Speed);
  REQUIRE(speed);
  REQUIRE(speed->steps.size() == 4);
  CHECK(speed->steps[0].source == SourceKind::SchemaDefault);
  CHECK(speed->steps[0].value == 60);
  CHECK(speed->steps[1].source == SourceKind::BuiltinDefault);
  CHECK(speed->steps[1].value == 25);
  CHECK(speed->steps[1].text == "speed = 25 mm/s when path.kind == outer_perimeter");
  CHECK(speed->steps[2].rule == "bridges");  // read by the rule after it
  CHECK(speed->steps[2].value == 15);
  CHECK(speed->steps[2].line == 1);
  CHECK(speed->steps[3].rule == "small islands");
  CHECK(speed->steps[3].value == 7.5);
  CHECK(speed->steps[3].line == 2);
  CHECK(speed->steps[3].source == SourceKind::Rule);
  CHECK(speed->steps[3].file.find("r.rules") != std::string::npos);
  // The fill angle is the island's: the built-in 135° on this odd layer.
  const auto* angle = slot(*outer, PropId::FillAngle);
  REQUIRE(angle);
  CHECK(angle->steps.back().value == 135);
  CHECK(angle->steps.back().source == SourceKind::BuiltinDefault);
  // The executor that wrote before the wall.
  REQUIRE(outer->provenance->executors.size() == 1);
  CHECK(outer->provenance->executors[0].text == "M900 K0.045");
  CHECK(outer->provenance->executors[0].rule == "pa");
  CHECK_FALSE(outer->provenance->executors[0].after);
  CHECK(outer->provenance->replacer == nullptr);
  // Travels between the paths, in print order.
  CHECK(layer.travels.size() + 1 >= lp.islands[0].paths.size() - 1);
}

TEST_CASE("preview: nothing is recorded when the run does not ask for provenance") {
  test::PrintFixture f(test::prism_layers(4, {test::square_mm(0, 0, 20, 20)}), kRules, {{"skirt_loops", "0"}});
  auto lp = f.plan(2);
  CHECK(lp.trace == nullptr);
  for (const auto& p : lp.islands[0].paths) CHECK(p.trace == nullptr);
  auto layer = pipeline::preview_layer(*f.setup, lp, nullptr, f.rules.get());
  for (const auto& p : layer.paths) CHECK(p.provenance == nullptr);
}

TEST_CASE("preview: a replacer's output is its paths, with the replacer named") {
  test::PrintFixture f(test::prism_layers(4, {test::square_mm(0, 0, 20, 20)}),
                       "rule \"wavy\" when path.kind == outer_perimeter {\n"
                       "  replace path { for p in path.points { move to (p.x, p.y + 0.2 mm) } }\n}\n",
                       {{"skirt_loops", "0"}});
  f.setup->provenance = true;
  auto lp = f.plan(2);
  auto layer = pipeline::preview_layer(*f.setup, lp, nullptr, f.rules.get());
  int replaced = 0;
  for (const auto& p : layer.paths)
    if (p.provenance && p.provenance->replacer) {
      ++replaced;
      CHECK(p.provenance->replacer->rule == "wavy");
      CHECK_FALSE(p.provenance->replacer->emitted_default);
      CHECK(p.points.size() >= 4);
    }
  CHECK(replaced == 1);
}
