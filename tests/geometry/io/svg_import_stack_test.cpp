// Layer stacks: reading the SVG that --export-svg writes, the round trip STL -> layers -> SVG ->
// layers, edits made in an editor, and the format's errors.
#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "geometry/export/layers_svg.h"
#include "geometry/mesh/primitives.h"
#include "geometry/slice/layer_heights.h"
#include "geometry/slice/simple_islands.h"
#include "geometry/slice/slicer.h"
#include "svg_test_util.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using tranche::test::parse_error;
using tranche::test::parse_ok;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

using Key = std::vector<std::pair<geo::coord_t, geo::coord_t>>;

// A ring as coordinate pairs rotated so that its smallest point comes first: equal rings compare
// equal whatever vertex they start at.
Key canonical(const geo::Ring& r) {
  Key k;
  for (const auto& p : r) k.emplace_back(p.X, p.Y);
  std::rotate(k.begin(), std::min_element(k.begin(), k.end()), k.end());
  return k;
}

// Polygons as sorted canonical ring lists, for exact comparison independent of order.
std::vector<std::vector<Key>> canonical(const geo::Polygons& polys) {
  std::vector<std::vector<Key>> out;
  for (const auto& p : polys) {
    std::vector<Key> holes;
    for (const auto& h : p.holes) holes.push_back(canonical(h));
    std::sort(holes.begin(), holes.end());
    holes.insert(holes.begin(), canonical(p.outer));
    out.push_back(std::move(holes));
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<geo::Layer> slice(const geo::Mesh& mesh, double layer_height) {
  auto layers = geo::plan_layer_heights(mesh.bbox().max.z - mesh.bbox().min.z, {layer_height, layer_height, {}});
  REQUIRE(layers.ok());
  Report report;
  REQUIRE(geo::slice_mesh(mesh, *layers, {}, report).ok());
  REQUIRE(geo::make_islands(*layers).ok());
  return std::move(layers).value();
}

void check_round_trip(const std::vector<geo::Layer>& layers) {
  tranche::test::TempDir dir("svg-stack");
  std::string path = (dir / "layers.svg").string();
  REQUIRE(exports::write_layers_svg(path, layers, "model.stl").ok());
  Report report;
  auto back = geo::load_svg(path, {}, report);
  REQUIRE_MESSAGE(back.ok(), back.error().to_string());
  CHECK(back->layer_stack);
  CHECK(report.empty());
  REQUIRE(back->layers.size() == layers.size());
  for (size_t i = 0; i < layers.size(); ++i) {
    CAPTURE(i);
    CHECK(back->layers[i].z_bottom == layers[i].z_bottom);
    CHECK(back->layers[i].z_top == layers[i].z_top);
    geo::Polygons islands;
    for (const auto& isl : layers[i].islands) islands.push_back(isl.shape);
    CHECK(canonical(back->layers[i].polygons) == canonical(islands));
  }
}

}  // namespace

TEST_CASE("stack: an exported layer stack reads back to the same islands, exactly") {
  // A plate with holes (islands with holes), a torus (rings, curved), and two separate boxes.
  check_round_trip(slice(geo::plate_with_holes(30, 20, 2, 3, 2, 3, 32), 0.5));
  check_round_trip(slice(geo::translated(geo::torus(12, 4, 48, 24), {3.25, -7.5, 0}), 1.0));
  geo::Mesh boxes = geo::box({10, 10, 3});
  geo::append(boxes, geo::box({5, 5, 3}, {20, 0, 0}));
  check_round_trip(slice(boxes, 0.3));
}

TEST_CASE("stack: hand-made layers with holes and an island in a hole, at negative coordinates") {
  geo::Layer a;
  a.index = 0, a.z_bottom = 0, a.z_top = 0.2;
  geo::Polygon sq;
  sq.outer = {geo::to_point(-10, -10), geo::to_point(10, -10), geo::to_point(10, 10), geo::to_point(-10, 10)};
  sq.holes.push_back(
      {geo::to_point(-5, -5), geo::to_point(-5, 5), geo::to_point(5, 5), geo::to_point(5, -5)});
  geo::Polygon inner;
  inner.outer = {geo::to_point(-1.000001, -1), geo::to_point(1, -1), geo::to_point(1, 1.333333)};
  a.islands.push_back({sq, geo::area_mm2(sq)});
  a.islands.push_back({inner, geo::area_mm2(inner)});
  geo::Layer b = a;
  b.index = 1, b.z_bottom = 0.2, b.z_top = 0.35;
  b.islands.pop_back();
  geo::Layer empty;
  empty.index = 2, empty.z_bottom = 0.35, empty.z_top = 0.5;
  check_round_trip({a, b, empty});
}

namespace {

// A minimal stack in the documented format, with `prefix` for the tranche namespace.
std::string stack_doc(const std::string& layers, const std::string& prefix = "tranche",
                      const std::string& root_extra = "") {
  return R"(<svg xmlns="http://www.w3.org/2000/svg" xmlns:)" + prefix + R"(="urn:tranche:layers" )" + prefix +
         R"(:format="tranche-layers-svg" )" + prefix + R"(:version="1" )" + prefix + R"(:units="mm" )" +
         root_extra + " viewBox=\"0 0 300 300\">\n<style>.island { fill: #3b82c4 }</style>\n" + layers +
         "</svg>\n";
}

std::string layer(int index, const std::string& zb, const std::string& zt, const std::string& body,
                  const std::string& prefix = "tranche") {
  return "<g id=\"layer-" + std::to_string(index) + "\" class=\"layer\" " + prefix + ":index=\"" +
         std::to_string(index) + "\" " + prefix + ":z-bottom=\"" + zb + "\" " + prefix + ":z-top=\"" + zt +
         "\" transform=\"translate(100 50)\">\n<rect class=\"frame\" x=\"-5\" y=\"-25\" width=\"30\" "
         "height=\"30\"/>\n"
         "<text class=\"caption\">#" +
         std::to_string(index) + "</text>\n" + body + "</g>\n";
}

const std::string kSquare = R"(<path class="island" fill-rule="evenodd" d="M0 0L10 0 10 -10 0 -10Z"/>)"
                            "\n";

}  // namespace

TEST_CASE("stack: what is material in a layer group, and where it lands") {
  Report report;
  geo::SvgModel m =
      parse_ok(stack_doc(layer(0, "0", "0.2", kSquare) + layer(1, "0.2", "0.4", kSquare)), report);
  CHECK(m.layer_stack);
  REQUIRE(m.layers.size() == 2);
  CHECK(m.layers[1].z_bottom == 0.2);
  CHECK(m.layers[1].z_top == 0.4);
  // Only the island counts (not the frame), at model coordinates (X, -Y): the group's translate
  // is ignored.
  REQUIRE(m.layers[0].polygons.size() == 1);
  geo::BBox2 b = geo::bbox(m.layers[0].polygons[0]);
  CHECK(b.min_x == 0);
  CHECK(b.min_y == 0);
  CHECK(b.max_x == geo::to_units(10));
  CHECK(b.max_y == geo::to_units(10));
  CHECK(report.empty());  // the sheet's style, frames and captions are not worth a warning

  // The namespace is matched by URI, whatever its prefix.
  geo::SvgModel p = parse_ok(stack_doc(layer(0, "0", "0.25", kSquare, "tl"), "tl"));
  CHECK(p.layer_stack);
  CHECK(p.layers[0].z_top == 0.25);
}

TEST_CASE("stack: edits made in an editor") {
  Report report;
  // Moved island (a transform on the path), a duplicated island, a new unclassed shape (not
  // material, with a warning), a shape outside any layer (warned), and a white island erasing
  // in subtractive mode.
  std::string body = R"svg(<path class="island" d="M0 0L10 0 10 -10 0 -10Z" transform="translate(20 0)"/>
<path class="island" d="M0 0L10 0 10 -10 0 -10Z"/>
<rect x="50" y="-10" width="10" height="10"/>
<path class="island" style="fill:#ffffff" d="M2 -2L8 -2 8 -8 2 -8Z"/>
)svg";
  std::string doc = stack_doc(layer(0, "0", "0.2", body) + R"(<circle r="3"/>)"
                                                           "\n");
  geo::SvgModel m = parse_ok(doc, report);
  CHECK(geo::area_mm2(m.layers[0].polygons) == doctest::Approx(200));  // additive: white adds
  geo::coord_t max_x = 0;
  for (const auto& p : m.layers[0].polygons) max_x = std::max(max_x, geo::bbox(p).max_x);
  CHECK(max_x == geo::to_units(30));  // the moved island
  CHECK(report.count("svg-stack-unclassed") == 1);
  CHECK(report.count("svg-stack-outside") == 1);
  geo::SvgImportOptions sub;
  sub.overlap = geo::SvgOverlap::Subtractive;
  Report r2;
  geo::SvgModel s = parse_ok(doc, r2, sub);
  CHECK(geo::area_mm2(s.layers[0].polygons) == doctest::Approx(200 - 36));
}

TEST_CASE("stack: format errors and warnings") {
  auto err = [](const std::string& doc) { return parse_error(doc); };
  Error e = err(stack_doc(layer(0, "0", "0.2", kSquare))
                    .replace(stack_doc("").find("version=\"1\""), 11, "version=\"3\""));
  CHECK(contains(e.message, "layer stack version 3 is newer than this reader (version 2)"));
  CHECK(e.where == "test.svg:1:1");
  e = err(stack_doc(layer(0, "0", "0.2", kSquare), "tranche")
              .replace(stack_doc("").find("units=\"mm\""), 10, "units=\"in\""));
  CHECK(contains(e.message, "units \"in\" are not mm"));
  e = err(stack_doc(layer(0, "0", "0.2", kSquare))
              .replace(stack_doc("").find("tranche-layers-svg"), 18, "tranche-layers-xyz"));
  CHECK(contains(e.message, "unknown tranche format \"tranche-layers-xyz\""));
  e = err(stack_doc(layer(0, "0", "abc", kSquare)));
  CHECK(contains(e.message, "without a readable tranche:z-bottom and tranche:z-top"));
  CHECK(e.where == "test.svg:3:1");  // the layer group
  e = err(stack_doc(layer(0, "0.2", "0.1", kSquare)));
  CHECK(contains(e.message, "it must run upwards"));
  e = err(stack_doc(layer(0, "0.2", "0.4", kSquare) + layer(1, "0", "0.2", kSquare)));
  CHECK(contains(e.message, "overlap or are out of order"));
  e = err(stack_doc(""));
  CHECK(contains(e.message, "has no layer groups"));
  e = err(stack_doc(layer(0, "0", "0.2", "")));
  CHECK(contains(e.message, "no shapes to fill"));

  Report report;
  geo::SvgModel m = parse_ok(stack_doc(layer(0, "0", "0.2", kSquare) + layer(2, "0.4", "0.6", kSquare),
                                       "tranche", "tranche:layers=\"3\""),
                             report);
  CHECK(m.layers.size() == 2);
  CHECK(report.count("svg-stack-gap") == 1);
  CHECK(report.count("svg-stack-count") == 1);
  // The namespace without the format attribute is a flat drawing (an editor kept the prefix).
  geo::SvgModel flat = parse_ok(R"(<svg xmlns="http://www.w3.org/2000/svg" xmlns:tranche="urn:tranche:layers"
      width="10mm" height="10mm" viewBox="0 0 10 10"><rect width="5" height="5"/></svg>)");
  CHECK_FALSE(flat.layer_stack);
}
