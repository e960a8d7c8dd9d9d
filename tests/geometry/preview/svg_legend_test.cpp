#include <doctest/doctest.h>
#include <pugixml.hpp>

#include "geometry/preview/svg_legend.h"

using namespace tranche::preview;

TEST_CASE("svg legend: one swatch and label per class, well-formed, sized for the viewBox") {
  const std::vector<LegendEntry> entries = {
      {"island", "", "island (material)", Swatch::Fill},
      {"edge artificial", "#e0483e", "cut <artificial> & not printed", Swatch::Dash},
      {"perimeter", "#ff7d38", "perimeter", Swatch::Line},
  };
  const SvgLegend legend = svg_legend(entries, {10, 20, 12, "Légende"});
  const std::string doc = "<svg xmlns=\"http://www.w3.org/2000/svg\">" + legend.svg + "</svg>";
  pugi::xml_document xml;
  REQUIRE(xml.load_string(doc.c_str()));
  const pugi::xml_node g = xml.child("svg").child("g");
  CHECK(std::string(g.attribute("class").value()) == "legend");
  CHECK(std::string(g.attribute("transform").value()) == "translate(10.000 20.000)");
  CHECK(std::string(g.child("text").text().get()) == "Légende");
  std::vector<pugi::xml_node> rows;
  for (pugi::xml_node e : g.children("g")) rows.push_back(e);
  REQUIRE(rows.size() == 3);
  CHECK(std::string(rows[0].child("rect").attribute("class").value()) == "island");
  CHECK(rows[0].child("rect").attribute("style").empty());  // its colour comes from the drawing's CSS
  CHECK(std::string(rows[1].child("line").attribute("class").value()) == "edge artificial");
  CHECK(std::string(rows[1].child("line").attribute("stroke-dasharray").value()) == "4 3");
  CHECK(std::string(rows[1].child("line").attribute("style").value()) == "stroke:#e0483e;stroke-width:3.000");
  CHECK(std::string(rows[1].child("text").text().get()) == "cut <artificial> & not printed");
  CHECK(rows[2].child("line").attribute("stroke-dasharray").empty());
  CHECK(legend.height == doctest::Approx(2 * 7.2 + 18 * 4));
  CHECK(legend.width > 0.6 * 12 * 30);  // the longest label, 30 characters
}

TEST_CASE("svg legend: the path kinds in the preview's colours") {
  const auto kinds = kind_legend_entries();
  REQUIRE(kinds.size() == 14);  // every path.kind: support, brim and gap fill included
  CHECK(kinds[13].css_class == "kind-gap_fill");
  CHECK(kinds[13].label == "Gap fill");
  CHECK(kinds[0].css_class == "kind-outer_perimeter");
  CHECK(kinds[0].colour == "#ff7d38");
  CHECK(kinds[0].label == "External perimeter");
  CHECK(kinds[2].label == "Internal infill");
  CHECK(kinds[2].colour == "#b03029");
}
