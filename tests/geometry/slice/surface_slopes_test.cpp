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

TEST_CASE("adaptive layers: on a sphere, thin layers at the top and bottom, thick ones at the equator, every cusp within bounds") {
  const double r = 10;
  Mesh m = sphere(r, 96, 64);
  m.transform(1, {0, 0, r});
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
