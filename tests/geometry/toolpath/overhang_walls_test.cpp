// Overhanging walls as bridges (geometry/toolpath/overhang_walls.h): when an island's wall band
// lies over air, what becomes a bridge, in which direction its lines run, and the walls kept.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "fixtures.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/edge_grid.h"
#include "geometry/toolpath/overhang_walls.h"
#include "geometry/toolpath/zigzag.h"

using namespace tranche;
using test::rect;

namespace {

constexpr double kBead = 0.45, kBand = 0.45 + 0.43;  // two walls

// The direction's distance from `want` (degrees, lines have no sense: 0 = 180).
double off_by(double deg, double want) {
  const double d = std::fmod(std::abs(deg - want), 180.0);
  return std::min(d, 180.0 - d);
}

}  // namespace

TEST_CASE("overhang walls: a slab over a gap between two pillars is bridged across the gap") {
  // Pillars x 0..5 and 17..22 (y 0..10) under a slab 0..22 × 0..10: a gap 12 mm wide.
  const geo::Rings below{rect(0, 0, 5, 10), rect(17, 0, 22, 10)};
  const geo::Rings slab{rect(0, 0, 22, 10)};
  const auto split = toolpath::split_overhang_walls(slab, below, kBand, kBead);
  REQUIRE_FALSE(split.empty());
  CHECK(off_by(split.angle_deg, 0) < 1e-9);  // along x: from pillar to pillar
  // The air is the gap (less half a bead each side); the bridge reaches the anchor into the pillars.
  CHECK(toolpath::area_mm2(split.air) == doctest::Approx((12 - kBead) * 10).epsilon(0.01));
  CHECK(toolpath::area_mm2(split.bridge) ==
        doctest::Approx((12 - kBead + 2 * toolpath::kBridgeAnchorMm) * 10).epsilon(0.01));
  // Lines across the bridge region at that angle (as the fill lays them) end on the pillars.
  toolpath::FillSpec fs;
  fs.angle_deg = split.angle_deg;
  fs.pitch_mm = 0.45;
  const toolpath::EdgeGrid below_grid(below);
  int lines = 0;
  for (const auto& fp : toolpath::zigzag(toolpath::fill_shape(split.bridge, geo::EdgeKind::Real), fs))
    for (size_t i = 0; i + 1 < fp.pts.size(); ++i) {
      const geo::Point &a = fp.pts[i], &b = fp.pts[i + 1];
      if (geo::to_mm(std::abs(b.X - a.X)) < 5) continue;  // a connector
      ++lines;
      CHECK(below_grid.inside(a));
      CHECK(below_grid.inside(b));
    }
  CHECK(lines > 15);
}

TEST_CASE("overhang walls: the same gap turned is crossed the other way") {
  const geo::Rings below{rect(0, 0, 10, 5), rect(0, 17, 10, 22)};
  const auto split = toolpath::split_overhang_walls({rect(0, 0, 10, 22)}, below, kBand, kBead);
  REQUIRE_FALSE(split.empty());
  CHECK(off_by(split.angle_deg, 90) < 1e-9);
}

TEST_CASE("overhang walls: a ledge held along one edge gets lines out from that edge, narrow or wide") {
  // A column x 15..25 under a plate 12..40: a ledge 3 mm out on one side, 15 mm on the other.
  const geo::Rings below{rect(15, 0, 25, 10)};
  const geo::Rings plate{rect(12, 0, 40, 10)};
  const auto split = toolpath::split_overhang_walls(plate, below, kBand, kBead);
  REQUIRE_FALSE(split.empty());
  CHECK(off_by(split.angle_deg, 0) < 1e-9);  // lines along the ledges' depth, not along the edge
  // Both ledges are air, and the walls kept are those on the column, clear of the bridge.
  CHECK(toolpath::area_mm2(split.air) == doctest::Approx((3 - 0.5 * kBead + 15 - 0.5 * kBead) * 10).epsilon(0.01));
  const geo::Ring outer = toolpath::offset(plate, -0.5 * kBead).front();
  const auto walls = toolpath::loops_outside({outer}, split.bridge, kBead);
  REQUIRE(walls.size() == 2);  // the column's two sides, y = 0 and y = 10
  const toolpath::EdgeGrid air_grid(split.air);
  for (const auto& w : walls) {
    double len = 0;
    for (size_t i = 0; i + 1 < w.size(); ++i) {
      len += geo::to_mm(std::hypot(double(w[i + 1].X - w[i].X), double(w[i + 1].Y - w[i].Y)));
      CHECK_FALSE(air_grid.inside(w[i]));
    }
    // Air starts half a bead past the column's edges; the bridge reaches the anchor back in.
    CHECK(len == doctest::Approx(10 + kBead - 2 * toolpath::kBridgeAnchorMm).epsilon(0.01));
  }
}

TEST_CASE("overhang walls: walls leaning out less than a bead, or an island on the layer below, are left alone") {
  const geo::Rings below{rect(0, 0, 10, 10)};
  // Hanging 0.4 mm out: the bead's centre is within half a bead of the layer below nearly all round.
  CHECK(toolpath::split_overhang_walls({rect(-0.4, -0.4, 10.4, 10.4)}, below, kBand, kBead).empty());
  CHECK(toolpath::split_overhang_walls({rect(1, 1, 9, 9)}, below, kBand, kBead).empty());
  // An island over a hole in the layer below, its wall band on material: the hole is the fill's
  // bridge, not the walls' business.
  const geo::Rings ring_below{rect(0, 0, 20, 20), rect(5, 5, 15, 15, false)};
  CHECK(toolpath::split_overhang_walls({rect(0, 0, 20, 20)}, ring_below, kBand, kBead).empty());
  // Nothing below at all: everything is air, no line is held: the loops stay.
  CHECK(toolpath::split_overhang_walls({rect(0, 0, 10, 4)}, {}, kBand, kBead).empty());
  double held = 1;
  CHECK(std::isfinite(toolpath::bridge_angle_deg({rect(0, 0, 10, 4)}, {}, 0.5, &held)));
  CHECK(held == 0);
  // An island mostly over nothing, held by a speck: its lines are held nowhere for the most part.
  CHECK(toolpath::split_overhang_walls({rect(0, 0, 20, 20)}, {rect(9, 9, 10, 10)}, kBand, kBead).empty());
  // Hanging 1.5 mm out on one side (a curved underside's crescent, steeper): nowhere 2 mm of air
  // across, left to the walls; 2.5 mm out, bridged.
  CHECK(toolpath::split_overhang_walls({rect(-1.5, 0, 10, 10)}, below, kBand, kBead).empty());
  CHECK_FALSE(toolpath::split_overhang_walls({rect(-2.5, 0, 10, 10)}, below, kBand, kBead).empty());
  // 2.5 mm out all round, a cap's brim: lines in one direction run along two of its sides held
  // nowhere (under 80% of their length held): the loops stay.
  CHECK(toolpath::split_overhang_walls({rect(-2.5, -2.5, 12.5, 12.5)}, below, kBand, kBead).empty());
}

TEST_CASE("overhang walls: a loop cut by a region comes out as one piece around the rest") {
  // A 10 × 10 loop starting at its lower left corner, less its left half: one piece, not two
  // meeting at the loop's first point.
  const geo::Ring loop = rect(0, 0, 10, 10);
  const auto pieces = toolpath::loops_outside({loop}, {rect(-1, 2, 5, 11)}, 0.1);
  REQUIRE(pieces.size() == 1);
  double len = 0;
  for (size_t i = 0; i + 1 < pieces[0].size(); ++i)
    len += geo::to_mm(std::hypot(double(pieces[0][i + 1].X - pieces[0][i].X), double(pieces[0][i + 1].Y - pieces[0][i].Y)));
  CHECK(len == doctest::Approx(2 + 10 + 10 + 5).epsilon(1e-6));  // (0,2) down, along the bottom, up, to (5,10)
}

namespace {


// What split_overhang_walls asked before the early-out: its difference shrunk by r, not empty.
bool holds_disc(const geo::Rings& region, const geo::Rings& below, double r) {
  return !toolpath::offset(toolpath::difference(region, below), -r).empty();
}

}  // namespace

TEST_CASE("overhang walls: the early-out rejects crescents and strips narrower than the disc, not wider ones") {
  const double r = 0.5 * toolpath::kMinAirAcrossMm;
  // A curved layer over the one below shifted 1.5 mm: a crescent 1.5 mm across at most. A disc
  // of radius 1 does not fit; the early-out says so, and the boolean agrees.
  const geo::Rings island{test::circle(0, 0, 10)};
  CHECK_FALSE(holds_disc(island, {test::circle(1.5, 0, 10)}, r));
  CHECK_FALSE(toolpath::may_hold_disc(island, {test::circle(1.5, 0, 10)}, r));
  // Strips along y 1.5 and 1.9 mm wide (the rows cross them: exact in x), along x 1.25 mm wide
  // (found from the rows a quarter of the radius apart: up to 2 (r − margin − pitch − slot) =
  // 1.34 mm sure to be rejected), and along a diagonal 1.8 mm wide.
  for (double wide : {1.5, 1.9}) CHECK_FALSE(toolpath::may_hold_disc({rect(0, 0, 10, 10)}, {rect(wide, -1, 11, 11)}, r));
  for (double at : {0.0, 0.05, 0.1, 0.15, 0.2}) {
    CHECK_FALSE(toolpath::may_hold_disc({rect(0, at, 10, 10 + at)}, {rect(-1, at + 1.25, 11, 11 + at)}, r));
    CHECK_FALSE(toolpath::may_hold_disc({rect(0, 0, 10, 10 + at)}, {rect(-1, 1.25, 11, 11 + at)}, r));
  }
  geo::Ring diag{geo::to_point(0, 0), geo::to_point(20, 20), geo::to_point(20 - 1.8 / std::sqrt(2), 20 + 1.8 / std::sqrt(2)),
                 geo::to_point(-1.8 / std::sqrt(2), 1.8 / std::sqrt(2))};  // 1.8 mm wide
  CHECK_FALSE(toolpath::may_hold_disc({diag}, {}, r));
  // Resting wholly on the layer below; nothing at all.
  CHECK_FALSE(toolpath::may_hold_disc({rect(1, 1, 9, 9)}, {rect(0, 0, 10, 10)}, r));
  CHECK_FALSE(toolpath::may_hold_disc({}, {rect(0, 0, 10, 10)}, r));
  // Shifted 2.5 mm, the crescent holds a disc of radius 1.25; a strip 2.1 mm wide; the island over
  // a hole 3 mm across in the layer below; over nothing: the early-out lets each through.
  CHECK(holds_disc(island, {test::circle(2.5, 0, 10)}, r));
  CHECK(toolpath::may_hold_disc(island, {test::circle(2.5, 0, 10)}, r));
  CHECK(toolpath::may_hold_disc({rect(0, 0, 10, 10)}, {rect(2.1, -1, 11, 11)}, r));
  geo::Ring hole = test::circle(10, 10, 1.5);
  std::reverse(hole.begin(), hole.end());
  const geo::Rings holed{rect(0, 0, 20, 20), hole};
  CHECK(toolpath::may_hold_disc({rect(0, 0, 20, 20)}, holed, r));
  CHECK(toolpath::may_hold_disc({rect(0, 0, 10, 4)}, {}, r));
  // A region 300 m tall would take a million rows: left to the boolean (conservatively "may"),
  // not a million rows' memory.
  CHECK(toolpath::may_hold_disc({rect(0, 0, 10, 3e5)}, {rect(0, 0, 10, 3e5)}, r));
}

TEST_CASE("overhang walls: the early-out never rejects what the boolean and the shrink let through") {
  // Random blobs (unions of discs) over random blobs shifted a little: whenever the difference
  // shrunk by r is not empty, may_hold_disc must say it may be; and it must reject most of the
  // rest (it is worth nothing otherwise).
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> u(0, 1);
  int exact = 0, rejected = 0, cases = 0;
  for (int t = 0; t < 300; ++t) {
    auto blob = [&](double dx, double dy) {
      geo::Rings b;
      for (int k = 0; k < 3; ++k) b.push_back(test::circle(dx + 8 * u(rng), dy + 8 * u(rng), 2 + 6 * u(rng), 24 + int(60 * u(rng))));
      return toolpath::union_of(b, {});
    };
    const geo::Rings below = blob(0, 0);
    const double shift = 3 * u(rng), a = 2 * M_PI * u(rng);
    geo::Rings island = below;
    for (auto& ring : island)
      for (auto& p : ring) p.X += geo::to_units(shift * std::cos(a)), p.Y += geo::to_units(shift * std::sin(a));
    if (t % 3 == 0) island = toolpath::union_of(island, blob(0, 0));  // some of another shape
    for (double r : {1.0, 0.5 + u(rng)}) {
      ++cases;
      const bool holds = holds_disc(island, below, r), may = toolpath::may_hold_disc(island, below, r);
      if (holds) ++exact;
      if (holds) CHECK(may);
      if (!may) ++rejected;
    }
  }
  CHECK(exact > 30);  // both kinds of case occur
  CHECK(rejected > (cases - exact) / 2);
}
