// Welding: weld_indexed (the 3MF loader's, from indexed triangles) gives what weld_corners gives
// on the same triangles' corners: the same vertices in the same order, the same triangles, the
// same warnings and errors.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "geometry/mesh/weld.h"

using namespace tranche;

namespace {

std::vector<float> corners_of(const std::vector<float>& vertices, const std::vector<uint32_t>& triangles) {
  std::vector<float> out;
  for (uint32_t v : triangles) out.insert(out.end(), &vertices[3 * v], &vertices[3 * v] + 3);
  return out;
}

void check_same(const std::vector<float>& vertices, const std::vector<uint32_t>& triangles) {
  Report ri, rc;
  auto indexed = geo::weld_indexed(vertices, triangles, "m.3mf", ri);
  auto corners = geo::weld_corners(corners_of(vertices, triangles), "m.3mf", rc);
  REQUIRE(indexed.ok() == corners.ok());
  if (!indexed) {
    CHECK(indexed.error().to_string() == corners.error().to_string());
    return;
  }
  REQUIRE(indexed->vertices.size() == corners->vertices.size());
  bool same = true;
  for (size_t i = 0; i < indexed->vertices.size(); ++i) {
    const auto &a = indexed->vertices[i], &b = corners->vertices[i];
    // Bit for bit: -0 and +0 are told apart too.
    same = same && std::signbit(a.x) == std::signbit(b.x) && a.x == b.x && a.y == b.y && a.z == b.z &&
           std::signbit(a.y) == std::signbit(b.y) && std::signbit(a.z) == std::signbit(b.z);
  }
  CHECK(same);
  CHECK(indexed->triangles == corners->triangles);
  const auto wi = ri.warnings(), wc = rc.warnings();
  REQUIRE(wi.size() == wc.size());
  for (size_t i = 0; i < wi.size(); ++i) {
    CHECK(wi[i].code == wc[i].code);
    CHECK(wi[i].message == wc[i].message);
  }
}

}  // namespace

TEST_CASE("weld_indexed: duplicate vertices, -0, degenerate and unused vertices weld as their corners do") {
  // A grid of points in which many are repeated under other indices (as a mesh whose parts were
  // joined has them), some -0, some triangles degenerate once welded, some vertices unused.
  std::mt19937 rng(13);
  std::uniform_int_distribution<int> coord(-3, 3), pick(0, 199);
  std::vector<float> vertices;
  for (int i = 0; i < 200; ++i) {
    for (int k = 0; k < 3; ++k) {
      const int c = coord(rng);
      vertices.push_back(c == 0 && (i % 3 == 0) ? -0.0f : static_cast<float>(c) * 0.5f);
    }
  }
  std::vector<uint32_t> triangles;
  for (int t = 0; t < 400; ++t)
    for (int k = 0; k < 3; ++k) triangles.push_back(static_cast<uint32_t>(pick(rng) % 150));  // 150..199 unused
  check_same(vertices, triangles);
  // No degenerate triangle: nothing dropped, no renumbering.
  std::vector<uint32_t> clean;
  for (size_t t = 0; t < triangles.size(); t += 3) {
    const uint32_t a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
    auto same = [&](uint32_t u, uint32_t v) {
      for (int k = 0; k < 3; ++k)
        if (!(vertices[3 * u + k] == vertices[3 * v + k])) return false;
      return true;
    };
    if (!same(a, b) && !same(b, c) && !same(a, c)) clean.insert(clean.end(), {a, b, c});
  }
  REQUIRE(clean.size() < triangles.size());
  check_same(vertices, clean);
  Report r;
  auto m = geo::weld_indexed(vertices, clean, "m.3mf", r);
  REQUIRE(m.ok());
  CHECK(r.empty());
  CHECK(m->triangles.size() == clean.size() / 3);
}

TEST_CASE("weld_indexed: meshes whose vertices are all distinct (the order's shorter way) weld as their corners do") {
  // Vertices no two of which are equal, -0 among them (a vertex with -0 where no other has +0),
  // given in a shuffled order, some unused, triangles in any order: the first-use order must come
  // out as the welder numbers corners. Then one vertex repeated under another index, and one -0
  // whose +0 twin is there: the longer way, the same results.
  std::mt19937 rng(1331);
  for (int round = 0; round < 40; ++round) {
    CAPTURE(round);
    const int nv = 3 + round * 7;
    std::vector<float> vertices;
    for (int i = 0; i < nv; ++i) {
      vertices.push_back(static_cast<float>(i) * 0.25f);
      vertices.push_back(i % 4 == 0 ? -0.0f : static_cast<float>(i % 5));
      vertices.push_back(i % 7 == 0 ? -0.0f : 1.0f);
    }
    // Shuffled, so that the first use is no longer the file's order.
    std::vector<uint32_t> perm(static_cast<size_t>(nv));
    for (int i = 0; i < nv; ++i) perm[static_cast<size_t>(i)] = static_cast<uint32_t>(i);
    std::shuffle(perm.begin(), perm.end(), rng);
    std::vector<float> shuffled(vertices.size());
    for (int i = 0; i < nv; ++i)
      for (int k = 0; k < 3; ++k) shuffled[3 * perm[static_cast<size_t>(i)] + k] = vertices[3 * i + k];
    std::uniform_int_distribution<uint32_t> pick(0, static_cast<uint32_t>(nv - 1 - nv / 5));  // the rest unused
    std::vector<uint32_t> triangles;
    for (int t = 0; t < 2 * nv; ++t) {
      const uint32_t a = pick(rng);
      uint32_t b = pick(rng), c = pick(rng);
      if (b == a) b = (a + 1) % static_cast<uint32_t>(nv);
      if (c == a || c == b) c = (std::max(a, b) + 1) % static_cast<uint32_t>(nv);
      if (c == a || c == b) continue;
      triangles.insert(triangles.end(), {a, b, c});
    }
    check_same(shuffled, triangles);
    // A triangle with one vertex twice (degenerate by its indices): dropped with a warning, as
    // its corners are.
    std::vector<uint32_t> with_degenerate = triangles;
    with_degenerate.insert(with_degenerate.end(), {perm[2], perm[2], perm[1]});
    check_same(shuffled, with_degenerate);
    std::vector<geo::Vec3> ordered;
    geo::WeldScratch scratch;
    std::vector<std::array<uint32_t, 3>> tri(triangles.size() / 3);
    for (size_t t = 0; t < tri.size(); ++t) tri[t] = {triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2]};
    CHECK(geo::order_by_first_use(shuffled.data(), static_cast<size_t>(nv), tri, ordered, scratch) == 0);
    bool positive_zeros = true;
    for (const auto& v : ordered) positive_zeros = positive_zeros && !std::signbit(v.x) && !std::signbit(v.y) && !std::signbit(v.z);
    CHECK(positive_zeros);
    // A repeated vertex (the last, equal to the first), then a +0 twin of a -0 vertex.
    std::vector<float> repeated = shuffled;
    repeated.insert(repeated.end(), shuffled.begin(), shuffled.begin() + 3);
    std::vector<uint32_t> more = triangles;
    more.insert(more.end(), {static_cast<uint32_t>(nv), 1, 2});
    check_same(repeated, more);
    std::vector<float> twin = shuffled;
    twin.insert(twin.end(), {0.0f, 0.0f, 1.0f});  // a vertex of its own
    twin.insert(twin.end(), {0.0f, 0.0f, 0.0f});  // vertex 0 before the shuffle is (0, -0, -0)
    more = triangles;
    more.insert(more.end(), {static_cast<uint32_t>(nv + 1), static_cast<uint32_t>(nv), perm[1]});
    check_same(twin, more);
  }
}

TEST_CASE("weld_indexed: errors are those of weld_corners") {
  const float inf = std::numeric_limits<float>::infinity();
  SUBCASE("a coordinate that is not finite, in a used vertex: the triangle that uses it is named") {
    const std::vector<float> v = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, inf, 0};
    check_same(v, {0, 1, 2, 0, 3, 1});
    Report r;
    CHECK(geo::weld_indexed(v, {0, 1, 2, 0, 3, 1}, "m.3mf", r).error().message.find("triangle 2") !=
          std::string::npos);
  }
  SUBCASE("in an unused vertex: no error") {
    const std::vector<float> v = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, inf, 0};
    check_same(v, {0, 1, 2});
    Report r;
    CHECK(geo::weld_indexed(v, {0, 1, 2}, "m.3mf", r).ok());
  }
  SUBCASE("only degenerate triangles") {
    const std::vector<float> v = {0, 0, 0, 1, 0, 0, 0, 0, 0};
    check_same(v, {0, 1, 2, 2, 0, 1});
    Report r;
    CHECK(geo::weld_indexed(v, {0, 1, 2}, "m.3mf", r).error().message.find("all 1 triangles are degenerate") !=
          std::string::npos);
  }
}
