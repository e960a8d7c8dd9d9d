// End to end: the seam choices (random, sharpest_corner, point) and adaptive layer heights with
// layer.max_slope, checked on the G-code (issue 15).
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>

#include "apps/slice_command.h"
#include "gcode_reader.h"
#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "mesh_run.h"
#include "tests/support/fixtures.h"

using namespace tranche;

namespace {

using test::Sets;

Result<pipeline::SliceSummary> run(const test::TempDir& dir, const std::string& name, const geo::Mesh& mesh,
                                   const std::string& rules, const Sets& sets, std::vector<Warning>* warnings = nullptr) {
  test::MeshRun r = test::slice_mesh(dir, name, mesh, sets, rules);
  if (warnings) *warnings = r.warnings;
  return r.result;
}

test::Gcode slice(const test::TempDir& dir, const std::string& name, const geo::Mesh& mesh, const Sets& sets,
                  const std::string& rules = "") {
  auto r = run(dir, name, mesh, rules, sets);
  REQUIRE_MESSAGE(r.ok(), (r.ok() ? "" : r.error().to_string()));
  return test::read_gcode((dir / (name + ".gcode")).string());
}

// Where each layer's first outer perimeter starts (bed mm).
std::map<int, std::pair<double, double>> outer_starts(const test::Gcode& g) {
  std::map<int, std::pair<double, double>> out;
  for (const auto& m : g.moves)
    if (m.has_xy && m.de > 0 && m.type == "External perimeter" && !out.count(m.layer)) out[m.layer] = {m.x0, m.y0};
  return out;
}

// Layer heights from the ;Z: of each layer.
std::vector<double> heights(const test::Gcode& g) {
  std::vector<double> h;
  double z = 0;
  for (const auto& [layer, top] : g.layer_z) {
    h.push_back(top - z);
    z = top;
  }
  return h;
}

geo::Mesh ball(double r) {
  geo::Mesh m = geo::sphere(r, 64, 48);
  m.transform(1, {0, 0, r});
  return m;
}

}  // namespace

TEST_CASE("seams e2e: point puts every layer's seam at the corner nearest (seam_x, seam_y)") {
  test::TempDir dir("seam-point");
  // A 20 mm cube centred on the 200 mm bed: its front-right corner is at (110, 90).
  auto g = slice(dir, "point", geo::box({20, 20, 3}), {{"seam", "point"}, {"seam_x", "200"}, {"seam_y", "0"}});
  auto starts = outer_starts(g);
  REQUIRE(starts.size() == 15);
  for (const auto& [layer, p] : starts) {
    CHECK(std::abs(p.first - 110) < 0.5);
    CHECK(std::abs(p.second - 90) < 0.5);
  }
  // Toward the rear left: the other corner.
  auto h = slice(dir, "point2", geo::box({20, 20, 3}), {{"seam", "point"}, {"seam_x", "0"}, {"seam_y", "200"}});
  for (const auto& [layer, p] : outer_starts(h)) {
    CHECK(std::abs(p.first - 90) < 0.5);
    CHECK(std::abs(p.second - 110) < 0.5);
  }
}

TEST_CASE("seams e2e: random moves the seam from layer to layer, the same on every run") {
  test::TempDir dir("seam-random");
  const geo::Mesh cyl = geo::cylinder(10, 4, 96);
  auto a = slice(dir, "a", cyl, {{"seam", "random"}});
  auto b = slice(dir, "b", cyl, {{"seam", "random"}});
  CHECK(a.moves.size() == b.moves.size());
  CHECK(outer_starts(a) == outer_starts(b));
  std::set<std::pair<long, long>> seen;
  for (const auto& [layer, p] : outer_starts(a)) seen.insert({std::lround(p.first * 10), std::lround(p.second * 10)});
  CHECK(seen.size() >= 12);  // of 20 layers
  // Aligned stays in one place.
  auto c = slice(dir, "c", cyl, {});
  std::set<std::pair<long, long>> aligned;
  for (const auto& [layer, p] : outer_starts(c)) aligned.insert({std::lround(p.first), std::lround(p.second)});
  CHECK(aligned.size() <= 2);
}

TEST_CASE("seams e2e: sharpest_corner hides the seam in an L's inner corner, where aligned goes to the rear") {
  test::TempDir dir("seam-corner");
  geo::Mesh l = geo::box({20, 10, 2});
  geo::append(l, geo::box({10, 20, 2}));  // an L: the inner corner at (10, 10), (100, 100) on the bed
  auto g = slice(dir, "corner", l, {{"seam", "sharpest_corner"}});
  auto starts = outer_starts(g);
  REQUIRE(starts.size() == 10);
  for (const auto& [layer, p] : starts) CHECK(std::hypot(p.first - 100, p.second - 100) < 0.6);
  auto a = slice(dir, "aligned", l, {});
  for (const auto& [layer, p] : outer_starts(a)) CHECK(p.second > 109);
}

TEST_CASE("adaptive layers e2e: a sphere gets thick layers at its equator, thin ones at its top, fewer than at 0.2 mm") {
  test::TempDir dir("adaptive");
  const geo::Mesh m = ball(10);
  auto g = slice(dir, "ball", m, {{"adaptive_layers", "true"}});
  auto h = heights(g);
  REQUIRE(h.size() > 20);
  CHECK(h.size() < 100);  // 20 mm at 0.2 mm: 100 layers
  CHECK(h.size() > 20 / 0.3);
  CHECK(h.front() == doctest::Approx(0.2));  // first_layer_height
  double equator = 0, top = 1;
  for (size_t i = 1; i + 1 < h.size(); ++i) {
    CHECK(h[i] >= 0.07 - 1e-6);
    CHECK(h[i] <= 0.3 + 1e-6);
    const double z = g.layer_z.at(static_cast<int>(i));
    if (std::abs(z - 10) < 1) equator = std::max(equator, h[i]);
    if (z > 19) top = std::min(top, h[i]);
  }
  CHECK(equator == doctest::Approx(0.3));
  CHECK(top < 0.2);
  // Finer quality: more layers.
  auto fine = slice(dir, "fine", m, {{"adaptive_layers", "true"}, {"adaptive_quality", "0.9"}});
  CHECK(fine.layer_z.size() > g.layer_z.size());
  CHECK(fine.layer_z.rbegin()->second == doctest::Approx(20));
}

// A 10 mm cylinder (vertical: 0.3 mm layers) under a 2 mm cone 11° from flat (0.19 mm layers):
// a bottom disc, the wall and the cone up to its apex, one closed shell.
geo::Mesh wall_then_roof() {
  const int n = 96;
  geo::Mesh m;
  m.vertices.push_back({0, 0, 0});
  m.vertices.push_back({0, 0, 12});
  for (double z : {0.0, 10.0})
    for (int k = 0; k < n; ++k) {
      const double a = 2 * M_PI * k / n;
      m.vertices.push_back({10 * std::cos(a), 10 * std::sin(a), z});
    }
  for (uint32_t k = 0; k < static_cast<uint32_t>(n); ++k) {
    const uint32_t k1 = (k + 1) % n, b0 = 2 + k, b1 = 2 + k1, t0 = 2 + n + k, t1 = 2 + n + k1;
    m.triangles.push_back({0, b1, b0});  // the bottom, seen from below
    m.triangles.push_back({b0, b1, t1});
    m.triangles.push_back({b0, t1, t0});
    m.triangles.push_back({t0, t1, 1});  // the cone up to the apex
  }
  return m;
}

// The largest change of height between neighbouring layers, the first and the last two left out.
double max_step(const std::vector<double>& h) {
  double m = 0;
  for (size_t i = 2; i + 2 < h.size(); ++i) m = std::max(m, std::abs(h[i] - h[i - 1]));
  return m;
}

TEST_CASE("adaptive layers e2e: adaptive_smoothing ramps the height down before a flatter surface") {
  test::TempDir dir("adaptive-smooth");
  const geo::Mesh m = wall_then_roof();
  auto raw = heights(slice(dir, "raw", m, {{"adaptive_layers", "true"}, {"adaptive_smoothing", "0"}}));
  auto smooth = heights(slice(dir, "smooth", m, {{"adaptive_layers", "true"}}));  // 5 layers by default
  CHECK(max_step(raw) > 0.08);
  CHECK(max_step(smooth) <= 1.25 * (0.3 - 0.07) / 5);
  CHECK(smooth.size() >= raw.size());
  CHECK(smooth.size() <= raw.size() + 5);
  for (size_t i = 1; i < smooth.size(); ++i) {
    CHECK(smooth[i] >= 0.07 - 1e-6);
    CHECK(smooth[i] <= 0.3 + 1e-6);
  }
  // A negative smoothing is out of range, refused with the property's name.
  auto bad = run(dir, "bad", m, "", {{"adaptive_layers", "true"}, {"adaptive_smoothing", "-1"}});
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().to_string().find("adaptive_smoothing") != std::string::npos);
}

TEST_CASE("adaptive layers e2e: a layer_height rule overrides the planner on the layers it matches") {
  test::TempDir dir("adaptive-rule");
  auto g = slice(dir, "ball", ball(10), {{"adaptive_layers", "true"}},
                 "rule \"fine top\" when layer.z_bottom >= 15 mm { layer_height = 0.1 mm }\n");
  auto h = heights(g);
  int fine = 0, other = 0;
  double z = 0;
  for (size_t i = 0; i + 1 < h.size(); ++i) {
    if (z >= 15 - 1e-9) {
      CHECK(h[i] == doctest::Approx(0.1));
      ++fine;
    } else if (std::abs(h[i] - 0.1) > 1e-6) {
      ++other;
    }
    z += h[i];
  }
  CHECK(fine >= 45);
  CHECK(other > 10);  // below 15 mm the planner's heights
}

TEST_CASE("adaptive layers e2e: layer.max_slope lets a rule thin the layers where the surface flattens") {
  test::TempDir dir("max-slope");
  auto g = slice(dir, "ball", ball(10), {}, "rule \"flat\" when layer.max_slope > 60 deg { layer_height = 0.1 mm }\n");
  auto h = heights(g);
  double z = 0;
  int thin = 0, thick = 0;
  for (size_t i = 0; i + 1 < h.size(); ++i) {
    if (i > 0 && std::abs(z - 10) < 3) CHECK(h[i] == doctest::Approx(0.2));  // walls within 30° of vertical
    if (z > 19.5) CHECK(h[i] == doctest::Approx(0.1));
    (std::abs(h[i] - 0.1) < 1e-6 ? thin : thick) += 1;
    z += h[i];
  }
  CHECK(thin > 10);
  CHECK(thick > 10);
}

TEST_CASE("adaptive layers e2e: contradictory bounds are refused with a message") {
  test::TempDir dir("adaptive-bad");
  auto r = run(dir, "bad", ball(5), "",
               {{"adaptive_layers", "true"}, {"min_layer_height", "0.3"}, {"max_layer_height", "0.1"}});
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().to_string().find("min_layer_height (0.3 mm) is more than max_layer_height (0.1 mm)") !=
        std::string::npos);
  // A quality out of 0–1 computed by a rule (a constant one is a check-time error, E0212).
  auto q = run(dir, "badq", ball(5), "rule \"q\" { adaptive_quality = print.height / 5 mm }\n", {{"adaptive_layers", "true"}});
  REQUIRE_FALSE(q.ok());
  CHECK(q.error().to_string().find("`adaptive_quality` was given 200%, outside its physical range") != std::string::npos);
  // Off, the same bounds are not looked at.
  CHECK(run(dir, "off", ball(5), "", {{"min_layer_height", "0.3"}, {"max_layer_height", "0.1"}}).ok());
}

TEST_CASE("adaptive layers e2e: --set layer_height decides every layer, and a warning says the planner is unused") {
  test::TempDir dir("adaptive-overridden");
  std::vector<Warning> w;
  auto r = run(dir, "all", ball(5), "", {{"adaptive_layers", "true"}, {"layer_height", "0.2"}}, &w);
  REQUIRE(r.ok());
  bool warned = false;
  for (const auto& x : w) warned = warned || (x.code == "adaptive-overridden" && x.message.find("drop --set layer_height") != std::string::npos);
  CHECK(warned);
  CHECK(test::read_gcode((dir / "all.gcode").string()).layer_z.size() == 50);
  // A rule for some layers only: no warning.
  w.clear();
  REQUIRE(run(dir, "some", ball(5), "rule \"top\" when layer.z_bottom > 8 mm { layer_height = 0.1 mm }\n",
              {{"adaptive_layers", "true"}}, &w)
              .ok());
  for (const auto& x : w) CHECK(x.code != "adaptive-overridden");
}
