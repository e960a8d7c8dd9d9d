// Monotone cells in the exports (added by geometry/polygon): the JSON keys fill_angle and cells,
// the SVG cell paths and cut paths, and that a re-imported SVG stack ignores them.
#include <doctest/doctest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "geometry/io/layers_json.h"
#include "geometry/io/svg_export.h"
#include "geometry/io/svg_import.h"
#include "geometry/polygon/decompose.h"
#include "geometry/polygon/resolve.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::geo;

namespace {

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// One layer: a 40 x 30 mm frame around a 20 x 10 mm hole (2 cells at 0°), and a square (1 cell).
std::vector<Layer> layers() {
  std::vector<Layer> out(1);
  Layer& l = out[0];
  l.z_top = 0.2;
  auto mm = [](double x, double y) { return to_point(x, y); };
  l.loops = {{mm(0, 0), mm(40, 0), mm(40, 30), mm(0, 30)},
             {mm(10, 10), mm(10, 20), mm(30, 20), mm(30, 10)},
             {mm(50, 0), mm(60, 0), mm(60, 10), mm(50, 10)}};
  Report rep;
  REQUIRE(resolve_layer(l, {}, rep).ok());
  for (Island& is : l.islands) REQUIRE(decompose_island(is, 0).ok());
  return out;
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST_CASE("cells export: JSON gives each island's fill angle and cells with edge kinds") {
  const auto ls = layers();
  fmt::memory_buffer buf;
  append_layer_json(buf, ls[0]);
  const std::string json(buf.data(), buf.size());
  CHECK(count(json, "\"fill_angle\": 0, \"cells\": [") == 2);
  CHECK(count(json, "\"edges\": \"") == 3);
  // The frame's two cells share two cuts, each listed once per cell: four 'a' letters in all.
  size_t a = 0, r = 0;
  for (size_t at = json.find("\"edges\": \""); at != std::string::npos;
       at = json.find("\"edges\": \"", at + 1)) {
    for (size_t k = at + 10; json[k] != '"'; ++k) (json[k] == 'a' ? a : r) += 1;
  }
  CHECK(a == 4);
  CHECK(r == 4 + 4 + 4);  // the frame's outline and hole, and the square
  // Islands not decomposed yet have neither key.
  Layer plain = ls[0];
  for (Island& is : plain.islands) is.fill_angle_deg = std::nan("");
  fmt::memory_buffer b2;
  append_layer_json(b2, plain);
  CHECK(std::string(b2.data(), b2.size()).find("cells") == std::string::npos);
}

TEST_CASE("cells export: SVG cell and cut paths, ignored when the stack is read back") {
  test::TempDir dir("cells-export");
  const auto ls = layers();
  const std::string path = (dir / "layers.svg").string();
  REQUIRE(write_layers_svg(path, ls, "test").ok());
  const std::string svg = read(path);
  CHECK(count(svg, "<path class=\"cell\" tranche:fill-angle=\"0\"") == 3);
  CHECK(count(svg, "<path class=\"edge artificial\"") == 1);  // only the frame has cuts
  Report rep;
  auto back = load_svg(path, {}, rep);
  REQUIRE(back.ok());
  CHECK(rep.empty());
  REQUIRE(back->layers.size() == 1);
  CHECK(area_mm2(back->layers[0].polygons) == doctest::Approx(40 * 30 - 20 * 10 + 100));
}
