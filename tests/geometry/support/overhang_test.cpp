#include <doctest/doctest.h>

#include <algorithm>

#include "tests/geometry/toolpath/fixtures.h"
#include "geometry/support/brim.h"
#include "geometry/support/overhang.h"
#include "geometry/toolpath/clip.h"

using namespace tranche;
using namespace tranche::support;
using doctest::Approx;
using test::rect;

namespace {
geo::Rings R(geo::Ring r) { return {std::move(r)}; }

// The overhang of `island` over `below` with the default spec (reach 0.2 mm, 0.4 mm nozzle).
geo::Rings over(const geo::Rings& island, const geo::Rings& below, double max_bridge = 10) {
  OverhangSpec s;
  s.max_bridge_mm = max_bridge;
  return overhang(island, toolpath::offset(below, s.reach_mm), below, s);
}
}  // namespace

TEST_CASE("overhang: a ledge beyond the reach needs support, the part within it does not") {
  // A 10 mm block over a 10 x 5 mm one: the 5 mm ledge, less the 0.2 mm reach, hangs in the air.
  auto o = over(R(rect(0, 0, 10, 10)), R(rect(0, 0, 10, 5)));
  CHECK(toolpath::area_mm2(o) == Approx(10 * 4.8).epsilon(1e-3));
  // Leaning out by less than the reach (a 45° slope at 0.2 mm layers leans 0.2 mm): nothing.
  CHECK(over(R(rect(0, 0, 10, 10.15)), R(rect(0, 0, 10, 10))).empty());
}

TEST_CASE("overhang: specks smaller than a nozzle and slivers are left alone") {
  // A 0.3 mm tab: its area is under a nozzle's disc.
  CHECK(over(toolpath::union_of({rect(0, 0, 10, 10), rect(9, 5, 10.5, 5.3)}), R(rect(0, 0, 10, 10))).empty());
  // A 0.02 mm sliver all along an edge (a slope barely past the angle).
  CHECK(over(R(rect(0, 0, 10, 10.22)), R(rect(0, 0, 10, 10))).empty());
}

TEST_CASE("overhang: a span held on two sides and short enough is a bridge") {
  // Two pillars 6 mm apart under a slab: the 6 mm span bridges.
  geo::Rings pillars{rect(0, 0, 2, 10), rect(8, 0, 10, 10)};
  CHECK(over(R(rect(0, 0, 10, 10)), pillars).empty());
  // The same pillars 20 mm apart: too long to bridge at 10 mm, supported.
  geo::Rings far{rect(0, 0, 2, 10), rect(22, 0, 24, 10)};
  CHECK(toolpath::area_mm2(over(R(rect(0, 0, 24, 10)), far)) == Approx(10 * 19.6).epsilon(1e-3));
  // support_max_bridge = 0: every overhang is supported.
  CHECK(!over(R(rect(0, 0, 10, 10)), pillars, 0).empty());
}

TEST_CASE("overhang: a ledge held on one side only, or a cap round a stem, is no bridge") {
  // A 4 mm ledge: short, but held on one side.
  CHECK(!over(R(rect(0, 0, 10, 10)), R(rect(0, 0, 10, 6))).empty());
  // A cap on a stem: held along its inner edge only (a quarter of its outline).
  auto o = over(R(rect(0, 0, 12, 12)), R(rect(4, 4, 8, 8)));
  CHECK(toolpath::area_mm2(o) > 100);
  // A ceiling held all round (the top of a box), 6 mm across: a bridge.
  geo::Rings walls{rect(0, 0, 8, 8), rect(1, 1, 7, 7, false)};
  CHECK(over(R(rect(0, 0, 8, 8)), walls).empty());
}

TEST_CASE("overhang: a sliver held all round but nowhere 2 mm across (a dome closing) is supported, not bridged") {
  // A ceiling ring 1.2 mm wide round a 6 mm opening, walls all round it below: once a bridge.
  geo::Rings below{rect(0, 0, 10, 10), rect(1.2, 1.2, 8.8, 8.8, false)};
  geo::Rings island{rect(0, 0, 10, 10), rect(2.4, 2.4, 7.6, 7.6, false)};
  auto o = over(island, below);
  CHECK(toolpath::area_mm2(o) > 4 * 5 * 0.8);
  // The same ring 3 mm wide is a bridge.
  geo::Rings wide{rect(0, 0, 10, 10), rect(4.2, 4.2, 5.8, 5.8, false)};
  CHECK(over(wide, below).empty());
}

TEST_CASE("overhang: a slope's thin sliver round a funnel is held on one side: supported, not bridged") {
  // A square funnel widening by 0.27 mm a layer (53° from vertical): a 0.07 mm ring beyond the reach.
  geo::Rings below{rect(0, 0, 20, 20)};
  auto o = over(R(rect(-0.27, -0.27, 20.27, 20.27)), below);
  CHECK(toolpath::area_mm2(o) > 4 * 20 * 0.05);
}

TEST_CASE("overhang: an L held at the ends of its arms has no straight span: supported, not bridged") {
  // Two holds and every point within 7 mm of one (max_bridge 14), as a curved underside's band
  // often is, yet no straight line across it lands on the layer below at both ends: bridge lines
  // would end in the air. (Two separate holds once made it a bridge.)
  geo::Rings below{rect(6.2, 0, 8, 2.5), rect(0, 6.2, 2.5, 8)};
  geo::Rings island = toolpath::union_of({rect(0, 0, 8, 2.5), rect(0, 0, 2.5, 8)});
  CHECK(toolpath::area_mm2(over(island, below, 14)) > 20);
  // A bar between the same kind of holds at both ends spans: a bridge.
  geo::Rings ends{rect(0, 0, 1, 2.5), rect(8, 0, 9, 2.5)};
  CHECK(over(R(rect(0, 0, 9, 2.5)), ends, 14).empty());
}

TEST_CASE("components: each outer ring with its holes") {
  geo::Rings r{rect(0, 0, 10, 10), rect(2, 2, 4, 4, false), rect(20, 0, 30, 10)};
  auto c = components(r);
  REQUIRE(c.size() == 2);
  size_t with_hole = c[0].size() == 2 ? 0 : 1;
  CHECK(c[with_hole].size() == 2);
  CHECK(c[1 - with_hole].size() == 1);
}

namespace {
// A piece as a comparable value: its rings as coordinate pairs, each started at its least vertex, sorted.
using Coords = std::vector<std::pair<geo::coord_t, geo::coord_t>>;
std::vector<Coords> canonical_piece(const geo::Rings& piece) {
  std::vector<Coords> out;
  for (const geo::Ring& r : piece) {
    Coords c;
    for (const geo::Point& p : r) c.emplace_back(p.X, p.Y);
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    out.push_back(std::move(c));
  }
  std::sort(out.begin(), out.end());
  return out;
}
std::vector<std::vector<Coords>> canonical_pieces(const std::vector<geo::Rings>& ps) {
  std::vector<std::vector<Coords>> out;
  for (const auto& p : ps) out.push_back(canonical_piece(p));
  std::sort(out.begin(), out.end());
  return out;
}
}  // namespace

TEST_CASE("pieces: a boolean's result split as components() splits it, without the union") {
  // Nested: a frame round a frame round a square, a hole touching its outer at a vertex, and
  // random unions and differences of rectangles and discs.
  std::vector<geo::Rings> cases;
  cases.push_back(toolpath::union_of({rect(0, 0, 30, 30), rect(2, 2, 28, 28, false), rect(5, 5, 25, 25),
                                      rect(7, 7, 23, 23, false), rect(10, 10, 20, 20)}));
  cases.push_back(toolpath::difference({rect(0, 0, 10, 10)}, {geo::Ring{geo::to_point(0, 5), geo::to_point(5, 2),
                                                                        geo::to_point(8, 5), geo::to_point(5, 8)}}));
  test::Lcg rnd{7};
  for (int c = 0; c < 60; ++c) {
    geo::Rings add, cut;
    for (int i = 0; i < 6; ++i) {
      const double x = 40 * rnd(), y = 40 * rnd(), w = 2 + 15 * rnd(), h = 2 + 15 * rnd();
      add.push_back(i % 2 ? rect(x, y, x + w, y + h) : test::circle(x, y, 0.5 * w, 24));
      const double u = 40 * rnd(), v = 40 * rnd();
      cut.push_back(i % 2 ? test::circle(u, v, 1 + 4 * rnd(), 24) : rect(u, v, u + 1 + 6 * rnd(), v + 1 + 6 * rnd()));
    }
    cases.push_back(toolpath::difference(toolpath::union_of(add), cut));
  }
  size_t with_holes = 0, nested = 0;
  for (const geo::Rings& r : cases) {
    const auto mine = pieces(r), theirs = components(r);
    CHECK(canonical_pieces(mine) == canonical_pieces(theirs));
    for (const auto& p : mine) with_holes += p.size() > 1;
    nested += mine.size() > 0 && mine.size() < r.size() && mine.size() > 1;
  }
  CHECK(with_holes > 10);  // the cases do exercise the holes' assignment
  CHECK(nested > 0);
  // Outers keep their order.
  const geo::Rings two{rect(20, 0, 30, 10), rect(0, 0, 10, 10), rect(2, 2, 4, 4, false)};
  const auto p = pieces(two);
  REQUIRE(p.size() == 2);
  CHECK(p[0].size() == 1);
  CHECK(p[1].size() == 2);
}

TEST_CASE("brim: loops round an island, outermost first, none over a neighbour") {
  std::vector<BrimIsland> asks{{rect(0, 0, 10, 10), 3}};
  geo::Rings all{rect(0, 0, 10, 10)};
  auto b = brim_paths(asks, all, 0.45, 0.4);
  REQUIRE(b.size() == 3);
  for (const auto& p : b) CHECK(p.closed);
  // The last loop is the one touching the part (centre half a bead out).
  CHECK(geo::to_mm(toolpath::bbox({b.back().pts}).max_x) == Approx(10.225).epsilon(1e-3));
  CHECK(geo::to_mm(toolpath::bbox({b.front().pts}).max_x) == Approx(10.225 + 0.8).epsilon(1e-3));
  // A neighbour without a brim 0.6 mm away cuts the outer loops into open pieces.
  all.push_back(rect(10.6, 0, 20, 10));
  auto cut = brim_paths(asks, all, 0.45, 0.4);
  bool open = false;
  for (const auto& p : cut) {
    open |= !p.closed;
    for (const auto& q : p.pts) CHECK(ClipperLib::PointInPolygon(q, rect(10.6 - 0.17, 0, 20, 10)) == 0);  // never over the neighbour
  }
  CHECK(open);
  // No island asks: no brim.
  CHECK(brim_paths({{rect(0, 0, 10, 10), 0}}, all, 0.45, 0.4).empty());
}
