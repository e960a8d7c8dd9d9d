#include <doctest/doctest.h>

#include <fmt/format.h>

#include <set>

#include "generators.h"
#include "geometry/polygon/bridge.h"
#include "geometry/polygon/resolve.h"
#include "polygon_checks.h"

using namespace tranche;
using namespace tranche::geo;
using test::mm_ring;
using test::rect;
using test::reversed;

namespace {

std::vector<Island> islands_of(const Rings& loops) {
  Report rep;
  auto r = resolve_islands(loops, {}, rep);
  REQUIRE(r.ok());
  return *r;
}

// What a bridged path must be: the island's boundary once, each cut once each way, cuts inside
// the island crossing nothing, and the enclosed area unchanged.
std::string path_problem(const Island& is, const BridgedPath& p) {
  if (p.ring.size() != p.edges.size()) return "edges and ring differ in size";
  if (exact::area2(p.ring) != test::island_area2(is)) return "area differs from the island's";
  std::multiset<test::Seg> real, boundary, cuts;
  for (size_t i = 0; i < p.ring.size(); ++i) {
    const auto s = test::seg(p.ring[i], p.ring[(i + 1) % p.ring.size()]);
    (p.edges[i] == EdgeKind::Real ? real : cuts).insert(s);
  }
  auto add = [&](const Ring& r) {
    for (size_t i = 0; i < r.size(); ++i) boundary.insert(test::seg(r[i], r[(i + 1) % r.size()]));
  };
  add(is.shape.outer);
  for (const auto& h : is.shape.holes) add(h);
  if (real != boundary) return "real edges are not the boundary";
  if (static_cast<int>(cuts.size()) != 2 * p.cuts) return "cut count differs";
  for (const auto& s : cuts) {
    if (cuts.count({s.second, s.first}) != 1) return "a cut is not walked once each way";
    const Point a(s.first.first, s.first.second), b(s.second.first, s.second.second);
    for (const auto& e : boundary) {
      const Point c(e.first.first, e.first.second), d(e.second.first, e.second.second);
      const auto k = exact::contact(a, b, c, d);
      if (k == exact::Contact::Cross || k == exact::Contact::Overlap) return "a cut crosses an edge";
      if (k == exact::Contact::Touch && !(a == c || a == d || b == c || b == d))
        return "a cut touches an edge";
    }
    for (const auto& t : cuts) {
      const Point c(t.first.first, t.first.second), d(t.second.first, t.second.second);
      if (exact::contact(a, b, c, d) == exact::Contact::Cross) return "two cuts cross";
    }
  }
  return "";
}

}  // namespace

TEST_CASE("bridge: a square with one hole becomes one path with one cut") {
  const auto v = islands_of(
      {mm_ring({{0, 0}, {10, 0}, {10, 10}, {0, 10}}), reversed(mm_ring({{4, 4}, {6, 4}, {6, 6}, {4, 6}}))});
  auto p = bridge_holes(v[0].shape);
  REQUIRE(p.ok());
  CHECK(p->cuts == 1);
  CHECK(p->ring.size() == 4 + 4 + 2);
  CHECK(path_problem(v[0], *p) == "");
  CHECK(exact::area2(p->ring) > 0);
}

TEST_CASE("bridge: no holes, and a hole touching the outline, need no cut") {
  const auto sq = islands_of({rect(0, 0, 10, 10)});
  auto p = bridge_holes(sq[0].shape);
  REQUIRE(p.ok());
  CHECK(p->cuts == 0);
  CHECK(p->ring == sq[0].shape.outer);
  const auto c =
      islands_of({mm_ring({{0, 0}, {10, 0}, {10, 10}, {0, 10}}), mm_ring({{5, 10}, {6, 8}, {5, 6}, {4, 8}})});
  auto q = bridge_holes(c[0].shape);
  REQUIRE(q.ok());
  CHECK(q->cuts == 0);
  CHECK(path_problem(c[0], *q) == "");
}

TEST_CASE("bridge: a plate with 100 holes gets 100 short cuts") {
  Rings loops{rect(0, 0, 115000000, 115000000)};
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      loops.push_back(reversed(rect(5000000 + i * 11000000, 5000000 + j * 11000000, 11000000 + i * 11000000,
                                    11000000 + j * 11000000)));
    }
  }
  const auto v = islands_of(loops);
  REQUIRE(v.size() == 1);
  auto p = bridge_holes(v[0].shape);
  REQUIRE(p.ok());
  CHECK(p->cuts == 100);
  CHECK(path_problem(v[0], *p) == "");
  int short_cuts = 0;
  for (size_t i = 0; i < p->ring.size(); ++i) {
    if (p->edges[i] != EdgeKind::Artificial) continue;
    const Point a = p->ring[i], b = p->ring[(i + 1) % p->ring.size()];
    // The gap between holes, or a plate corner to the nearest hole corner (cuts join vertices).
    const double len = std::hypot(double(a.X - b.X), double(a.Y - b.Y));
    CHECK((len == 5000000.0 || len == doctest::Approx(5000000.0 * std::sqrt(2.0))));
    short_cuts += len == 5000000.0;
  }
  CHECK(short_cuts == 2 * 99);  // each cut is walked twice
}

TEST_CASE("bridge: random islands with holes") {
  test::gen::Rng rng(5);
  int islands = 0, cuts = 0;
  for (int i = 0; i < 400; ++i) {
    const Rings loops = i % 2 ? test::gen::stars_with_holes(rng, 1) : test::gen::circles(rng, 1000000);
    for (const auto& is : islands_of(loops)) {
      auto p = bridge_holes(is.shape);
      REQUIRE_MESSAGE(p.ok(), (p.ok() ? "" : p.error().to_string()));
      const std::string problem = path_problem(is, *p);
      CHECK_MESSAGE(problem.empty(), fmt::format("case {}: {}", i, problem));
      ++islands;
      cuts += p->cuts;
    }
  }
  MESSAGE(fmt::format("{} islands, {} cuts", islands, cuts));
  CHECK(cuts > 50);
}
