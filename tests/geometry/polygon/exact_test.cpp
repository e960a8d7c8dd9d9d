#include <doctest/doctest.h>

#include <random>

#include "geometry/polygon/exact.h"

using namespace tranche::geo;
using exact::Contact;

TEST_CASE("exact: orientation stays exact where int64 cross products overflow") {
  const coord_t big = (coord_t{1} << 31) - 1;
  CHECK(exact::orientation({-big, -big}, {big, big}, {big - 1, big}) == 1);
  CHECK(exact::orientation({-big, -big}, {big, big}, {big, big - 1}) == -1);
  CHECK(exact::orientation({-big, -big}, {big, big}, {0, 0}) == 0);
  // Nearly collinear: (3, 1)·k lies exactly on the line, one unit off does not.
  const coord_t k = 700000000;
  CHECK(exact::orientation({0, 0}, {3 * k, k}, {3 * (k - 1), k - 1}) == 0);
  CHECK(exact::orientation({0, 0}, {3 * k, k}, {3 * (k - 1), k}) == 1);
}

TEST_CASE("exact: contact kinds") {
  CHECK(exact::contact({0, 0}, {10, 10}, {0, 10}, {10, 0}) == Contact::Cross);
  CHECK(exact::contact({0, 0}, {10, 0}, {5, 0}, {5, 5}) == Contact::Touch);
  CHECK(exact::contact({0, 0}, {10, 0}, {10, 0}, {20, 5}) == Contact::Touch);
  CHECK(exact::contact({0, 0}, {10, 0}, {5, 0}, {20, 0}) == Contact::Overlap);
  CHECK(exact::contact({0, 0}, {10, 0}, {10, 0}, {20, 0}) == Contact::Touch);
  CHECK(exact::contact({0, 0}, {10, 0}, {11, 0}, {20, 0}) == Contact::None);
  CHECK(exact::contact({0, 0}, {10, 0}, {12, -1}, {12, 1}) == Contact::None);
  CHECK(exact::strictly_between({0, 0}, {5, 5}, {10, 10}));
  CHECK_FALSE(exact::strictly_between({0, 0}, {10, 10}, {10, 10}));
}

TEST_CASE("exact: angular order around a point starts at +x") {
  const Point o(0, 0);
  const Point e(1, 0), n(0, 1), w(-1, 0), s(0, -1), se(1, -1);
  CHECK(exact::angle_less(o, e, n));
  CHECK(exact::angle_less(o, n, w));
  CHECK(exact::angle_less(o, w, s));
  CHECK(exact::angle_less(o, s, se));
  CHECK_FALSE(exact::angle_less(o, se, e));
  CHECK_FALSE(exact::angle_less(o, e, Point(5, 0)));
}

TEST_CASE("exact: doubled area") {
  CHECK(exact::area2({{0, 0}, {10, 0}, {10, 10}, {0, 10}}) == 200);
  CHECK(exact::area2({{0, 0}, {0, 10}, {10, 10}, {10, 0}}) == -200);
}

TEST_CASE("exact: the integer orientation agrees with CGAL's, degenerate cases included") {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<coord_t> big(-(coord_t{1} << 31), coord_t{1} << 31), small(-3, 3);
  for (int i = 0; i < 20000; ++i) {
    const bool degenerate = i % 2 == 0;  // small grids: many collinear and repeated points
    auto pick = [&] {
      return degenerate ? Point(small(rng) * 1000003, small(rng) * 999983) : Point(big(rng), big(rng));
    };
    Point a = pick(), b = pick(), c = pick();
    if (i % 7 == 0) c = Point(a.X + 2 * (b.X - a.X), a.Y + 2 * (b.Y - a.Y));  // exactly collinear
    CHECK(exact::orientation(a, b, c) == exact::orientation_cgal(a, b, c));
  }
}
