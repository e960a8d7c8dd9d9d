// What the exports draw besides the islands: the paths the G-code prints (from a layer plan) with
// the G-code's cells, and, as an analysis view on request, the seed's exact monotone cells; and
// that a re-imported SVG stack takes none of them as material.
#include <doctest/doctest.h>

#include <string>

#include "geometry/export/layers_json.h"
#include "geometry/export/layers_svg.h"
#include "geometry/io/svg_import.h"
#include "geometry/polygon/decompose.h"
#include "geometry/polygon/resolve.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::geo;
using namespace tranche::exports;

namespace {

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// One layer: a 40 x 30 mm frame around a 20 x 10 mm hole (2 exact cells at 0°), and a square (1).
Layer layer() {
  Layer l;
  l.z_top = 0.2;
  auto mm = [](double x, double y) { return to_point(x, y); };
  l.loops = {{mm(0, 0), mm(40, 0), mm(40, 30), mm(0, 30)},
             {mm(10, 10), mm(10, 20), mm(30, 20), mm(30, 10)},
             {mm(50, 0), mm(60, 0), mm(60, 10), mm(50, 10)}};
  Report rep;
  REQUIRE(resolve_layer(l, {}, rep).ok());
  return l;
}

std::vector<std::vector<Cell>> exact(const Layer& l) {
  std::vector<std::vector<Cell>> out;
  for (size_t i = 0; i < l.islands.size(); ++i) {
    auto c = decompose_island(l, i, 0);
    REQUIRE(c.ok());
    out.push_back(std::move(*c));
  }
  return out;
}

// A plan for the square (island 1): one loop and one zig-zag cell, and a skirt loop.
plan::LayerPlan square_plan() {
  plan::LayerPlan lp;
  plan::IslandPlan ip;
  ip.index = 1;
  ip.props[schema::PropId::FillAngle] = 45;
  ip.cells.push_back({0, 64.0, 45, true});
  plan::PathPlan loop;
  loop.kind = schema::PathKind::OuterPerimeter;
  loop.closed = true;
  loop.pts = {to_point(50.2, 0.2), to_point(59.8, 0.2), to_point(59.8, 9.8), to_point(50.2, 9.8), to_point(50.2, 0.2)};
  ip.paths.push_back(loop);
  plan::PathPlan zig;
  zig.kind = schema::PathKind::TopSolid;
  zig.cell = 0;
  zig.pts = {to_point(51, 1), to_point(59, 9), to_point(59, 8)};
  ip.paths.push_back(zig);
  lp.islands.push_back(ip);
  plan::PathPlan skirt;
  skirt.kind = schema::PathKind::Skirt;
  skirt.closed = true;
  skirt.pts = {to_point(-3, -3), to_point(63, -3), to_point(63, 33), to_point(-3, -3)};
  lp.skirt.push_back(skirt);
  return lp;
}

}  // namespace

TEST_CASE("exports: JSON gives each planned island its angle, the G-code's cells and paths in print order") {
  const Layer l = layer();
  const plan::LayerPlan lp = square_plan();
  fmt::memory_buffer buf;
  LayersJson::append_layer(buf, planned_layer(l, lp, {0, 1}));
  const std::string json(buf.data(), buf.size());
  CHECK(count(json, "\"fill_angle\": 45, \"replaced\": false, \"cells\": [{\"index\": 0, \"solid\": true") == 1);
  CHECK(count(json, "\"kind\": \"outer_perimeter\", \"cell\": -1, \"width\": 0.45, \"closed\": true") == 1);
  CHECK(count(json, "\"kind\": \"top_solid\", \"cell\": 0") == 1);
  CHECK(count(json, "\"skirt\": [") == 1);
  CHECK(count(json, "\"points\": [[51,1],[59,9],[59,8]]") == 1);
  CHECK(count(json, "exact_cells") == 0);  // only on request
  CHECK(count(json, "\"paths\"") == 1);    // the frame (island 0) has no plan here: islands only
}

TEST_CASE("exports: JSON exact cells (analysis) with edge kinds") {
  const Layer l = layer();
  const auto cells = exact(l);
  fmt::memory_buffer buf;
  ExportLayer e;
  e.layer = &l;
  e.exact = &cells;
  LayersJson::append_layer(buf, e);
  const std::string json(buf.data(), buf.size());
  CHECK(count(json, "\"exact_cells\": [") == 2);
  CHECK(count(json, "\"edges\": \"") == 3);
  // The frame's two cells share two cuts, each listed once per cell: four 'a' letters in all.
  size_t a = 0, r = 0;
  for (size_t at = json.find("\"edges\": \""); at != std::string::npos; at = json.find("\"edges\": \"", at + 1)) {
    for (size_t k = at + 10; json[k] != '"'; ++k) (json[k] == 'a' ? a : r) += 1;
  }
  CHECK(a == 4);
  CHECK(r == 4 + 4 + 4);  // the frame's outline and hole, and the square
}

TEST_CASE("exports: SVG printed paths, exact cells and cuts, none of them material when read back") {
  test::TempDir dir("cells-export");
  const std::vector<Layer> ls{layer()};
  const plan::LayerPlan lp = square_plan();
  const auto cells = exact(ls[0]);
  const std::string path = (dir / "layers.svg").string();
  const Sheet sheet = sheet_layout(ls, true);
  {
    auto w = LayersSvg::open(path, "test", 1, sheet, true);
    REQUIRE(w.ok());
    fmt::memory_buffer g;
    ExportLayer e = planned_layer(ls[0], lp, {0, 1});
    e.exact = &cells;
    LayersSvg::append_layer(g, e, 0, sheet);
    REQUIRE((*w)->write_layer(g).ok());
    REQUIRE((*w)->finish().ok());
  }
  const std::string svg = test::read_file(path);
  CHECK(count(svg, "<path class=\"path outer_perimeter\"") == 1);
  CHECK(count(svg, "<path class=\"path top_solid\" tranche:cell=\"0\"") == 1);
  CHECK(count(svg, "<path class=\"path skirt\"") == 1);
  CHECK(count(svg, "<g class=\"legend\"") == 1);
  CHECK(count(svg, "<path class=\"exact-cell\" tranche:fill-angle=\"0\"") == 3);
  CHECK(count(svg, "<path class=\"edge artificial\"") == 1);  // only the frame has cuts
  Report rep;
  auto back = load_svg(path, {}, rep);
  REQUIRE(back.ok());
  CHECK(rep.empty());
  REQUIRE(back->layers.size() == 1);
  CHECK(area_mm2(back->layers[0].polygons) == doctest::Approx(40 * 30 - 20 * 10 + 100));
}
