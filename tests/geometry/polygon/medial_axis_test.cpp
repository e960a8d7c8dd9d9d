// The medial axis on constructed shapes (a bar, a wedge, a tube) and on random polygons.
#include <doctest/doctest.h>

#include <cmath>

#include "generators.h"
#include "geometry/polygon/medial_axis.h"

using namespace tranche;
using namespace tranche::geo;
using doctest::Approx;

namespace {

Ring rect(double x0, double y0, double x1, double y1) {
  return {to_point(x0, y0), to_point(x1, y0), to_point(x1, y1), to_point(x0, y1)};
}

Ring circle(double r, int n, bool ccw = true) {
  Ring out;
  for (int i = 0; i < n; ++i) {
    double a = 2 * M_PI * i / n * (ccw ? 1 : -1);
    out.push_back(to_point(r * std::cos(a), r * std::sin(a)));
  }
  return out;
}

double total_length(const AxisPath& p) {
  double l = 0;
  for (size_t i = 1; i < p.pts.size(); ++i)
    l += std::hypot(to_mm(p.pts[i].X - p.pts[i - 1].X), to_mm(p.pts[i].Y - p.pts[i - 1].Y));
  return l;
}

}  // namespace

TEST_CASE("medial axis: a 0.6 x 20 mm bar has one axis along its middle, 0.6 mm wide") {
  auto axis = medial_axis({rect(0, 0, 20, 0.6)});
  REQUIRE(axis.size() == 1);
  const AxisPath& a = axis[0];
  CHECK_FALSE(a.closed);
  REQUIRE(a.pts.size() == a.radius_mm.size());
  for (size_t i = 0; i < a.pts.size(); ++i) {
    CHECK(to_mm(a.pts[i].Y) == Approx(0.3).epsilon(1e-6));
    CHECK(a.radius_mm[i] == Approx(0.3).epsilon(1e-6));
  }
  // The corners' branches are pruned: the axis ends where they met, half a width from the ends.
  double x0 = to_mm(std::min(a.pts.front().X, a.pts.back().X)), x1 = to_mm(std::max(a.pts.front().X, a.pts.back().X));
  CHECK(x0 == Approx(0.3).epsilon(1e-6));
  CHECK(x1 == Approx(19.7).epsilon(1e-6));
}

TEST_CASE("medial axis: a wedge's width grows linearly from its tip") {
  // Tip at the origin, 3 mm wide at x = 20.
  Ring wedge{to_point(0, 0), to_point(20, -1.5), to_point(20, 1.5)};
  auto axis = medial_axis({wedge});
  const AxisPath* spine = nullptr;
  for (const auto& a : axis)
    for (const Point& p : {a.pts.front(), a.pts.back()})
      if (std::abs(to_mm(p.X)) < 1e-3 && std::abs(to_mm(p.Y)) < 1e-3) spine = &a;
  REQUIRE(spine != nullptr);  // the axis reaches the tip
  const double sin_half = std::sin(std::atan(1.5 / 20));
  int checked = 0;
  for (size_t i = 0; i < spine->pts.size(); ++i) {
    const double x = to_mm(spine->pts[i].X);
    CHECK(std::abs(to_mm(spine->pts[i].Y)) < 1e-4);
    CHECK(spine->radius_mm[i] == Approx(x * sin_half).epsilon(1e-4));
    ++checked;
  }
  CHECK(checked >= 2);
  CHECK(total_length(*spine) > 15);
}

TEST_CASE("medial axis: a tube's axis is a closed loop half way through its wall") {
  // Outer radius 5 mm, inner 4.2: a 0.8 mm wall.
  auto axis = medial_axis({circle(5, 256), circle(4.2, 256, false)});
  REQUIRE(axis.size() == 1);
  CHECK(axis[0].closed);
  CHECK(axis[0].pts.front() == axis[0].pts.back());
  for (size_t i = 0; i < axis[0].pts.size(); ++i) {
    const double r = std::hypot(to_mm(axis[0].pts[i].X), to_mm(axis[0].pts[i].Y));
    CHECK(r == Approx(4.6).epsilon(2e-3));
    CHECK(axis[0].radius_mm[i] == Approx(0.4).epsilon(5e-3));
  }
  CHECK(total_length(axis[0]) == Approx(2 * M_PI * 4.6).epsilon(5e-3));
}

TEST_CASE("medial axis: degenerate input gives no axis") {
  CHECK(medial_axis({}).empty());
  CHECK(medial_axis({Ring{}}).empty());
  CHECK(medial_axis({Ring{to_point(0, 0), to_point(1, 0)}}).empty());
  CHECK(medial_axis({Ring{to_point(0, 0), to_point(1, 0), to_point(2, 0)}}).empty());
  CHECK(medial_axis({Ring{to_point(0, 0), to_point(0, 0), to_point(0, 0)}}).empty());
  // Coordinates too far apart for the Voronoi builder's 32-bit integers.
  CHECK(medial_axis({rect(-1000, -1000, 1000, 1000)}).empty());
}

TEST_CASE("medial axis: random polygons give finite points inside the region") {
  test::gen::Rng rng(14);
  int paths = 0;
  for (int round = 0; round < 150; ++round) {
    Rings region = test::gen::stars_with_holes(rng, round % 3 == 0 ? 100000 : 1);
    auto axis = medial_axis(region);
    for (const auto& a : axis) {
      REQUIRE(a.pts.size() == a.radius_mm.size());
      REQUIRE(a.pts.size() >= 2);
      ++paths;
      for (size_t i = 0; i < a.pts.size(); ++i) {
        REQUIRE(std::isfinite(a.radius_mm[i]));
        CHECK(a.radius_mm[i] >= 0);
        // Inside or on the border (Clipper: -1 on it), up to the rounding of a point to 1 nm.
        int winding = 0;
        bool on = false;
        for (const auto& r : region) {
          int at = ClipperLib::PointInPolygon(a.pts[i], r);
          if (at == -1) on = true;
          if (at == 1) winding += ClipperLib::Orientation(r) ? 1 : -1;
        }
        if (!on && a.radius_mm[i] > 1e-5) CHECK(winding > 0);
      }
    }
  }
  CHECK(paths > 150);
}
