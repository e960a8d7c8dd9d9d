// --export-svg: well-formed XML whose layer groups give back the exact geometry.
#include <doctest/doctest.h>

#include <pugixml.hpp>

#include <cstdlib>
#include <sstream>
#include <string>

#include "geometry/export/layers_svg.h"
#include "geometry/mesh/primitives.h"
#include "geometry/slice/layer_heights.h"
#include "geometry/slice/simple_islands.h"
#include "geometry/slice/slicer.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::geo;
using namespace tranche::exports;

namespace {

// Rings of a path written as "M x y L x y x y ... Z" (absolute, one subpath per ring), with y
// negated back as docs/formats.md says.
Rings parse_path(const std::string& d) {
  Rings rings;
  std::istringstream in(d);
  char c;
  while (in >> c) {
    if (c == 'M') rings.emplace_back();
    if (c == 'Z') continue;
    if (c != 'M' && c != 'L') {
      in.putback(c);
    }
    double x, y;
    while (in >> std::ws && in.peek() != 'Z' && in.peek() != 'L' && in >> x >> y)
      rings.back().push_back(to_point(x, -y));
  }
  return rings;
}

}  // namespace

SCENARIO("the SVG contact sheet of a sliced model") {
  test::TempDir dir("svg");
  Mesh m = plate_with_holes(30, 20, 1, 3, 2, 3, 16);
  append(m, translated(cylinder(4, 2, 24), {40, 10, 0}));  // a second island, taller than the plate
  auto plan = plan_layer_heights(m.bbox().max.z, {});
  REQUIRE(plan.ok());
  Report r;
  REQUIRE(slice_mesh(m, *plan, {}, r).ok());
  REQUIRE(make_islands(*plan).ok());
  const auto& layers = *plan;
  const auto path = dir / "out.svg";
  REQUIRE(write_layers_svg(path.string(), layers, "a<b>&c.stl").ok());

  pugi::xml_document doc;
  auto res = doc.load_file(path.c_str());
  REQUIRE_MESSAGE(res, res.description());
  pugi::xml_node svg = doc.child("svg");
  REQUIRE(svg);
  THEN("the root names the format, version and namespace") {
    CHECK(std::string(svg.attribute("xmlns").value()) == "http://www.w3.org/2000/svg");
    CHECK(std::string(svg.attribute("xmlns:tranche").value()) == kTrancheSvgNamespace);
    CHECK(std::string(svg.attribute("tranche:format").value()) == "tranche-layers-svg");
    CHECK(svg.attribute("tranche:version").as_int() == 2);
    CHECK(svg.attribute("tranche:layers").as_int() == static_cast<int>(layers.size()));
    CHECK(std::string(svg.attribute("tranche:source").value()) == "a<b>&c.stl");
    CHECK(std::string(svg.attribute("viewBox").value()).rfind("0 0 ", 0) == 0);
  }
  THEN("each layer is a group with its index and z range, and its islands come back exactly") {
    size_t n = 0;
    for (pugi::xml_node g : svg.children("g")) {
      REQUIRE(n < layers.size());
      const Layer& l = layers[n];
      CHECK(std::string(g.attribute("id").value()) == "layer-" + std::to_string(n));
      CHECK(g.attribute("tranche:index").as_int() == l.index);
      CHECK(g.attribute("tranche:z-bottom").as_double() == l.z_bottom);
      CHECK(g.attribute("tranche:z-top").as_double() == l.z_top);
      CHECK(std::string(g.attribute("transform").value()).rfind("translate(", 0) == 0);
      size_t k = 0;
      for (pugi::xml_node p : g.children("path")) {
        REQUIRE(k < l.islands.size());
        CHECK(std::string(p.attribute("fill-rule").value()) == "evenodd");
        Rings rings = parse_path(p.attribute("d").value());
        REQUIRE(rings.size() == 1 + l.islands[k].shape.holes.size());
        CHECK(rings[0] == l.islands[k].shape.outer);
        for (size_t h = 0; h < l.islands[k].shape.holes.size(); ++h)
          CHECK(rings[h + 1] == l.islands[k].shape.holes[h]);
        ++k;
      }
      CHECK(k == l.islands.size());
      CHECK(g.child("text"));
      ++n;
    }
    CHECK(n == layers.size());
    CHECK(layers.front().islands.size() == 2);
    CHECK(layers.back().islands.size() == 1);
  }
}

TEST_CASE("an SVG of no layers is still a valid document") {
  test::TempDir dir("svg-empty");
  REQUIRE(write_layers_svg((dir / "e.svg").string(), {}, "empty").ok());
  pugi::xml_document doc;
  REQUIRE(doc.load_file((dir / "e.svg").c_str()));
  CHECK(doc.child("svg").attribute("tranche:layers").as_int() == 0);
}
