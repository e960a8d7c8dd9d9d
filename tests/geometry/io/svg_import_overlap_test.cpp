// Overlap modes for SVG drawings: additive (nonzero union), boolean (even-odd across shapes) and
// subtractive colours (background-coloured shapes erase, in paint order).
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "svg_test_util.h"

using namespace tranche;
using tranche::test::area_of;
using tranche::test::page_mm;
using tranche::test::parse_ok;

namespace {

constexpr double kPi = std::numbers::pi;

geo::SvgImportOptions mode(geo::SvgOverlap m, std::string background = "white") {
  geo::SvgImportOptions o;
  o.overlap = m;
  o.background = std::move(background);
  return o;
}

// Two 20 x 20 squares overlapping on 10 x 20.
const std::string kTwoSquares = R"(<rect x="0" y="0" width="20" height="20"/>
  <rect x="10" y="0" width="20" height="20"/>)";

}  // namespace

TEST_CASE("additive: overlapping shapes are united") {
  CHECK(area_of(page_mm(kTwoSquares), mode(geo::SvgOverlap::Additive)) == doctest::Approx(600));
  geo::SvgModel m = parse_ok(page_mm(kTwoSquares), mode(geo::SvgOverlap::Additive));
  CHECK(m.layers[0].polygons.size() == 1);
  // Colours do not matter: white adds like any other fill.
  CHECK(
      area_of(
          page_mm(R"(<rect width="20" height="20"/><rect x="5" y="5" width="10" height="10" fill="white"/>)"),
          mode(geo::SvgOverlap::Additive)) == doctest::Approx(400));
}

TEST_CASE("boolean: overlaps cancel, across shapes") {
  geo::SvgModel m = parse_ok(page_mm(kTwoSquares), mode(geo::SvgOverlap::Boolean));
  CHECK(geo::area_mm2(m.layers[0].polygons) == doctest::Approx(400));
  CHECK(m.layers[0].polygons.size() == 2);  // the two outer strips
  // Three nested squares: in, out, in.
  CHECK(area_of(page_mm(R"(<rect width="60" height="60"/><rect x="10" y="10" width="40" height="40"/>
                           <rect x="20" y="20" width="20" height="20"/>)"),
                mode(geo::SvgOverlap::Boolean)) == doctest::Approx(3600 - 1600 + 400));
  // A shape's own fill rule still applies inside it: an evenodd ring then a disc in its hole.
  double ring_and_disc =
      area_of(page_mm(R"(<path fill-rule="evenodd" d="M0 0 H40 V40 H0 Z M10 10 H30 V30 H10 Z"/>
                                            <rect x="15" y="15" width="10" height="10"/>)"),
              mode(geo::SvgOverlap::Boolean));
  CHECK(ring_and_disc == doctest::Approx(1200 + 100));
}

TEST_CASE("subtractive: a white shape painted later erases, a later black one restores") {
  // A black square with a white circle on top: a square with a round hole.
  const std::string square_hole = R"(<rect x="0" y="0" width="40" height="40" fill="black"/>
      <circle cx="20" cy="20" r="10" fill="white"/>)";
  geo::SvgModel m = parse_ok(page_mm(square_hole), mode(geo::SvgOverlap::Subtractive));
  REQUIRE(m.layers[0].polygons.size() == 1);
  CHECK(m.layers[0].polygons[0].holes.size() == 1);
  double a = geo::area_mm2(m.layers[0].polygons);
  CHECK(a >= 1600 - kPi * 100 - 1e-6);
  CHECK(a <= 1600 - kPi * 100 + 2 * kPi * 10 * 0.01);  // the hole is inscribed, so slightly smaller
  // The same drawing in additive mode is just the square.
  CHECK(area_of(page_mm(square_hole)) == doctest::Approx(1600));

  // A black square over the white circle fills part of the hole back in.
  geo::SvgModel r =
      parse_ok(page_mm(square_hole + R"(<rect x="15" y="15" width="10" height="10" fill="#000"/>)"),
               mode(geo::SvgOverlap::Subtractive));
  CHECK(geo::area_mm2(r.layers[0].polygons) == doctest::Approx(a + 100));
  CHECK(r.layers[0].polygons.size() == 2);  // the holed square and the island inside its hole

  // Paint order matters: white drawn first erases nothing.
  CHECK(area_of(page_mm(R"(<circle cx="20" cy="20" r="10" fill="white"/><rect width="40" height="40"/>)"),
                mode(geo::SvgOverlap::Subtractive)) == doctest::Approx(1600));
  // Any spelling of the background colour erases: #fff, rgb(), style, inherited from a group.
  for (const char* white : {R"(fill="#FFF")", R"x(fill="rgb(255,255,255)")x", R"(style="fill:#ffffff")"}) {
    CAPTURE(white);
    CHECK(area_of(page_mm(std::string(R"(<rect width="40" height="40"/><rect width="20" height="40" )") +
                          white + "/>"),
                  mode(geo::SvgOverlap::Subtractive)) == doctest::Approx(800));
  }
  CHECK(
      area_of(page_mm(R"(<rect width="40" height="40"/><g fill="white"><rect width="20" height="40"/></g>)"),
              mode(geo::SvgOverlap::Subtractive)) == doctest::Approx(800));
  // Other colours add.
  CHECK(area_of(
            page_mm(R"(<rect width="40" height="40"/><rect x="30" width="20" height="40" fill="#fefefe"/>)"),
            mode(geo::SvgOverlap::Subtractive)) == doctest::Approx(2000));
}

TEST_CASE("subtractive: --background chooses the erasing colour") {
  const std::string doc = page_mm(R"(<rect width="40" height="40" fill="white"/>
      <rect width="20" height="40" fill="red"/><rect x="30" width="20" height="40" fill="black"/>)");
  CHECK(area_of(doc, mode(geo::SvgOverlap::Subtractive, "red")) == doctest::Approx(20 * 40 + 10 * 40));
  CHECK(area_of(doc, mode(geo::SvgOverlap::Subtractive, "#ff0000")) == doctest::Approx(20 * 40 + 10 * 40));
  CHECK(area_of(doc, mode(geo::SvgOverlap::Subtractive, "black")) == doctest::Approx(40 * 40 - 10 * 40));
  // With white as background, the first white shape adds nothing (nothing below it to erase).
  CHECK(area_of(doc + "", mode(geo::SvgOverlap::Subtractive)) == doctest::Approx(20 * 40 + 20 * 40));
}

TEST_CASE("islands come out strictly connected: shapes touching at a point are separate") {
  // Two squares sharing only a corner, drawn as two shapes and as one path.
  for (const char* body : {R"(<rect width="10" height="10"/><rect x="10" y="10" width="10" height="10"/>)",
                           R"(<path d="M0 0 H10 V10 H20 V20 H10 V10 H0 Z"/>)"}) {
    CAPTURE(body);
    geo::SvgModel m = parse_ok(page_mm(body));
    CHECK(m.layers[0].polygons.size() == 2);
    CHECK(geo::area_mm2(m.layers[0].polygons) == doctest::Approx(200));
  }
  // A zero-width spike sticking out of a square vanishes.
  geo::SvgModel spike = parse_ok(page_mm(R"(<path d="M0 0 H10 V5 H20 H10 V10 H0 Z"/>)"));
  REQUIRE(spike.layers[0].polygons.size() == 1);
  CHECK(geo::bbox(spike.layers[0].polygons[0]).max_x == geo::to_units(10));
}
