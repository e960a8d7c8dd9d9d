// SVG elements, transforms, units, fill rules and styles: areas and positions against analytic
// values.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "geometry/io/svg_style.h"
#include "svg_test_util.h"

using namespace tranche;
using tranche::test::area_of;
using tranche::test::page_mm;
using tranche::test::parse_ok;

namespace {

constexpr double kPi = std::numbers::pi;

geo::BBox2 bbox_of(const geo::SvgModel& m) {
  geo::BBox2 box;
  for (const auto& p : m.layers.at(0).polygons) {
    geo::BBox2 b = geo::bbox(p);
    box.add({b.min_x, b.min_y});
    box.add({b.max_x, b.max_y});
  }
  return box;
}

void check_box(const std::string& svg, double x0, double y0, double x1, double y1, double eps = 1e-3) {
  geo::BBox2 b = bbox_of(parse_ok(svg));
  CHECK(geo::to_mm(b.min_x) == doctest::Approx(x0).epsilon(eps).scale(1));
  CHECK(geo::to_mm(b.min_y) == doctest::Approx(y0).epsilon(eps).scale(1));
  CHECK(geo::to_mm(b.max_x) == doctest::Approx(x1).epsilon(eps).scale(1));
  CHECK(geo::to_mm(b.max_y) == doctest::Approx(y1).epsilon(eps).scale(1));
}

}  // namespace

TEST_CASE("elements: rect, rounded rect, circle, ellipse, polygon, polyline") {
  CHECK(area_of(page_mm(R"(<rect x="10" y="10" width="20" height="30"/>)")) == doctest::Approx(600));
  // Rounded corners remove (4 - pi) r^2; ry defaults to rx; radii are clamped to half the side.
  double tol = 0.01;
  double rounded = area_of(page_mm(R"(<rect x="10" y="10" width="20" height="30" rx="5"/>)"));
  CHECK(rounded <= 600 - (4 - kPi) * 25 + 1e-6);
  CHECK(rounded >= 600 - (4 - kPi) * 25 - 2 * kPi * 5 * tol);
  double clamped = area_of(page_mm(R"(<rect x="0" y="0" width="20" height="20" rx="50" ry="50"/>)"));
  CHECK(clamped == doctest::Approx(kPi * 100).epsilon(0.003));  // a circle of radius 10
  double elliptic = area_of(page_mm(R"(<rect width="40" height="20" rx="10" ry="5"/>)"));
  CHECK(elliptic == doctest::Approx(800 - (4 - kPi) * 50).epsilon(0.001));

  for (double t : {0.1, 0.01, 0.001}) {
    CAPTURE(t);
    double a =
        area_of(page_mm(R"(<circle cx="50" cy="50" r="20"/>)"), {t, geo::SvgOverlap::Additive, "white"});
    CHECK(a <= kPi * 400 + 1e-6);
    CHECK(a >= kPi * 400 - 2 * kPi * 20 * t);  // perimeter * chord error
  }
  double e = area_of(page_mm(R"(<ellipse cx="50" cy="50" rx="30" ry="10"/>)"));
  CHECK(e <= kPi * 300 + 1e-6);
  CHECK(e >= kPi * 300 - 2 * kPi * 30 * tol);

  CHECK(area_of(page_mm(R"(<polygon points="0,0 40,0 40,10 0,10"/>)")) == doctest::Approx(400));
  CHECK(area_of(page_mm(R"(<polyline points="0 0 40 0 0 30"/>)")) ==
        doctest::Approx(600));  // closed for filling
}

TEST_CASE("the y axis is flipped about the page height, so the print is not mirrored") {
  // A rect at the top-left of a 100 x 100 mm page lands at the top-left of the bed plane.
  check_box(page_mm(R"(<rect x="10" y="0" width="20" height="5"/>)"), 10, 95, 30, 100);
  // An L shape keeps its handedness: the foot points to +x on the page and on the bed.
  geo::SvgModel m = parse_ok(page_mm(R"(<path d="M0 0 H10 V40 H30 V50 H0 Z"/>)"));
  REQUIRE(m.layers[0].polygons.size() == 1);
  geo::BBox2 b = bbox_of(m);
  CHECK(geo::to_mm(b.min_y) == doctest::Approx(50));
  CHECK(geo::to_mm(b.max_y) == doctest::Approx(100));
  // The foot (x up to 30) is at the bottom (y from 50 to 60 on the bed).
  bool foot_low = false;
  for (const auto& p : m.layers[0].polygons[0].outer)
    if (p.X == geo::to_units(30)) foot_low = geo::to_mm(p.Y) <= 60 + 1e-9;
  CHECK(foot_low);
  CHECK(m.page_width_mm == doctest::Approx(100));
  CHECK(m.page_height_mm == doctest::Approx(100));
  CHECK_FALSE(m.layer_stack);
  // Outer rings come out counter-clockwise.
  CHECK(geo::area_mm2(m.layers[0].polygons[0].outer) > 0);
}

TEST_CASE("transforms: translate, scale, rotate about a point, skew, matrix, lists, nesting") {
  const char* sq = R"(<rect x="40" y="40" width="20" height="20" transform="%s"/>)";
  auto with = [&](const std::string& t) {
    char buf[256];
    std::snprintf(buf, sizeof buf, sq, t.c_str());
    return page_mm(buf);
  };
  // translate(5, -10): page y 30..50 -> bed y 50..70.
  check_box(with("translate(5, -10)"), 45, 50, 65, 70);
  check_box(with("translate(5)"), 45, 40, 65, 60);
  CHECK(area_of(with("scale(2 0.5)")) == doctest::Approx(400 * 1.0));
  check_box(with("scale(0.5)"), 20, 70, 30, 80);
  // rotate(45 50 50): the square turns about its own centre into a diamond of half-diagonal 14.14.
  double h = 10 * std::sqrt(2.0);
  check_box(with("rotate(45 50 50)"), 50 - h, 50 - h, 50 + h, 50 + h);
  CHECK(area_of(with("rotate(45 50 50)")) == doctest::Approx(400));
  // rotate(90) about the origin: (x, y) -> (-y, x): x in -60..-40 and page y 40..60.
  check_box(with("rotate(90)"), -60, 40, -40, 60);
  // skewX(45): x += y, area kept; skewY(45): y += x.
  check_box(with("skewX(45)"), 80, 40, 120, 60);
  CHECK(area_of(with("skewX(45)")) == doctest::Approx(400));
  check_box(with("skewY(-45)"), 40, 80, 60, 120);  // y -= x: page -20..20
  // matrix(a b c d e f) = translate(10 0) scale(2); lists apply right to left.
  check_box(with("matrix(2 0 0 2 10 0)"), 90, -20, 130, 20);
  check_box(with("translate(10,0) scale(2)"), 90, -20, 130, 20);
  check_box(with("scale(2) translate(10,0)"), 100, -20, 140, 20);
  // Nested groups compose parent-first.
  check_box(page_mm(R"svg(<g transform="translate(10 0)"><g transform="scale(2)">
      <rect x="40" y="40" width="20" height="20"/></g></g>)svg"),
            90, -20, 130, 20);
}

TEST_CASE("units: the root size and viewBox map user units to millimetres") {
  auto doc = [](const std::string& attrs, const std::string& body) {
    return R"(<svg xmlns="http://www.w3.org/2000/svg" )" + attrs + ">" + body + "</svg>";
  };
  const std::string rect = R"(<rect width="10" height="10"/>)";
  // One user unit is 0.5 mm.
  CHECK(area_of(doc(R"(width="100mm" height="50mm" viewBox="0 0 200 100")", rect)) == doctest::Approx(25));
  CHECK(area_of(doc(R"(width="10cm" height="5cm" viewBox="0 0 200 100")", rect)) == doctest::Approx(25));
  // 1 in = 25.4 mm; 72 pt = 1 in; 6 pc = 1 in; no unit and px are 1/96 in.
  CHECK(area_of(doc(R"(width="1in" height="1in" viewBox="0 0 10 10")", rect)) ==
        doctest::Approx(25.4 * 25.4));
  CHECK(area_of(doc(R"(width="72pt" height="72pt" viewBox="0 0 10 10")", rect)) ==
        doctest::Approx(25.4 * 25.4));
  CHECK(area_of(doc(R"(width="6pc" height="6pc" viewBox="0 0 10 10")", rect)) ==
        doctest::Approx(25.4 * 25.4));
  CHECK(area_of(doc(R"(width="96" height="96")", rect)) == doctest::Approx(std::pow(10 * 25.4 / 96, 2)));
  CHECK(area_of(doc(R"(width="96px" height="96px")", rect)) == doctest::Approx(std::pow(10 * 25.4 / 96, 2)));
  CHECK(area_of(doc("", rect)) == doctest::Approx(std::pow(10 * 25.4 / 96, 2)));  // no size at all: px
  CHECK(area_of(doc(R"(viewBox="0 0 10 10")", rect)) == doctest::Approx(std::pow(10 * 25.4 / 96, 2)));
  // Lengths on shapes carry units too (in user space: 1mm = 96/25.4 user units).
  CHECK(area_of(doc(R"(width="100mm" height="100mm" viewBox="0 0 100 100")",
                    R"(<rect width="10mm" height="1cm"/>)")) == doctest::Approx(std::pow(10 * 96 / 25.4, 2)));
  // Percentages refer to the viewport in user units (a background rect of 100% is common).
  CHECK(area_of(doc(R"(width="100mm" height="50mm" viewBox="0 0 200 100")",
                    R"(<rect width="100%" height="50%"/>)")) == doctest::Approx(100 * 25));
  CHECK(area_of(doc(R"(width="100mm" height="100mm" viewBox="0 0 100 100")",
                    R"(<circle cx="50%" cy="50%" r="10%"/>)")) ==
        doctest::Approx(std::numbers::pi * 100).epsilon(0.003));
  // preserveAspectRatio: a 100 x 50 mm page over a square viewBox scales uniformly by default
  // (meet: 0.5 mm per unit, centred) and stretches with "none".
  CHECK(area_of(doc(R"(width="100mm" height="50mm" viewBox="0 0 100 100")", rect)) == doctest::Approx(25));
  CHECK(area_of(doc(R"(width="100mm" height="50mm" viewBox="0 0 100 100" preserveAspectRatio="none")",
                    rect)) == doctest::Approx(50));
  // meet centres the viewBox horizontally: x offset 25 mm.
  geo::SvgModel m = parse_ok(doc(R"(width="100mm" height="50mm" viewBox="0 0 100 100")", rect));
  geo::BBox2 b = bbox_of(m);
  CHECK(geo::to_mm(b.min_x) == doctest::Approx(25));
  CHECK(geo::to_mm(b.max_y) == doctest::Approx(50));
  // A viewBox origin shifts user space.
  check_box(
      doc(R"(width="100mm" height="100mm" viewBox="-50 -50 100 100")", R"(<rect width="10" height="10"/>)"),
      50, 40, 60, 50);
}

TEST_CASE("length and colour parsing") {
  CHECK(*geo::svg::parse_length_px("25.4mm") == doctest::Approx(96));
  CHECK(*geo::svg::parse_length_px(" 1e1 ") == doctest::Approx(10));
  CHECK(*geo::svg::parse_length_px("1e1mm") == doctest::Approx(10 * 96 / 25.4));
  CHECK(*geo::svg::parse_length_px("4Q") == doctest::Approx(96 / 25.4));
  CHECK_FALSE(geo::svg::parse_length_px("3 furlongs").ok());
  CHECK_FALSE(geo::svg::parse_length_px("50%").ok());
  CHECK_FALSE(geo::svg::parse_length_px("2em").ok());
  CHECK_FALSE(geo::svg::parse_length_px("mm").ok());
  CHECK(*geo::svg::parse_color("white") == 0xffffffu);
  CHECK(*geo::svg::parse_color("#FFF") == 0xffffffu);
  CHECK(*geo::svg::parse_color("#12ab3C") == 0x12ab3cu);
  CHECK(*geo::svg::parse_color("rgb(255, 0, 10)") == 0xff000au);
  CHECK(*geo::svg::parse_color("rgb(100%,0%,50%)") == 0xff0080u);
  CHECK(*geo::svg::parse_color("rgb(255 128 0)") == 0xff8000u);
  CHECK(*geo::svg::parse_color("RebeccaPurple") == 0x663399u);
  CHECK_FALSE(geo::svg::parse_color("#12345").has_value());
  CHECK_FALSE(geo::svg::parse_color("blurple").has_value());
  CHECK(geo::svg::parse_paint("none")->kind == geo::svg::Paint::Kind::None);
  CHECK(geo::svg::parse_paint("url(#g) none")->kind == geo::svg::Paint::Kind::None);
  CHECK(geo::svg::parse_paint("url(#g)")->kind == geo::svg::Paint::Kind::Url);
}

TEST_CASE("fill rules: nonzero and evenodd, by attribute, style and inheritance") {
  // Two squares drawn the same way round: nonzero fills the inner one, evenodd makes it a hole.
  const std::string same = "M0 0 H40 V40 H0 Z M10 10 H30 V30 H10 Z";
  const std::string opposite = "M0 0 H40 V40 H0 Z M10 10 V30 H30 V10 Z";
  auto path = [](const std::string& d, const std::string& attrs = "") {
    return page_mm("<path d=\"" + d + "\" " + attrs + "/>");
  };
  CHECK(area_of(path(same)) == doctest::Approx(1600));
  CHECK(area_of(path(same, R"(fill-rule="evenodd")")) == doctest::Approx(1200));
  CHECK(area_of(path(same, R"(style="fill-rule: evenodd")")) == doctest::Approx(1200));
  CHECK(area_of(path(opposite)) == doctest::Approx(1200));  // nonzero: opposite winding is a hole
  CHECK(area_of(path(opposite, R"(fill-rule="evenodd")")) == doctest::Approx(1200));
  // Inherited from a group; a style declaration beats a presentation attribute.
  CHECK(area_of(page_mm("<g fill-rule=\"evenodd\"><path d=\"" + same + "\"/></g>")) == doctest::Approx(1200));
  CHECK(area_of(page_mm("<g style=\"fill-rule:evenodd\"><path d=\"" + same +
                        "\" fill-rule=\"nonzero\"/></g>")) == doctest::Approx(1600));
  CHECK(area_of(page_mm("<g fill-rule=\"evenodd\"><path d=\"" + same +
                        "\" style=\"fill-rule:nonzero\"/></g>")) == doctest::Approx(1600));
  CHECK(area_of(page_mm("<g fill-rule=\"evenodd\"><path d=\"" + same + "\" fill-rule=\"inherit\"/></g>")) ==
        doctest::Approx(1200));
}

TEST_CASE("fill and visibility decide what is material") {
  auto rect = [&](const std::string& attrs) { return "<rect width=\"10\" height=\"10\" " + attrs + "/>"; };
  const std::string other = R"(<rect x="50" width="20" height="20"/>)";  // 400 mm², always material
  CHECK(area_of(page_mm(rect("") + other)) == doctest::Approx(500));
  CHECK(area_of(page_mm(rect(R"(fill="none")") + other)) == doctest::Approx(400));
  CHECK(area_of(page_mm(rect(R"(style="fill:none")") + other)) == doctest::Approx(400));
  CHECK(area_of(page_mm("<g fill=\"none\">" + rect("") + "</g>" + other)) == doctest::Approx(400));
  CHECK(area_of(page_mm("<g fill=\"none\">" + rect(R"(fill="red")") + "</g>" + other)) ==
        doctest::Approx(500));
  CHECK(area_of(page_mm(rect(R"(display="none")") + other)) == doctest::Approx(400));
  CHECK(area_of(page_mm("<g style=\"display:none\">" + rect(R"(display="inline")") + "</g>" + other)) ==
        doctest::Approx(400));  // display:none hides the whole subtree
  CHECK(area_of(page_mm(rect(R"(visibility="hidden")") + other)) == doctest::Approx(400));
  CHECK(area_of(page_mm("<g visibility=\"hidden\">" + rect(R"(visibility="visible")") + "</g>" + other)) ==
        doctest::Approx(500));  // visibility is inherited but a child may override it
  // <defs> content is not drawn; <use> draws it, moved by x, y; href and xlink:href both work.
  CHECK(area_of(page_mm("<defs>" + rect(R"(id="sq")") + "</defs>" + other)) == doctest::Approx(400));
  geo::SvgModel m =
      parse_ok(page_mm("<defs>" + rect(R"(id="sq")") + R"svg(</defs><use href="#sq" x="20" y="0"/>
      <use xlink:href="#sq" x="20" y="80" transform="translate(5 0)"/>)svg"));
  CHECK(geo::area_mm2(m.layers[0].polygons) == doctest::Approx(200));
  geo::BBox2 b = bbox_of(m);
  CHECK(geo::to_mm(b.min_x) == doctest::Approx(20));
  CHECK(geo::to_mm(b.max_x) == doctest::Approx(35));
  // A symbol draws its children through <use>.
  CHECK(area_of(page_mm("<symbol id=\"s\">" + rect("") + rect(R"(x="20")") +
                        "</symbol><use href=\"#s\"/>")) == doctest::Approx(200));
}

TEST_CASE("a nested svg element is a viewport at its x, y") {
  check_box(page_mm(R"(<svg x="10" y="10" width="20" height="20" viewBox="0 0 10 10">
      <rect width="10" height="10"/></svg>)"),
            10, 70, 30, 90);
}
