// SVG files in the shape editors write them (tests/data/svg): Inkscape and Illustrator habits.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "svg_test_util.h"
#include "tests/support/fixtures.h"

using namespace tranche;

namespace {

constexpr double kPi = std::numbers::pi;

std::string fixture(const std::string& name) {
  return (test::source_dir() / "tests/data/svg" / name).string();
}

// "path:line:col" of the first occurrence of `needle` in the file (1-based), computed here
// independently of the reader.
std::string location_of(const std::string& path, const std::string& needle) {
  std::ifstream in(path);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n)
    if (auto c = line.find(needle); c != std::string::npos)
      return path + ":" + std::to_string(n) + ":" + std::to_string(c + 1);
  return "";
}

geo::SvgModel load(const std::string& path, Report& report,
                   geo::SvgOverlap mode = geo::SvgOverlap::Additive) {
  geo::SvgImportOptions o;
  o.overlap = mode;
  auto r = geo::load_svg(path, o, report);
  REQUIRE_MESSAGE(r.ok(), r.error().to_string());
  return std::move(r).value();
}

}  // namespace

TEST_CASE("an Inkscape document: layers, mm page, legacy translate, arcs, text, hidden layer") {
  std::string path = fixture("inkscape_plate.svg");
  Report report;
  geo::SvgModel m = load(path, report);
  // The rounded rect 40 x 20 (corner radius 2) on the page; the white circle adds nothing.
  double plate = 800 - (4 - kPi) * 4;
  double a = geo::area_mm2(m.layers[0].polygons);
  CHECK(a <= plate);
  CHECK(a >= plate - 2 * kPi * 2 * 0.01);  // corner arcs inscribed within the 0.01 mm tolerance
  geo::BBox2 b = geo::bbox(m.layers[0].polygons.at(0));
  CHECK(geo::to_mm(b.min_x) == doctest::Approx(5));
  CHECK(geo::to_mm(b.max_x) == doctest::Approx(45));
  CHECK(geo::to_mm(b.min_y) == doctest::Approx(5));  // page y 5..25 on a 30 mm page
  CHECK(geo::to_mm(b.max_y) == doctest::Approx(25));
  CHECK(report.count("svg-ignored") == 1);  // the text; the hidden layer is skipped silently
  CHECK(report.warnings().at(0).where == location_of(path, "<text"));
  CHECK(report.size() == 1);

  // Subtractive: the white circle (radius 4, centre (15, 15) on the bed) is a hole.
  Report r2;
  geo::SvgModel s = load(path, r2, geo::SvgOverlap::Subtractive);
  REQUIRE(s.layers[0].polygons.size() == 1);
  REQUIRE(s.layers[0].polygons[0].holes.size() == 1);
  double hole = std::abs(geo::area_mm2(s.layers[0].polygons[0].holes[0]));
  CHECK(hole <= kPi * 16);
  CHECK(hole >= kPi * 16 - 2 * kPi * 4 * 0.01);
  geo::BBox2 hb = geo::bbox(s.layers[0].polygons[0].holes[0]);
  CHECK(geo::to_mm(hb.min_x + hb.max_x) / 2 == doctest::Approx(15).epsilon(1e-3));
  CHECK(geo::to_mm(hb.min_y + hb.max_y) / 2 == doctest::Approx(15).epsilon(1e-3));
}

TEST_CASE("an Illustrator export: px units, a CSS class fill, an evenodd ring of Béziers") {
  std::string path = fixture("illustrator_badge.svg");
  Report report;
  geo::SvgModel m = load(path, report);
  double px2 = std::pow(25.4 / 96, 2);  // mm² per px²
  CHECK(geo::area_mm2(m.layers[0].polygons) == doctest::Approx(96 * 96 * px2));
  CHECK(report.count("svg-css") == 1);
  CHECK(report.warnings().at(0).where == location_of(path, "<style"));
  // Boolean: the ring (radii 24 and 12 px, as Bézier quarter circles) cancels out of the square.
  Report r2;
  geo::SvgModel b = load(path, r2, geo::SvgOverlap::Boolean);
  double ring = kPi * (24 * 24 - 12 * 12) * px2;
  CHECK(std::abs(geo::area_mm2(b.layers[0].polygons) - (96 * 96 * px2 - ring)) < 0.01 * ring);
  CHECK(b.layers[0].polygons.size() == 2);  // the square with a ring-shaped hole, and the disc inside
}

TEST_CASE("a fuzzer-mangled Illustrator file in boolean mode (many slivers) still resolves") {
  // Found by libFuzzer: overlapping Bézier shapes whose even-odd combination leaves dozens of
  // slivers; it took 0.8 s in the polygon stage's exact snap rounding (90 s under sanitizers).
  Report report;
  geo::SvgModel m = load(fixture("fuzz_boolean_slivers.svg"), report, geo::SvgOverlap::Boolean);
  CHECK(m.layers[0].polygons.size() > 10);
  for (const auto& p : m.layers[0].polygons) CHECK(geo::area_mm2(p) > 0);
}
