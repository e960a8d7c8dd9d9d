// Path data: the tokenizer, every command, implicit repeats, curve flattening and arcs.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "geometry/io/svg_path.h"
#include "svg_test_util.h"

using namespace tranche;
using geo::svg::Subpath;
using geo::svg::Vec2;

namespace {

constexpr double kPi = std::numbers::pi;

std::vector<Subpath> parse(const std::string& d, double tol = 0.01) {
  auto r = geo::svg::parse_path_data(d, tol);
  if (!r) FAIL("path '" << d << "': " << r.error().message);
  return std::move(r).value();
}

// Shoelace area of one subpath (closed implicitly), signed: positive when counter-clockwise in a
// y-up frame.
double signed_area(const std::vector<Vec2>& pts) {
  double a = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    const Vec2& p = pts[i];
    const Vec2& q = pts[(i + 1) % pts.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return a / 2;
}

double path_area(const std::string& d, double tol = 0.01) {
  return tranche::test::area_of(tranche::test::page_mm("<path d=\"" + d + "\"/>"),
                                geo::SvgImportOptions{tol, geo::SvgOverlap::Additive, "white"});
}

}  // namespace

TEST_CASE("path: straight commands, absolute and relative") {
  auto sp = parse("M 1 2 L 11 2 L 11 12 L 1 12 Z");
  REQUIRE(sp.size() == 1);
  CHECK(sp[0].closed);
  REQUIRE(sp[0].points.size() == 4);
  CHECK(sp[0].points[2].x == 11);
  CHECK(sp[0].points[2].y == 12);
  CHECK(std::abs(signed_area(sp[0].points)) == doctest::Approx(100));

  auto rel = parse("m 1 2 l 10 0 l 0 10 l -10 0 z");
  REQUIRE(rel.size() == 1);
  CHECK(rel[0].points[2].x == 11);
  CHECK(rel[0].points[2].y == 12);

  auto hv = parse("M0 0 H10 V10 H0 Z m 20 0 h 5 v 5 h -5 z");
  REQUIRE(hv.size() == 2);
  CHECK(std::abs(signed_area(hv[0].points)) == doctest::Approx(100));
  CHECK(hv[1].points[0].x == 20);  // relative moveto after Z starts from the subpath start
  CHECK(hv[1].points[0].y == 0);
  CHECK(std::abs(signed_area(hv[1].points)) == doctest::Approx(25));
}

TEST_CASE("path: implicit repeats and compact number syntax") {
  auto implicit_l = parse("M0 0 10 0 10 10 0 10z");  // pairs after M are linetos
  REQUIRE(implicit_l.size() == 1);
  CHECK(implicit_l[0].points.size() == 4);
  auto implicit_rel = parse("m0 0 10 0 0 10 -10 0z");  // pairs after m are relative linetos
  CHECK(implicit_rel[0].points[2].x == 10);
  CHECK(implicit_rel[0].points[2].y == 10);
  auto repeated = parse("M0,0 L10,0,10,10 0,10z");  // commas between groups
  CHECK(repeated[0].points.size() == 4);
  auto compact = parse("M.5.5L10-5l-1e1,0Z");  // ".5.5" is two numbers; "10-5" is two; 1e1 = 10
  REQUIRE(compact[0].points.size() == 3);
  CHECK(compact[0].points[0].x == 0.5);
  CHECK(compact[0].points[0].y == 0.5);
  CHECK(compact[0].points[1].x == 10);
  CHECK(compact[0].points[1].y == -5);
  CHECK(compact[0].points[2].x == 0);
  CHECK(compact[0].points[2].y == -5);
}

TEST_CASE("path: drawing after Z without a moveto starts at the subpath start") {
  auto sp = parse("M 5 5 h 10 v 10 z l 10 0 l 0 -10 z");
  REQUIRE(sp.size() == 2);
  CHECK(sp[1].points[0].x == 5);
  CHECK(sp[1].points[0].y == 5);
  CHECK(sp[1].points[1].x == 15);
}

TEST_CASE("path: cubic and quadratic Béziers match their analytic areas") {
  // The cubic (0,0) (0,10) (10,10) (10,0) bounds 0.6 * w * h with its chord (integral of y dx).
  double tol = 0.01;
  double cubic = path_area("M0 0 C 0 10 10 10 10 0 Z", tol);
  CHECK(cubic <= 60.0 + 1e-6);
  CHECK(cubic >= 60.0 - 30 * tol);  // an inscribed polyline loses at most length * tol
  // The parabola (0,0) (5,10) (10,0) rises to 5: area 2/3 * 10 * 5.
  double quad = path_area("M0 0 Q 5 10 10 0 Z", tol);
  CHECK(quad <= 100.0 / 3 + 1e-6);
  CHECK(quad >= 100.0 / 3 - 30 * tol);
  // S and T reflect the previous control point: a second, mirrored lobe of the same area.
  CHECK(path_area("M0 0 C 0 10 10 10 10 0 S 20 -10 20 0 Z", tol) == doctest::Approx(2 * cubic).epsilon(1e-4));
  CHECK(path_area("M0 0 Q 5 10 10 0 T 20 0 Z", tol) == doctest::Approx(2 * quad).epsilon(1e-4));
  // Without a preceding C, S's first control point is the current point (a different curve).
  CHECK(path_area("M0 0 L 10 0 S 20 -10 20 0 Z", tol) < 0.8 * cubic);
  // Relative forms give the same shapes.
  CHECK(path_area("m0 0 c 0 10 10 10 10 0 s 10 -10 10 0 z", tol) == doctest::Approx(2 * cubic).epsilon(1e-4));
  CHECK(path_area("m0 0 q 5 10 10 0 t 10 0 z", tol) == doctest::Approx(2 * quad).epsilon(1e-4));
}

TEST_CASE("path: flattened curves stay within the tolerance") {
  for (double tol : {0.1, 0.01, 0.001}) {
    std::vector<Vec2> pts{{0, 0}};
    geo::svg::flatten_cubic({0, 0}, {0, 10}, {10, 10}, {10, 0}, tol, pts);
    // The curve's true points at fine parameter steps lie within tol of the polyline.
    double worst = 0;
    for (int i = 0; i <= 1000; ++i) {
      double t = i / 1000.0, s = 1 - t;
      Vec2 b{3 * s * t * t * 10 + t * t * t * 10, 3 * s * s * t * 10 + 3 * s * t * t * 10};
      double best = 1e9;
      for (size_t k = 0; k + 1 < pts.size(); ++k) {
        Vec2 a = pts[k], c = pts[k + 1];
        double vx = c.x - a.x, vy = c.y - a.y;
        double u = std::clamp(((b.x - a.x) * vx + (b.y - a.y) * vy) / (vx * vx + vy * vy), 0.0, 1.0);
        best = std::min(best, std::hypot(a.x + u * vx - b.x, a.y + u * vy - b.y));
      }
      worst = std::max(worst, best);
    }
    CHECK(worst <= tol);
    CHECK(worst > tol / 20);  // and not absurdly finer than asked
  }
}

TEST_CASE("arc: endpoint to centre conversion for the four flag combinations") {
  // From (10, 0) to (0, -10) with r = 10 the centre is (0, 0) or (10, -10).
  struct Case {
    bool large, sweep;
    double cx, cy, dtheta_deg;
  };
  for (Case c : {Case{false, false, 0, 0, -90}, Case{true, true, 0, 0, 270}, Case{false, true, 10, -10, 90},
                 Case{true, false, 10, -10, -270}}) {
    CAPTURE(c.large);
    CAPTURE(c.sweep);
    auto a = geo::svg::arc_endpoint_to_center({10, 0}, 10, 10, 0, c.large, c.sweep, {0, -10});
    REQUIRE(a.has_value());
    CHECK(a->center.x == doctest::Approx(c.cx).epsilon(1e-9));
    CHECK(a->center.y == doctest::Approx(c.cy).epsilon(1e-9));
    CHECK(a->dtheta * 180 / kPi == doctest::Approx(c.dtheta_deg));
    CHECK(a->rx == doctest::Approx(10));
  }
  // Radii too small to reach are scaled up (F.6.6): a half circle of radius 10.
  auto small = geo::svg::arc_endpoint_to_center({0, 0}, 1, 1, 0, false, true, {20, 0});
  REQUIRE(small.has_value());
  CHECK(small->rx == doctest::Approx(10));
  CHECK(small->center.x == doctest::Approx(10));
  CHECK(std::abs(small->dtheta) == doctest::Approx(kPi));
  // Degenerate arcs: equal endpoints draw nothing, a zero radius is a straight line.
  CHECK_FALSE(geo::svg::arc_endpoint_to_center({1, 1}, 5, 5, 0, false, true, {1, 1}).has_value());
  std::vector<Vec2> out;
  geo::svg::flatten_arc({0, 0}, 0, 5, 0, false, true, {7, 3}, 0.01, out);
  REQUIRE(out.size() == 1);
  CHECK(out[0].x == 7);
}

TEST_CASE("arc: pie slices and half discs have their analytic areas") {
  double tol = 0.001;
  double slack = 2 * kPi * 10 * tol;  // perimeter * tolerance
  auto near = [&](double got, double want) {
    CHECK(got <= want + 1e-6);
    CHECK(got >= want - slack);
  };
  near(path_area("M0 0 L10 0 A10 10 0 1 1 0 -10 Z", tol), 75 * kPi);  // three quarters
  near(path_area("M0 0 L10 0 A10 10 0 0 0 0 -10 Z", tol), 25 * kPi);  // one quarter
  near(path_area("M0 0 A1 1 0 0 1 20 0 Z", tol), 50 * kPi);           // radii scaled up
  near(path_area("M0 0 a5 5 0 1010 0 z", tol), 12.5 * kPi);           // flags need no separator
}

TEST_CASE("arc: a rotated elliptical arc stays on its ellipse") {
  // Ellipse rx = 20, ry = 10 rotated 30°, centre (0, 0): go between two of its points.
  double phi = 30 * kPi / 180;
  auto on = [&](double t) {
    double ex = 20 * std::cos(t), ey = 10 * std::sin(t);
    return Vec2{std::cos(phi) * ex - std::sin(phi) * ey, std::sin(phi) * ex + std::cos(phi) * ey};
  };
  Vec2 p0 = on(0.3), p1 = on(2.5);
  std::vector<Vec2> pts;
  geo::svg::flatten_arc(p0, 20, 10, 30, false, true, p1, 0.01, pts);
  REQUIRE(pts.size() > 10);
  for (const Vec2& p : pts) {
    double x = std::cos(phi) * p.x + std::sin(phi) * p.y, y = -std::sin(phi) * p.x + std::cos(phi) * p.y;
    CHECK(x * x / 400 + y * y / 100 == doctest::Approx(1).epsilon(1e-9));
  }
  auto a = geo::svg::arc_endpoint_to_center(p0, 20, 10, 30, false, true, p1);
  REQUIRE(a.has_value());
  CHECK(a->center.x == doctest::Approx(0).scale(1));
  CHECK(a->center.y == doctest::Approx(0).scale(1));
  CHECK(a->dtheta == doctest::Approx(2.2));
}

TEST_CASE("path: malformed data reports what was expected and where") {
  struct Case {
    const char* d;
    size_t offset;
    const char* message;
  };
  for (Case c :
       {Case{"M 0 0 L 10 x", 11, "expected a number for 'L'"}, Case{"L 0 0", 0, "must start with a moveto"},
        Case{"M 0 0 K 3 3", 6, "unknown path command 'K'"},
        Case{"M 0 0 A 5 5 0 2 1 3 3", 14, "expected a flag (0 or 1) for 'A'"},
        Case{"M 0 0 Z 5", 8, "unexpected number after closepath"},
        Case{"M 0 0 L 1e999 0", 8, "number out of range"},
        Case{"M 0 0 L 5 5,", 12, "expected a number after ','"},
        Case{"M 0 0 C 1 1 2 2", 15, "expected a number for 'C'"},
        Case{"M 0 0 # 1 2", 6, "unexpected character '#'"}}) {
    CAPTURE(c.d);
    size_t at = 999;
    auto r = geo::svg::parse_path_data(c.d, 0.01, &at);
    REQUIRE_FALSE(r.ok());
    CHECK(at == c.offset);
    CHECK(r.error().message.find(c.message) != std::string::npos);
  }
  // A point budget stops runaway flattening (huge arcs at a tiny tolerance) at the command.
  size_t at = 0;
  auto big = geo::svg::parse_path_data("M0 0 L 1 1 A 1000 1000 0 1 0 2 0", 0.001, &at, 1000);
  REQUIRE_FALSE(big.ok());
  CHECK(at == 11);
  CHECK(big.error().message.find("more than 1000 points") != std::string::npos);
  CHECK(geo::svg::parse_path_data("M0 0 L 1 1 A 1000 1000 0 1 0 2 0", 0.001, &at, 100000).ok());
  CHECK(parse("").empty());
  CHECK(parse("   ").empty());
}
