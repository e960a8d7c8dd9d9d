// End to end: overhang_walls = bridge (the default) on the G-code of a slab over a gap and of a
// shelf hanging out from a column: on the first layer over air the part over air is bridge
// infill whose lines start on the layer below, and no wall runs in the air; with
// overhang_walls = loops the walls run round in the air there, as before.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "geometry/mesh/primitives.h"
#include "mesh_run.h"

using namespace tranche;

namespace {

constexpr double kBead = 0.45;
const test::Sets kSets = {{"min_layer_time", "0"}, {"layer_height", "0.2"}, {"first_layer_height", "0.2"},
                          {"width", "0.45"}, {"perimeters", "2"}};

bool extrudes(const test::Move& m) { return m.has_xy && m.de > 0; }
bool is_wall(const test::Move& m) { return m.type == "External perimeter" || m.type == "Perimeter"; }

// The G-code's layer whose top is at z (mm).
int layer_at(const test::Gcode& g, double z) {
  for (const auto& [n, lz] : g.layer_z)
    if (std::abs(lz - z) < 1e-3) return n;
  FAIL("no layer at z " << z);
  return -1;
}

// Bed x minus model x: the first layer's leftmost bead edge is the model's leftmost x there.
double shift_x(const test::Gcode& g, double model_min_x) {
  double lo = 1e9;
  for (const auto& m : g.moves)
    if (extrudes(m) && m.layer == 0) lo = std::min({lo, m.x, m.x0});
  return lo - 0.5 * kBead - model_min_x;
}

struct LayerMoves {
  std::vector<test::Move> bridges, walls;  // bridge lines longer than `long_mm`; wall moves
};

LayerMoves moves_on(const test::Gcode& g, int layer, double long_mm) {
  LayerMoves out;
  for (const auto& m : g.moves) {
    if (!extrudes(m) || m.layer != layer) continue;
    if (m.type == "Bridge infill" && std::hypot(m.x - m.x0, m.y - m.y0) > long_mm) out.bridges.push_back(m);
    if (is_wall(m)) out.walls.push_back(m);
  }
  return out;
}

// Pillars x 0..5 and 17..22 (y 0..10, 6 mm high) under a slab 22 × 10 × 2 mm: a 12 mm gap.
geo::Mesh gap_slab() {
  geo::Mesh m = geo::box({5, 10, 6}, {0, 0, 0});
  geo::append(m, geo::box({5, 10, 6}, {17, 0, 0}));
  geo::append(m, geo::box({22, 10, 2}, {0, 0, 6}));
  return m;
}

// A column x 10..20 (y 0..10, 8 mm high) under a plate 30 × 10 × 2 mm: 10 mm of shelf on either
// side (bench/overhang_models.py's shelf).
geo::Mesh shelf() {
  geo::Mesh m = geo::box({10, 10, 8}, {10, 0, 0});
  geo::append(m, geo::box({30, 10, 2}, {0, 0, 8}));
  return m;
}

// Whether some wall piece's middle lies over the gap slab's gap (x 8..14 from the part's left, `sx`).
bool walls_cross_gap(const LayerMoves& lm, double sx) {
  return std::any_of(lm.walls.begin(), lm.walls.end(), [&](const test::Move& m) {
    const double mid = 0.5 * (m.x + m.x0) - sx;
    return mid > 8 && mid < 14;
  });
}

}  // namespace

TEST_CASE("overhang walls: a slab over a gap is bridged from pillar to pillar, no wall in the air") {
  test::TempDir dir("overhang-walls-gap");
  auto r = test::slice_mesh(dir, "gap", gap_slab(), kSets);
  REQUIRE_MESSAGE(r.result.ok(), (r.result.ok() ? "" : r.result.error().to_string()));
  const double sx = shift_x(r.g, 0);
  const LayerMoves lm = moves_on(r.g, layer_at(r.g, 6.2), 5);
  REQUIRE(lm.bridges.size() > 15);  // about 10 mm / 0.45 mm of lines
  auto on_pillar = [&](double x) {
    const double mx = x - sx;
    return (mx >= 0 && mx <= 5) || (mx >= 17 && mx <= 22);
  };
  for (const auto& m : lm.bridges) {
    CHECK(std::abs(m.y - m.y0) < 0.05 * std::abs(m.x - m.x0));  // across the gap
    CHECK(on_pillar(m.x0));                                       // both ends on the layer below
    CHECK(on_pillar(m.x));
    CHECK(m.f == doctest::Approx(1500));  // the bridges' 25 mm/s (stdlib/defaults.rules)
  }
  // Walls only where they rest on the pillars (their centre within half a bead of them).
  for (const auto& m : lm.walls) {
    const double mid = 0.5 * (m.x + m.x0) - sx;
    CHECK_FALSE((mid > 5 + 0.5 * kBead + 0.05 && mid < 17 - 0.5 * kBead - 0.05));
  }
  // The layer above, on the bridge, has its walls all round again.
  const LayerMoves above = moves_on(r.g, layer_at(r.g, 6.4), 5);
  CHECK(walls_cross_gap(above, sx));
}

TEST_CASE("overhang walls: with overhang_walls = loops the walls cross the gap in the air") {
  test::TempDir dir("overhang-walls-loops");
  auto sets = kSets;
  sets.push_back({"overhang_walls", "loops"});
  auto r = test::slice_mesh(dir, "gap", gap_slab(), sets);
  REQUIRE_MESSAGE(r.result.ok(), (r.result.ok() ? "" : r.result.error().to_string()));
  const double sx = shift_x(r.g, 0);
  const LayerMoves lm = moves_on(r.g, layer_at(r.g, 6.2), 5);
  CHECK(walls_cross_gap(lm, sx));
}

TEST_CASE("overhang walls: a shelf's lines run out from the column, each starting on it") {
  test::TempDir dir("overhang-walls-shelf");
  auto r = test::slice_mesh(dir, "shelf", shelf(), kSets);
  REQUIRE_MESSAGE(r.result.ok(), (r.result.ok() ? "" : r.result.error().to_string()));
  const double sx = shift_x(r.g, 10);
  const LayerMoves lm = moves_on(r.g, layer_at(r.g, 8.2), 5);
  REQUIRE(lm.bridges.size() > 30);  // two shelves, about 10 mm / 0.45 mm of lines each
  for (const auto& m : lm.bridges) {
    CHECK(std::abs(m.y - m.y0) < 0.05 * std::abs(m.x - m.x0));  // out from the column's edge
    const double a = m.x0 - sx, b = m.x - sx;
    CHECK(((a >= 10 && a <= 20) || (b >= 10 && b <= 20)));  // one end on the column
  }
  for (const auto& m : lm.walls) {
    const double mid = 0.5 * (m.x + m.x0) - sx;
    CHECK(mid >= 10 - 0.5 * kBead - 0.05);
    CHECK(mid <= 20 + 0.5 * kBead + 0.05);
  }
}
