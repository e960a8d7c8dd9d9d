// Bad SVG input: every error names the file and line:col and says what is wrong; ignored content
// is a warning with its location.
#include <doctest/doctest.h>

#include <fstream>

#include "svg_test_util.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using tranche::test::page_mm;
using tranche::test::parse_error;
using tranche::test::parse_ok;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

#define CHECK_ERROR(text_, where_, part_)                       \
  do {                                                          \
    Error e_ = parse_error(text_);                              \
    CHECK_MESSAGE(e_.where == (where_), e_.to_string());        \
    CHECK_MESSAGE(contains(e_.message, part_), e_.to_string()); \
  } while (0)

const char* kHead =
    R"(<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100">)";

}  // namespace

TEST_CASE("errors: not XML, not SVG, nothing to fill") {
  CHECK_ERROR("<svg>\n  <rect width='1' height='1'>\n</svg>\n", "test.svg:3:3", "not valid XML");
  CHECK_ERROR("this is not xml", "test.svg:1:16", "not valid XML");  // where pugixml gave up
  CHECK_ERROR("", "test.svg:1:1", "not valid XML");
  CHECK_ERROR("<?xml version='1.0'?>\n<html><body/></html>", "test.svg:2:1", "not an SVG document");
  CHECK_ERROR(std::string(kHead) + "\n<text>hello</text></svg>", "test.svg", "no shapes to fill");
  CHECK_ERROR(std::string(kHead) + R"(<rect width="10" height="10" fill="none"/><line x2="5" y2="5"/></svg>)",
              "test.svg", "enclose no material");
  CHECK_ERROR(std::string(kHead) + R"(<rect width="0" height="10"/></svg>)", "test.svg",
              "enclose no material");
}

TEST_CASE("errors: units and sizes") {
  CHECK_ERROR(R"(<svg xmlns="http://www.w3.org/2000/svg" width="10furlongs" height="10mm"><rect/></svg>)",
              "test.svg:1:48", "unknown unit 'furlongs'");
  CHECK_ERROR(R"(<svg width="10em" height="10mm"><rect/></svg>)", "test.svg:1:13", "font-relative");
  CHECK_ERROR(R"(<svg width="-5mm" height="10mm"><rect/></svg>)", "test.svg:1:13", "not a usable page size");
  CHECK_ERROR(R"(<svg width="1e9mm" height="10mm"><rect/></svg>)", "test.svg:1:13", "not a usable page size");
  CHECK_ERROR(R"(<svg viewBox="0 0 10"><rect/></svg>)", "test.svg:1:15", "viewBox must be four numbers");
  CHECK_ERROR(R"(<svg viewBox="0 0 10 0"><rect/></svg>)", "test.svg:1:15", "must be positive");
  CHECK_ERROR(std::string(kHead) + "\n" + R"(<rect width="3km" height="1"/></svg>)", "test.svg:2:14",
              "unknown unit 'km'");
  // A drawing larger than any bed, or far from the page: the units are probably wrong.
  CHECK_ERROR(std::string(kHead) + R"(<rect x="-1500" width="3000" height="10"/></svg>)", "test.svg",
              "the drawing is 3000 x 10 mm, larger than 2000 mm");
  CHECK_ERROR(std::string(kHead) + R"(<rect width="5000" height="10"/></svg>)", "test.svg:1:92",
              "more than 2 m from the page origin");
  CHECK_ERROR(std::string(kHead) + "\n" + R"(<rect x="1e7" width="1" height="1"/></svg>)", "test.svg:2:1",
              "more than 2 m from the page origin");
  CHECK_ERROR(std::string(kHead) + R"(<rect width="-1" height="10"/></svg>)", "test.svg:1:105",
              "negative width");
  CHECK_ERROR(std::string(kHead) + R"(<circle r="-1"/></svg>)", "test.svg:1:103", "negative r");
}

TEST_CASE("errors: malformed path data and transforms point at the character") {
  // The 'x' is on line 3, column 23 of the file.
  CHECK_ERROR(std::string(kHead) + "\n<g>\n  <path d=\"M 0 0 L 10 x\"/>\n</g></svg>", "test.svg:3:23",
              "expected a number for 'L'");
  CHECK_ERROR(std::string(kHead) + "\n<path d=\"M 0 0 L 10 x\"/></svg>", "test.svg:2:21",
              "at character 12 of d");
  // With an entity before the error the raw text does not map one to one: the element is named.
  CHECK_ERROR(std::string(kHead) + "\n<path d=\"M&#32;0 0 L 10 x\"/></svg>", "test.svg:2:1",
              "expected a number");
  CHECK_ERROR(std::string(kHead) + "\n<rect width='1' height='1' transform='rotate(1, 2)'/></svg>",
              "test.svg:2:39", "rotate() takes 1 or 3 numbers, got 2");
  CHECK_ERROR(std::string(kHead) + "\n<rect width='1' height='1' transform='spin(3)'/></svg>",
              "test.svg:2:39", "unknown transform 'spin'");
  CHECK_ERROR(std::string(kHead) + "\n<rect width='1' height='1' transform='scale(2'/></svg>",
              "test.svg:2:44", "missing ')'");
  CHECK_ERROR(std::string(kHead) + "\n<polygon points='0,0 10,0 10,a'/></svg>", "test.svg:2:30",
              "expected a number in the points list");
}

TEST_CASE("errors: cycles and runaway nesting") {
  CHECK_ERROR(std::string(kHead) + R"(<g id="a"><use href="#a"/></g></svg>)", "test.svg:1:102", "a cycle");
  CHECK_ERROR(std::string(kHead) + R"(<use id="u" href="#u"/></svg>)", "test.svg:1:92", "a cycle");
  std::string deep = kHead;
  for (int i = 0; i < 300; ++i) deep += "<g>";
  deep += R"(<rect width="1" height="1"/>)";
  for (int i = 0; i < 300; ++i) deep += "</g>";
  deep += "</svg>";
  Error e = parse_error(deep);
  CHECK(contains(e.message, "nested deeper than 256"));
  // Uses of uses multiply: ten levels of ten copies would be 10^10 shapes.
  std::string bomb = std::string(kHead) + R"(<defs><rect id="l0" width="1" height="1"/>)";
  for (int i = 1; i <= 10; ++i) {
    bomb += "<g id=\"l" + std::to_string(i) + "\">";
    for (int k = 0; k < 10; ++k) bomb += "<use href=\"#l" + std::to_string(i - 1) + "\"/>";
    bomb += "</g>";
  }
  bomb += R"(</defs><use href="#l10"/></svg>)";
  e = parse_error(bomb);
  CHECK(contains(e.message, "more than 1000000 elements"));
}

TEST_CASE("errors: options") {
  geo::SvgImportOptions bad_tol;
  bad_tol.tolerance_mm = 0;
  Error e = parse_error(page_mm(R"(<rect width="1" height="1"/>)"), bad_tol);
  CHECK(contains(e.message, "tolerance"));
  geo::SvgImportOptions bad_bg;
  bad_bg.background = "blurple";
  e = parse_error(page_mm(R"(<rect width="1" height="1"/>)"), bad_bg);
  CHECK(e.where == "--background");
  CHECK(contains(e.message, "\"blurple\" is not a colour"));
}

TEST_CASE("errors: files") {
  Report report;
  auto r = geo::load_svg("/nonexistent/drawing.svg", {}, report);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().where == "/nonexistent/drawing.svg");
  CHECK(contains(r.error().message, "cannot open"));
}

TEST_CASE("warnings: ignored content is reported with its location") {
  Report report;
  std::string doc = std::string(kHead) + R"svg(
<style>rect { fill: red }</style>
<text x="1" y="1">hi</text>
<image href="x.png" width="1" height="1"/>
<line x1="0" y1="0" x2="10" y2="10" stroke="black"/>
<rect width="10" height="10" fill="none" stroke="black"/>
<polygon points="0,0 10,0 10,10 5"/>
<rect width="10" height="10" fill="url(#grad)" clip-path="url(#c)"/>
<rect width="0" height="10" fill="black"/>
<use href="#missing"/>
<path d="M 0 0 L 5 5 Z"/>
</svg>)svg";
  geo::SvgModel m = parse_ok(doc, report);
  CHECK(geo::area_mm2(m.layers[0].polygons) > 0);
  auto w = report.warnings();
  auto find = [&](const std::string& code) -> const Warning* {
    for (const auto& x : w)
      if (x.code == code) return &x;
    return nullptr;
  };
  struct Expect {
    const char* code;
    const char* where;
    const char* part;
  };
  for (Expect x : {Expect{"svg-css", "test.svg:2:1", "stylesheets are not applied"},
                   Expect{"svg-ignored", "test.svg:3:1", "<text> is not material"},
                   Expect{"svg-line", "test.svg:5:1", "<line> encloses no area"},
                   Expect{"svg-stroke", "test.svg:6:1", "strokes are not material"},
                   Expect{"svg-points", "test.svg:7:1", "odd count"},
                   Expect{"svg-paint", "test.svg:8:1", "gradient or pattern"},
                   Expect{"svg-clip", "test.svg:8:1", "clip-path and mask are not applied"},
                   Expect{"svg-use", "test.svg:10:1", "\"#missing\", which is not in the file"},
                   Expect{"svg-zero-area", "test.svg:9:1", "encloses no area"}}) {
    CAPTURE(x.code);
    const Warning* got = find(x.code);
    REQUIRE(got != nullptr);
    CHECK(got->where == x.where);
    CHECK(contains(got->message, x.part));
  }
  CHECK(report.count("svg-ignored") == 2);  // text and image
  CHECK(report.count("svg-css") == 1);
  CHECK(report.count("svg-zero-area") == 2);  // the empty rect and the two-point path
}

TEST_CASE("files: load_svg reads from disk") {
  tranche::test::TempDir dir("svg");
  auto path = (dir / "square.svg").string();
  std::ofstream(path) << page_mm(R"(<rect width="10" height="10"/>)");
  Report report;
  auto r = geo::load_svg(path, {}, report);
  REQUIRE(r.ok());
  CHECK(geo::area_mm2(r->layers[0].polygons) == doctest::Approx(100));
  CHECK(geo::looks_like_svg("\xef\xbb\xbf<?xml version='1.0'?>\n<svg>"));
  CHECK(geo::looks_like_svg("  <svg:svg xmlns:svg='http://www.w3.org/2000/svg'>"));
  CHECK_FALSE(geo::looks_like_svg("solid cube\n facet normal"));
}
