// One layer's text from a constructed plan: the layer header, the marks the writer resolves in
// order (temperatures, fan, the layer change), ;TYPE and ;WIDTH once per change, travels with
// their retraction and combing, E from the bead's cross-section, executors around elements.
#include <doctest/doctest.h>

#include "geometry/gcode/layer_text.h"
#include "geometry/toolpath/flow.h"
#include "tests/support/print_fixture.h"

using namespace tranche;
using gcode::LayerText;
using schema::PathKind;

namespace {

plan::PathPlan path(PathKind kind, std::vector<geo::Point> pts, float speed, float fan, bool retract = false) {
  plan::PathPlan p;
  p.kind = kind;
  p.pts = std::move(pts);
  p.pieces = {{speed, 1}};
  p.fan = fan;
  p.retract = retract;
  return p;
}

// A layer at z 0.4 with one island: two 10 mm extrusions apart, the second after a retracted travel.
plan::LayerPlan layer() {
  plan::LayerPlan lp;
  lp.index = 1;
  lp.z_bottom = 0.2;
  lp.z = 0.4;
  lp.height = 0.2;
  lp.props = ctx::PropertyValues::schema_defaults();
  plan::IslandPlan ip;
  ip.paths.push_back(path(PathKind::OuterPerimeter, {geo::to_point(0, 0), geo::to_point(10, 0)}, 25, 1));
  ip.paths.push_back(path(PathKind::Infill, {geo::to_point(10, 5), geo::to_point(0, 5)}, 80, 0.5, true));
  lp.islands.push_back(ip);
  return lp;
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("layer text: header, marks, types, travels and E") {
  test::PrintFixture f(test::prism_layers(2, {test::square_mm(0, 0, 10, 10)}));
  auto t = gcode::format_layer(*f.setup, nullptr, layer());
  REQUIRE(t.ok());
  const std::string& g = t->text;
  CHECK(g.rfind(";LAYER_CHANGE\n;Z:0.4\n;HEIGHT:0.2\n;LAYER:1\n", 0) == 0);
  CHECK(count(g, "G92 E0\n") == 1);  // the text stands alone: E restarts on every layer
  CHECK(count(g, ";TYPE:External perimeter\n") == 1);
  CHECK(count(g, ";TYPE:Internal infill\n") == 1);
  CHECK(count(g, ";WIDTH:0.45\n") == 1);  // once: both paths have the default width
  // Marks, in text order: temperatures, the layer change's retraction/route/unretraction, fans.
  std::vector<LayerText::Mark::Kind> kinds;
  for (const auto& m : t->marks) kinds.push_back(m.kind);
  using K = LayerText::Mark::Kind;
  CHECK(kinds == std::vector<K>{K::NozzleTemp, K::BedTemp, K::LayerRetract, K::LayerTravel, K::Fan, K::LayerUnretract,
                                 K::Fan});
  // The retracted travel to the infill: retract, travel, unretract (retract_length 0.8 mm).
  CHECK(count(g, " F2100\n") == 2);  // G1 E... at retract_speed, there and back
  CHECK(t->retractions == 1);
  CHECK(t->travels == 2);  // to the first path's start, and to the infill
  CHECK(t->first == f.setup->layers[0].islands[0].shape.outer[0]);
  CHECK(t->last == geo::to_point(0, 5));
  const double e10 = 10 * toolpath::e_per_mm(0.45, 0.2, 1, 1.75);
  CHECK(t->e_mm == doctest::Approx(2 * e10));
  CHECK_FALSE(t->ends_retracted);
  CHECK(t->any_move);
  CHECK(t->comber == nullptr);  // the plan had none (the travel stage sets it)
}

TEST_CASE("layer text: executors add their G-code around the elements they hook") {
  test::PrintFixture f(test::prism_layers(2, {test::square_mm(0, 0, 10, 10)}),
                       "rule when path.kind == infill { before path { gcode \"M900 K0\" } }\n"
                       "on layer.start { gcode \"; layer {layer.index}\" }\n");
  auto t = gcode::format_layer(*f.setup, f.cascade->executors(), layer());
  REQUIRE(t.ok());
  const std::string& g = t->text;
  CHECK(count(g, "M900 K0\n") == 1);
  CHECK(g.find("M900 K0") < g.find(";TYPE:Internal infill"));
  CHECK(g.find("M900 K0") > g.find(";TYPE:External perimeter"));
  CHECK(count(g, "; layer 1\n") == 1);
}
