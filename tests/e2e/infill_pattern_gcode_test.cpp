// End to end: infill_pattern on the G-code of a 20 mm cube, set by --set and by a rule: each
// pattern's sparse infill stays inside the walls, lays about as much plastic as the zig-zag at the
// same density (honeycomb 1.27 × as much, as PrusaSlicer's; lightning far less), keeps the solid layers' zig-zags, and 0 % / 100 % behave
// as they do for the zig-zag.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <string>

#include "apps/slice_command.h"
#include "gcode_reader.h"
#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "mesh_run.h"
#include "tests/support/fixtures.h"

using namespace tranche;

namespace {

using Run = test::MeshRun;

Run run(const test::TempDir& dir, const std::string& name, const geo::Mesh& mesh, const test::Sets& sets,
        const std::string& rules = "") {
  return test::slice_mesh(dir, name, mesh, sets, rules);
}

bool extrudes(const test::Move& m) { return m.has_xy && m.de > 0; }

// Filament (mm) by ;TYPE:.
std::map<std::string, double> filament_by_type(const test::Gcode& g) {
  std::map<std::string, double> out;
  for (const auto& m : g.moves)
    if (extrudes(m)) out[m.type] += m.de;
  return out;
}

// Non-extruding moves in the XY plane between two infill moves of one layer.
int infill_travels(const test::Gcode& g) {
  int n = 0;
  bool in_infill = false;
  for (const auto& m : g.moves) {
    if (extrudes(m)) {
      in_infill = m.type == "Internal infill";
      continue;
    }
    if (in_infill && m.has_xy && !m.has_e) ++n;
  }
  return n;
}

const char* kPatterns[] = {"grid", "triangles", "cubic", "gyroid", "honeycomb", "concentric", "lightning"};

}  // namespace

TEST_CASE("infill_pattern: every pattern slices a cube, its infill inside the walls") {
  test::TempDir dir("infill-patterns");
  const geo::Mesh cube = geo::box({20, 20, 20}, {0, 0, 0});  // centred on the bed: x, y in [90, 110]
  Run zig = run(dir, "zigzag", cube, {});
  REQUIRE(zig.result.ok());
  const double zig_infill = filament_by_type(zig.g)["Internal infill"];
  REQUIRE(zig_infill > 0);
  for (const char* p : kPatterns) {
    CAPTURE(p);
    Run r = run(dir, p, cube, {{"infill_pattern", p}});
    REQUIRE_MESSAGE(r.result.ok(), (r.result.ok() ? "" : r.result.error().to_string()));
    CHECK(r.g.contains(";TYPE:Internal infill\n"));
    CHECK(r.g.contains(";TYPE:Solid infill\n"));
    auto by_type = filament_by_type(r.g);
    // Walls and skins do not depend on the pattern.
    // (E is absolute, rounded to 5 decimals per move: sums differ in the last digits.)
    CHECK(by_type["External perimeter"] == doctest::Approx(filament_by_type(zig.g)["External perimeter"]).epsilon(1e-4));
    CHECK(by_type["Top solid infill"] == doctest::Approx(filament_by_type(zig.g)["Top solid infill"]).epsilon(1e-4));
    const double infill = by_type["Internal infill"];
    if (std::string(p) == "lightning") {
      // Only the trees under the top: at 20 % on a 20 mm cube, less than half the zig-zag's.
      CHECK(infill > 0);
      CHECK(infill < 0.5 * zig_infill);
    } else {
      // The same density: within 20 % of the zig-zag's plastic (links and clipping differ);
      // honeycomb's hexagons at 20 % are PrusaSlicer's, their doubled sides 0.253 / 0.2 of that.
      const double expect = std::string(p) == "honeycomb" ? 3.8 / 3 * zig_infill : zig_infill;
      CHECK(infill > 0.8 * expect);
      CHECK(infill < 1.2 * expect);
    }
    // Every infill bead lies inside the innermost wall: 2 walls of 0.45 mm from x, y = 90 / 110.
    for (const auto& m : r.g.moves) {
      if (!extrudes(m) || m.type != "Internal infill") continue;
      CHECK(m.x > 90.6);
      CHECK(m.x < 109.4);
      CHECK(m.y > 90.6);
      CHECK(m.y < 109.4);
    }
    // Few pieces: fewer travels between infill moves than twice the sparse layers' count times
    // the pattern's line sets (each layer's pattern is a handful of linked paths).
    CHECK(infill_travels(r.g) < 8 * static_cast<int>(r.g.layer_z.size()));
  }
}

TEST_CASE("infill_pattern: lightning's trees hold up the top and shrink away below it") {
  test::TempDir dir("infill-patterns-lightning");
  const geo::Mesh cube = geo::box({20, 20, 20}, {0, 0, 0});  // 100 layers; 97-99 are the top's
  Run r = run(dir, "lightning", cube, {{"infill_pattern", "lightning"}});
  REQUIRE(r.result.ok());
  std::map<int, double> per_layer;  // sparse infill's length (mm) per layer
  for (const auto& m : r.g.moves) {
    if (!extrudes(m) || m.type != "Internal infill") continue;
    const double l = std::hypot(m.x - m.x0, m.y - m.y0);
    CHECK(l > 0);  // no zero-length extrusion
    CHECK(std::isfinite(m.x));
    CHECK(std::isfinite(m.y));
    per_layer[m.layer] += l;
  }
  auto at = [&](int layer) { return per_layer.count(layer) ? per_layer[layer] : 0.0; };
  // Under the top (layer 96): branches over all of the 18 mm square, every point of it within
  // width / density (2.25 mm) of a node: more than 18² / 4.5 = 72 mm of them, about a grid's
  // 18² · 0.2 / 0.42 = 154 mm. Then pruned 0.2 mm a layer from their tips: less and less, and
  // nothing left 14 mm down (no branch is 12 mm long).
  CHECK(at(96) > 72);
  CHECK(at(96) < 185);
  CHECK(at(80) < 0.7 * at(96));
  CHECK(at(60) < 0.3 * at(96));
  for (int i = 0; i < 30; ++i) CHECK(at(i) == 0);
}

TEST_CASE("infill_pattern: lightning under a small top far above the base is a thin tree") {
  // A 40 mm square base 4 mm thick with an 8 mm square column on it up to 20 mm, centred on the
  // bed: the column's top (layers 97-99) is the small top 16 mm above the base's.
  test::TempDir dir("infill-patterns-lightning-column");
  geo::Mesh part = geo::box({40, 40, 4}, {0, 0, 0});
  geo::append(part, geo::box({8, 8, 17}, {16, 16, 3}));
  Run light = run(dir, "lightning", part, {{"infill_pattern", "lightning"}});
  Run grid = run(dir, "grid", part, {{"infill_pattern", "grid"}});
  REQUIRE(light.result.ok());
  REQUIRE(grid.result.ok());
  auto column = [](const test::Gcode& g, int from, int to) {  // infill (mm) in layers [from, to]
    double l = 0;
    for (const auto& m : g.moves)
      if (extrudes(m) && m.type == "Internal infill" && m.layer >= from && m.layer <= to)
        l += std::hypot(m.x - m.x0, m.y - m.y0);
    return l;
  };
  // Under the column's top: branches over its 7 mm of sparse area, every point within 2.25 mm
  // of a node (at least 7² / 4.5 = 11 mm of them).
  CHECK(column(light.g, 96, 96) > 11);
  // The column's layers (z 5-19 mm) all together: far less than the grid's (6 % here).
  CHECK(column(light.g, 25, 95) < 0.15 * column(grid.g, 25, 95));
  // The base's top needs the whole base held up just under it (layers 17-19 are its top's).
  CHECK(column(light.g, 16, 16) > 0.5 * column(grid.g, 16, 16));
  // Every lightning bead inside the column's walls above the base.
  for (const auto& m : light.g.moves)
    if (extrudes(m) && m.type == "Internal infill" && m.layer >= 25) {
      CHECK(std::abs(m.x - 100) < 4);
      CHECK(std::abs(m.y - 100) < 4);
    }
}

TEST_CASE("infill_pattern: cubic and gyroid change from layer to layer, grid stands on itself") {
  test::TempDir dir("infill-patterns-z");
  const geo::Mesh cube = geo::box({20, 20, 10}, {0, 0, 0});
  auto layer_infill = [&](const std::string& p, int layer) {
    Run r = run(dir, p, cube, {{"infill_pattern", p}});
    REQUIRE(r.result.ok());
    std::vector<std::pair<double, double>> pts;
    for (const auto& m : r.g.moves)
      if (extrudes(m) && m.type == "Internal infill" && m.layer == layer) pts.push_back({m.x, m.y});
    return pts;
  };
  for (const char* p : {"cubic", "gyroid"}) {
    CAPTURE(p);
    auto a = layer_infill(p, 10), b = layer_infill(p, 12);  // two even layers: same fill_angle
    REQUIRE(!a.empty());
    CHECK(a != b);
  }
  auto a = layer_infill("grid", 10), b = layer_infill("grid", 11);
  REQUIRE(!a.empty());
  // The odd layer's angle is 135°, the even one's 45°: the grid's two sets are the same lines.
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  int common = 0;
  for (const auto& q : a)
    if (std::binary_search(b.begin(), b.end(), q)) ++common;
  CHECK(common * 2 > static_cast<int>(a.size()));
}

TEST_CASE("infill_pattern: density 0 prints no infill, density 1 solid zig-zags, for every pattern") {
  test::TempDir dir("infill-patterns-density");
  const geo::Mesh cube = geo::box({20, 20, 10}, {0, 0, 0});
  Run solid_zig = run(dir, "solid-zigzag", cube, {{"infill_density", "1"}});
  REQUIRE(solid_zig.result.ok());
  for (const char* p : kPatterns) {
    CAPTURE(p);
    Run none = run(dir, std::string("none-") + p, cube, {{"infill_pattern", p}, {"infill_density", "0"}});
    REQUIRE(none.result.ok());
    CHECK_FALSE(none.g.contains(";TYPE:Internal infill\n"));
    Run solid = run(dir, std::string("solid-") + p, cube, {{"infill_pattern", p}, {"infill_density", "1"}});
    REQUIRE(solid.result.ok());
    CHECK_FALSE(solid.g.contains(";TYPE:Internal infill\n"));
    // Exactly the zig-zag's solid fill: the same G-code after the header (which lists the --sets).
    auto body = [](const test::Gcode& g) { return g.text.substr(g.text.find(";LAYER:0")); };
    CHECK(body(solid.g) == body(solid_zig.g));
  }
}

TEST_CASE("infill_pattern: a rule picks the pattern per island (by height)") {
  test::TempDir dir("infill-patterns-rule");
  const geo::Mesh cube = geo::box({20, 20, 10}, {0, 0, 0});
  Run all_gyroid = run(dir, "gyroid", cube, {{"infill_pattern", "gyroid"}});
  Run zig = run(dir, "zigzag", cube, {});
  Run mixed = run(dir, "mixed", cube, {}, "rule \"gyroid above 5 mm\" when layer.z_bottom >= 5 mm { infill_pattern = gyroid }\n");
  REQUIRE(mixed.result.ok());
  REQUIRE(all_gyroid.result.ok());
  auto layer_text = [](const test::Gcode& g, int layer) {
    std::string s;
    for (const auto& m : g.moves)
      if (m.layer == layer && extrudes(m)) s += std::to_string(m.x) + "," + std::to_string(m.y) + ";";
    return s;
  };
  CHECK(layer_text(mixed.g, 10) == layer_text(zig.g, 10));         // z 2.0 mm: zig-zag
  CHECK(layer_text(mixed.g, 30) == layer_text(all_gyroid.g, 30));  // z 6.0 mm: gyroid
  CHECK(layer_text(mixed.g, 30) != layer_text(zig.g, 30));
}

TEST_CASE("infill_pattern: an unknown pattern is refused with the list of patterns") {
  test::TempDir dir("infill-patterns-bad");
  const geo::Mesh cube = geo::box({20, 20, 10}, {0, 0, 0});
  Run r = run(dir, "bad-set", cube, {{"infill_pattern", "stars"}});
  REQUIRE_FALSE(r.result.ok());
  const std::string msg = r.result.error().to_string();
  CHECK(msg.find("stars") != std::string::npos);
  CHECK(msg.find("gyroid") != std::string::npos);
  CHECK(msg.find("lightning") != std::string::npos);
  Run q = run(dir, "bad-rule", cube, {}, "rule \"stars\" { infill_pattern = stars }\n");
  REQUIRE_FALSE(q.result.ok());
  const std::string qm = q.result.error().to_string();
  CHECK(qm.find("stars") != std::string::npos);
  CHECK(qm.find("honeycomb") != std::string::npos);
}
