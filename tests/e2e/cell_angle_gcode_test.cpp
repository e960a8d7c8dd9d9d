// fill_angle per cell, end to end: a rule reading `cell.*` gives a cell its own angle, and the
// G-code's fill lines of that cell run at it; the rest of the island keeps the island's angle.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "apps/slice_command.h"
#include "gcode_reader.h"
#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "mesh_run.h"
#include "tests/support/fixtures.h"

using namespace tranche;

namespace {

test::Gcode slice(const test::TempDir& dir, const std::string& name, const geo::Mesh& mesh, const std::string& rules,
                  const test::Sets& sets = {}) {
  test::MeshRun r = test::slice_mesh(dir, name, mesh, sets, rules);
  REQUIRE_MESSAGE(r.result.ok(), (r.result.ok() ? "" : r.result.error().to_string()));
  return r.g;
}

// The directions (undirected, degrees in [0, 180)) of the fill lines of `type` on `layer`:
// extrusions longer than 4.5 mm (connectors along the border are shorter: 4.1 mm at most, for lines
// at 60° to a side).
std::vector<double> fill_lines(const test::Gcode& g, int layer, const std::string& type, double* length = nullptr) {
  std::vector<double> out;
  if (length) *length = 0;
  for (const auto& m : g.moves) {
    if (m.layer != layer || m.type != type || !m.has_xy || m.de <= 0) continue;
    const double len = std::hypot(m.x - m.x0, m.y - m.y0);
    if (length) *length += len;
    if (len < 4.5) continue;
    out.push_back(std::fmod(std::atan2(m.y - m.y0, m.x - m.x0) * 180 / std::numbers::pi + 360, 180));
  }
  return out;
}

bool near(double a, double b) { return std::abs(a - b) < 0.5 || std::abs(std::abs(a - b) - 180) < 0.5; }
size_t count_at(const std::vector<double>& v, double a) {
  return static_cast<size_t>(std::count_if(v.begin(), v.end(), [&](double x) { return near(x, a); }));
}

}  // namespace

TEST_CASE("fill_angle per cell: sparse cells along x, solid cells at the island's angle") {
  test::TempDir dir("cell-angle");
  const auto box = geo::box({20, 20, 4});
  auto g = slice(dir, "cells", box, "rule \"sparse along x\" when not cell.solid { fill_angle = 0 deg }\n");
  auto sparse = fill_lines(g, 10, "Internal infill");
  REQUIRE(sparse.size() > 3);
  CHECK(count_at(sparse, 0) == sparse.size());
  auto solid = fill_lines(g, 1, "Solid infill");  // bottom layers: solid cells, odd layer: 135°
  REQUIRE(solid.size() > 3);
  CHECK(count_at(solid, 135) == solid.size());

  // The cell filled again covers what the island filled at that angle covers.
  auto island = slice(dir, "island", box, "rule \"along x\" { fill_angle = 0 deg }\n");
  double per_cell = 0, per_island = 0;
  fill_lines(g, 10, "Internal infill", &per_cell);
  fill_lines(island, 10, "Internal infill", &per_island);
  CHECK(per_cell == doctest::Approx(per_island).epsilon(0.05));
  // ... in as many whole lines: the cell's shape has no slits that would cut them.
  const auto island_lines = fill_lines(island, 10, "Internal infill");
  CHECK(sparse.size() + 1 >= island_lines.size());
  CHECK(sparse.size() <= island_lines.size() + 1);

  // Without a cell rule the island's angle stands: 45° on even layers.
  auto plain = slice(dir, "plain", box, "");
  auto lines = fill_lines(plain, 10, "Internal infill");
  REQUIRE(!lines.empty());
  CHECK(count_at(lines, 45) == lines.size());
}

TEST_CASE("fill_angle per cell: one cell of an island turned, its others at the island's angle") {
  test::TempDir dir("cell-angle-one");
  // A plate with four holes: at 45° its sparse region is cut into several cells.
  const auto plate = geo::plate_with_holes(30, 30, 4, 2, 2, 4, 24);
  auto g = slice(dir, "one", plate, "rule \"first cell along x\" when cell.index == 0 { fill_angle = 0 deg }\n");
  auto lines = fill_lines(g, 10, "Internal infill");
  REQUIRE(lines.size() > 6);
  CHECK(count_at(lines, 0) > 0);
  CHECK(count_at(lines, 45) > 0);
  CHECK(count_at(lines, 0) + count_at(lines, 45) == lines.size());
}

TEST_CASE("fill_angle per cell: the last matching rule still wins, per island or per cell") {
  test::TempDir dir("cell-angle-order");
  auto g = slice(dir, "order", geo::box({20, 20, 4}),
                 "rule \"sparse along x\" when not cell.solid { fill_angle = 0 deg }\n"
                 "rule \"later, per island\" { fill_angle = 90 deg }\n");
  auto lines = fill_lines(g, 10, "Internal infill");
  REQUIRE(!lines.empty());
  CHECK(count_at(lines, 90) == lines.size());
  // A plain --set is above every rule, per cell too.
  auto set = slice(dir, "set", geo::box({20, 20, 4}), "rule \"sparse along x\" when not cell.solid { fill_angle = 0 deg }\n",
                   {{"fill_angle", "60"}});
  lines = fill_lines(set, 10, "Internal infill");
  REQUIRE(!lines.empty());
  CHECK(count_at(lines, 60) == lines.size());
}

TEST_CASE("fill_angle per cell: every sparse cell at one angle fills as the island at that angle") {
  // The cells given one angle are filled together, to the region's border: no cut, no gap. The
  // same lines and travels as when the island is given the angle, up to a connector's point at
  // the border (the cells' union is the region up to its sharpest corners).
  test::TempDir dir("cell-angle-all");
  const auto plate = geo::plate_with_holes(30, 30, 4, 2, 2, 4, 24);
  auto cells = slice(dir, "cells", plate, "rule \"sparse along x\" when not cell.solid { fill_angle = 0 deg }\n");
  auto island = slice(dir, "island", plate, "rule \"along x\" { fill_angle = 0 deg }\n");
  auto travels = [](const test::Gcode& g) {
    return std::count_if(g.moves.begin(), g.moves.end(), [](const test::Move& m) {
      return m.layer == 10 && m.type == "Internal infill" && m.has_xy && m.de <= 0;
    });
  };
  double a = 0, b = 0;
  const auto lines_a = fill_lines(cells, 10, "Internal infill", &a);
  const auto lines_b = fill_lines(island, 10, "Internal infill", &b);
  REQUIRE(lines_b.size() > 10);
  CHECK(lines_a.size() == lines_b.size());
  CHECK(count_at(lines_a, 0) == lines_a.size());
  CHECK(a == doctest::Approx(b).epsilon(0.005));
  CHECK(travels(cells) == travels(island));
}
