// Adaptive layer heights and layer.max_slope from a mesh's facets (geometry/slice/surface_slopes.h).
#include "geometry/slice/surface_slopes.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/mesh/primitives.h"

using namespace tranche::geo;
using doctest::Approx;

namespace {

struct Face {
  double zmin, zmax, nz;
};

// |n_z| and the z span of every facet, computed here independently of the planner.
std::vector<Face> faces_of(const Mesh& m) {
  std::vector<Face> out;
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    double nx = (b.y - a.y) * (c.z - a.z) - (b.z - a.z) * (c.y - a.y);
    double ny = (b.z - a.z) * (c.x - a.x) - (b.x - a.x) * (c.z - a.z);
    double nz = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    out.push_back({std::min({a.z, b.z, c.z}), std::max({a.z, b.z, c.z}), std::abs(nz) / len});
  }
  return out;
}

// Layers bottom to top from the planner alone: (z_bottom, height).
std::vector<std::pair<double, double>> plan(const SurfaceSlopes& s, double top, const AdaptiveParams& p) {
  std::vector<std::pair<double, double>> out;
  for (double z = 0; z < top - 1e-9;) {
    double h = s.adaptive_height(z, p);
    REQUIRE(h > 0);
    out.emplace_back(z, h);
    z += h;
  }
  return out;
}

}  // namespace

TEST_CASE("adaptive layers: contradictory bounds are errors naming the properties") {
  AdaptiveParams p;
  CHECK(check_adaptive(p).ok());
  p.min_height = 0.3;
  p.max_height = 0.1;
  auto s = check_adaptive(p);
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().message.find("min_layer_height (0.3 mm) is more than max_layer_height (0.1 mm)") != std::string::npos);
  p = AdaptiveParams{};
  p.quality = 1.5;
  REQUIRE_FALSE(check_adaptive(p).ok());
  CHECK(check_adaptive(p).error().message.find("adaptive_quality must be between 0") != std::string::npos);
  p.quality = std::nan("");
  CHECK_FALSE(check_adaptive(p).ok());
  p = AdaptiveParams{};
  p.min_height = 0;
  CHECK(check_adaptive(p).error().message.find("min_layer_height must be at least") != std::string::npos);
  p = AdaptiveParams{};
  p.max_height = std::numeric_limits<double>::infinity();
  CHECK_FALSE(check_adaptive(p).ok());
}

TEST_CASE("adaptive layers: the quality maps to the cusp, max_layer_height at 0 to min_layer_height at 1") {
  AdaptiveParams p{0.1, 0.3, 0};
  CHECK(p.cusp() == Approx(0.3));
  p.quality = 1;
  CHECK(p.cusp() == Approx(0.1));
  p.quality = 0.25;
  CHECK(p.cusp() == Approx(0.25));
}

TEST_CASE("adaptive layers: vertical walls get the thickest layers, a flat top ends a layer") {
  SurfaceSlopes s;
  s.add(box({10, 10, 10}));
  const AdaptiveParams p{0.07, 0.3, 0.5};
  CHECK(s.adaptive_height(5, p) == Approx(0.3));
  CHECK(s.max_slope_deg(5, 5.3) == Approx(0));
  // The top at z = 10 is 0.2 mm above 9.8: the layer ends there, not at 10.1.
  CHECK(s.adaptive_height(9.8, p) == Approx(0.2));
  CHECK(s.max_slope_deg(9.8, 10.1) == Approx(90));
  // Closer than min_layer_height: the layer cannot end on it.
  CHECK(s.adaptive_height(9.95, p) == Approx(0.3));
  // The bottom at z = 0 is below the first layer, not in it.
  CHECK(s.max_slope_deg(0, 0.3) == Approx(0));
  SurfaceSlopes none;
  CHECK(none.empty());
  CHECK(none.adaptive_height(1, p) == Approx(0.3));
  CHECK(none.max_slope_deg(0, 1) == 0);
}

TEST_CASE("adaptive layers: a 45° cone gets cusp / cos 45°, clamped to the bounds") {
  SurfaceSlopes s;
  const Mesh cone45 = cone(10, 0, 10, 256);  // sides at 45° (to 0.01° with 256 sides)
  s.add(cone45);
  AdaptiveParams p{0.05, 0.4, 0.5};  // cusp 0.225 mm
  CHECK(s.adaptive_height(3, p) == Approx(0.225 * std::sqrt(2.0)).epsilon(1e-3));
  CHECK(s.max_slope_deg(3, 3.4) == Approx(45).epsilon(1e-3));
  p.quality = 1;  // cusp 0.05: 0.0707 mm
  CHECK(s.adaptive_height(3, p) == Approx(0.05 * std::sqrt(2.0)).epsilon(1e-3));
  p.quality = 0;  // cusp 0.4: 0.57 mm, more than max_layer_height
  CHECK(s.adaptive_height(3, p) == Approx(0.4));
}

// A sphere of radius r standing on the bed (96 × 64 facets).
Mesh standing_sphere(double r) {
  Mesh m = sphere(r, 96, 64);
  m.transform(1, {0, 0, r});
  return m;
}

TEST_CASE("adaptive layers: on a sphere, thin layers at the top and bottom, thick ones at the equator, every cusp within bounds") {
  const double r = 10;
  const Mesh m = standing_sphere(r);
  SurfaceSlopes s;
  s.add(m);
  const AdaptiveParams p{0.07, 0.3, 0.5};
  const double cusp = p.cusp();
  auto layers = plan(s, 2 * r, p);
  // Fewer layers than at min_layer_height, more than at max.
  CHECK(layers.size() > static_cast<size_t>(2 * r / 0.3));
  CHECK(layers.size() < static_cast<size_t>(2 * r / 0.07));
  double equator = 0, pole = 1;
  for (const auto& [z, h] : layers) {
    if (std::abs(z - r) < 1) equator = std::max(equator, h);
    if (z > 2 * r - 0.5) pole = std::min(pole, h);
  }
  CHECK(equator == Approx(0.3));
  CHECK(pole < 0.2);
  // No facet crossing a layer makes a cusp above the allowed one, unless the layer is already
  // at min_layer_height.
  const auto faces = faces_of(m);
  int checked = 0;
  for (const auto& [z, h] : layers) {
    if (h <= p.min_height + 1e-9) continue;
    for (const Face& f : faces)
      if (f.zmax > z + 1e-6 && f.zmin < z + h - 1e-6 && f.zmax - f.zmin > 1e-6) {
        CHECK(h * f.nz <= cusp + 1e-9);
        ++checked;
      }
  }
  CHECK(checked > 1000);
  // Symmetric: the bottom half mirrors the top (within a layer).
  size_t below = 0;
  for (const auto& l : layers) below += l.first < r ? 1 : 0;
  CHECK(std::abs(static_cast<double>(below) - static_cast<double>(layers.size() - below)) <= 2);
  // The flattest surface above the equator's layer is steep, near the top it is almost flat.
  CHECK(s.max_slope_deg(r, r + 0.3) < 10);
  CHECK(s.max_slope_deg(2 * r - 0.3, 2 * r) > 80);
}

namespace {

// The side of a solid of revolution through the (r, z) points of `profile`, bottom to top.
Mesh revolved(const std::vector<std::pair<double, double>>& profile, int segments) {
  Mesh m;
  for (const auto& [r, z] : profile)
    for (int k = 0; k < segments; ++k) {
      const double a = 2 * std::numbers::pi * k / segments;
      m.vertices.push_back({r * std::cos(a), r * std::sin(a), z});
    }
  const auto n = static_cast<uint32_t>(segments);
  for (uint32_t i = 0; i + 1 < profile.size(); ++i)
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t a = i * n + k, b = i * n + (k + 1) % n, c = a + n, d = b + n;
      m.triangles.push_back({a, b, d});
      m.triangles.push_back({a, d, c});
    }
  return m;
}

// A 10 mm cylinder's wall (vertical: the thickest layers) under a 2 mm cone whose side is 11.3°
// from flat (layers of cusp / cos 11.3°): the unsmoothed plan jumps from 0.3 to 0.19 mm.
Mesh wall_then_roof() { return revolved({{10, 0}, {10, 10}, {0.01, 12}}, 128); }

// Whether no facet crossing a layer makes a cusp above the allowed one (unless the layer is
// already at min_height).
bool cusps_within(const Mesh& m, const std::vector<std::pair<double, double>>& layers, const AdaptiveParams& p) {
  const auto faces = faces_of(m);
  for (const auto& [z, h] : layers) {
    if (h <= p.min_height + 1e-9) continue;
    for (const Face& f : faces)
      if (f.zmax > z + 1e-6 && f.zmin < z + h - 1e-6 && f.zmax - f.zmin > 1e-6 && h * f.nz > p.cusp() + 1e-9)
        return false;
  }
  return true;
}

// Plans with the smoothing's cap, as load_plate does.
std::vector<std::pair<double, double>> plan_smooth(const SurfaceSlopes& s, double top, const AdaptiveParams& p) {
  const SmoothHeights smooth(s, p);
  std::vector<std::pair<double, double>> out;
  for (double z = 0; z < top - 1e-9;) {
    const double h = s.adaptive_height(z, p, smooth.cap(z));
    REQUIRE(h > 0);
    out.emplace_back(z, h);
    z += h;
  }
  return out;
}

double max_step(const std::vector<std::pair<double, double>>& layers, size_t skip_top) {
  double m = 0;
  for (size_t i = 1; i + skip_top < layers.size(); ++i) m = std::max(m, std::abs(layers[i].second - layers[i - 1].second));
  return m;
}

}  // namespace

TEST_CASE("adaptive smoothing: heights change by about (max − min) / smoothing a layer, never above the cusp height") {
  const Mesh m = wall_then_roof();
  SurfaceSlopes s;
  s.add(m);
  AdaptiveParams p{0.07, 0.3, 0.5};
  const double top = s.top();
  const auto raw = plan(s, top, p);
  CHECK(max_step(raw, 2) > 0.1);  // the jump from the wall to the roof
  for (int n : {3, 5, 10}) {
    CAPTURE(n);
    p.smoothing = n;
    const double d = (p.max_height - p.min_height) / n;
    const auto smooth = plan_smooth(s, top, p);
    // Up a layer by less than d, down by about √(h² − 2dh) below h (1.1 d at h = 0.3 mm; the
    // samples interpolated add a little);
    // the last two layers share the rest under the top.
    CHECK(max_step(smooth, 2) <= 1.25 * d + 1e-9);
    // Within the cusp and the bounds; below the top's last two layers, never thicker than the
    // unsmoothed planner at the same z; the wall's middle keeps the thickest layers.
    CHECK(cusps_within(m, smooth, p));
    double middle = 0;
    for (const auto& [z, h] : smooth) {
      if (z + h < top - 2 * p.max_height) CHECK(h <= s.adaptive_height(z, p) + 1e-12);
      CHECK(h >= p.min_height - 1e-12);
      CHECK(h <= p.max_height + 1e-12);
      if (std::abs(z - 5) < 0.5) middle = std::max(middle, h);
    }
    CHECK(middle == Approx(0.3));
    // Only the layers next to the change got thinner: a few more than unsmoothed.
    CHECK(smooth.size() >= raw.size());
    CHECK(smooth.size() <= raw.size() + 2 * static_cast<size_t>(n));
  }
  // No smoothing: the cap is no cap, the plan the planner's.
  p.smoothing = 0;
  const SmoothHeights none(s, p);
  CHECK(none.cap(5) > 1e9);
  const auto same = plan_smooth(s, top, p);
  REQUIRE(same.size() == raw.size());
  for (size_t i = 0; i < raw.size(); ++i) CHECK(same[i].second == raw[i].second);
  p.smoothing = -1;
  CHECK(check_adaptive(p).error().message.find("adaptive_smoothing must be 0") != std::string::npos);
}

TEST_CASE("adaptive smoothing: a sphere's layers ramp without jumps, every cusp within bounds") {
  const double r = 10;
  const Mesh m = standing_sphere(r);
  SurfaceSlopes s;
  s.add(m);
  AdaptiveParams p{0.07, 0.3, 0.5, 5};
  const auto layers = plan_smooth(s, 2 * r, p);
  CHECK(max_step(layers, 2) <= 1.25 * (p.max_height - p.min_height) / 5 + 1e-9);
  CHECK(cusps_within(m, layers, p));
}

TEST_CASE("adaptive smoothing: the layers under a flat top share the distance to it evenly") {
  SurfaceSlopes s;
  s.add(box({10, 10, 10}));
  AdaptiveParams p{0.07, 0.3, 0.5};
  // Unsmoothed: 33 layers of 0.3 mm, then 0.1 mm onto the top at 10 mm.
  const auto raw = plan(s, 10, p);
  REQUIRE(raw.size() == 34);
  CHECK(raw.back().second == Approx(0.1));
  p.smoothing = 5;
  const auto smooth = plan_smooth(s, 10, p);
  CHECK(smooth.back().first + smooth.back().second == Approx(10));
  // Within the last six layers (smoothing + 1) the height drops once, by less than 0.3 / 6 mm,
  // and stays; all of them at most 0.3 mm.
  CHECK(smooth.size() == 34);
  CHECK(max_step(smooth, 0) < 0.3 / 6);
  for (const auto& [z, h] : smooth) CHECK(h <= 0.3 + 1e-12);
}
