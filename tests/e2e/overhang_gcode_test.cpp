// End to end: the overhang speed steps of stdlib/defaults.rules on the G-code of a straight wall
// beside a leaning one, and the ways a user changes them (a param, --set, a rule of their own).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "geometry/mesh/primitives.h"
#include "mesh_run.h"

using namespace tranche;

namespace {

constexpr double kHeight = 8;

// A 6 × 20 mm wall `kHeight` high at y = y0, its top moved by `lean_deg` from vertical toward +x.
geo::Mesh wall(double y0, double lean_deg) {
  geo::Mesh m = geo::box({6, 20, kHeight}, {0, y0, 0});
  const double dx = kHeight * std::tan(lean_deg * M_PI / 180.0);
  for (auto& v : m.vertices)
    if (v.z > kHeight - 1e-9) v.x += dx;
  return m;
}

// A straight wall (y 0..20) and one leaning 55° (y 30..50): at 0.2 mm layers each layer of the
// leaning one hangs 0.286 mm out, 64% of a 0.45 mm bead, so its leaning side's outer wall pieces
// rest between 25% and 50% on the layer below.
geo::Mesh walls() {
  geo::Mesh m = wall(0, 0);
  geo::append(m, wall(30, 55));
  return m;
}

bool extrudes(const test::Move& m) { return m.has_xy && m.de > 0; }

// Feed rates (mm/min) of the outer wall's moves from layer 2 up, by wall (straight: y below the
// middle of the print) and, for the leaning one, by side (its +x side, the one hanging out).
struct Speeds {
  std::set<double> straight, leaning_side, leaning_rest, inner_straight;
};

Speeds speeds(const test::Gcode& g) {
  double y_lo = 1e9, y_hi = -1e9;
  for (const auto& m : g.moves)
    if (extrudes(m)) y_lo = std::min(y_lo, m.y), y_hi = std::max(y_hi, m.y);
  const double y_mid = 0.5 * (y_lo + y_hi);
  std::map<int, double> x_max;  // per layer: the leaning wall's outer wall's largest x
  for (const auto& m : g.moves)
    if (extrudes(m) && m.type == "External perimeter" && m.y > y_mid)
      x_max[m.layer] = std::max({x_max[m.layer], m.x, m.x0});
  Speeds s;
  for (const auto& m : g.moves) {
    if (!extrudes(m) || m.layer < 2) continue;
    if (m.type == "Perimeter" && m.y < y_mid) s.inner_straight.insert(m.f);
    if (m.type != "External perimeter") continue;
    if (m.y < y_mid)
      s.straight.insert(m.f);
    else if (std::abs(m.x - x_max[m.layer]) < 0.01 && std::abs(m.x0 - x_max[m.layer]) < 0.01)
      s.leaning_side.insert(m.f);
    else
      s.leaning_rest.insert(m.f);
  }
  return s;
}

// No slowdown for short layers: the speeds are the rules' own.
const test::Sets kSets = {{"min_layer_time", "0"}};

}  // namespace

TEST_CASE("overhang speeds: the leaning side of a wall is slowed by the step it reaches, the rest is not") {
  test::TempDir dir("overhang-steps");
  auto r = test::slice_mesh(dir, "w", walls(), kSets);
  REQUIRE_MESSAGE(r.result.ok(), (r.result.ok() ? "" : r.result.error().to_string()));
  const Speeds s = speeds(r.g);
  // 64% over air: overhang_speed_50 (20 mm/s), below the outer wall's 25 mm/s.
  CHECK(s.leaning_side == std::set<double>{1200});
  CHECK(s.leaning_rest == std::set<double>{1500});
  CHECK(s.straight == std::set<double>{1500});
  CHECK(s.inner_straight == std::set<double>{2700});
}

TEST_CASE("overhang speeds: changed by a param, by --set, turned off, overridden by a rule") {
  test::TempDir dir("overhang-user");
  SUBCASE("a param in the user's rules") {
    auto r = test::slice_mesh(dir, "p", walls(), kSets, "param overhang_speed_50 = 10 mm/s\n");
    REQUIRE(r.result.ok());
    CHECK(speeds(r.g).leaning_side == std::set<double>{600});
    CHECK(speeds(r.g).straight == std::set<double>{1500});
  }
  SUBCASE("--set") {
    test::Sets sets = kSets;
    sets.push_back({"overhang_speed_50", "12"});
    auto r = test::slice_mesh(dir, "s", walls(), sets);
    REQUIRE(r.result.ok());
    CHECK(speeds(r.g).leaning_side == std::set<double>{720});
  }
  SUBCASE("turned off") {
    test::Sets sets = kSets;
    sets.push_back({"overhang_speeds", "false"});
    auto r = test::slice_mesh(dir, "o", walls(), sets);
    REQUIRE(r.result.ok());
    CHECK(speeds(r.g).leaning_side == std::set<double>{1500});
  }
  SUBCASE("a rule of the user's wins over the defaults' steps") {
    auto r = test::slice_mesh(dir, "r", walls(), kSets,
                              "rule when path.kind == outer_perimeter and piece.overhang > 30% { speed = 9 mm/s }\n");
    REQUIRE(r.result.ok());
    CHECK(speeds(r.g).leaning_side == std::set<double>{540});
    CHECK(speeds(r.g).straight == std::set<double>{1500});
  }
  SUBCASE("a step never speeds a wall up") {
    auto r = test::slice_mesh(dir, "f", walls(), kSets, "param overhang_speed_50 = 40 mm/s\n");
    REQUIRE(r.result.ok());
    CHECK(speeds(r.g).leaning_side == std::set<double>{1500});
  }
}
