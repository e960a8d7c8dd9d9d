#include <doctest/doctest.h>

#include "geometry/polygon/monotone.h"
#include "polygon_checks.h"

using namespace tranche::geo;
using tranche::test::mm_ring;

TEST_CASE("monotone: the fill direction is exact for multiples of 45 degrees") {
  const FillDirection d0(0), d45(45), d90(90), d135(135), d180(180), dm45(-45);
  CHECK(d0.dy == 0);
  CHECK(d90.dx == 0);
  CHECK(d45.dx == d45.dy);
  CHECK(d135.dx == -d135.dy);
  CHECK(d180.dx == d0.dx);
  CHECK(d180.dy == 0);
  CHECK(dm45.dx == d135.dx);
  CHECK(dm45.dy == d135.dy);
}

TEST_CASE("monotone: convex shapes are monotone at every angle") {
  const Ring square = mm_ring({{0, 0}, {10, 0}, {10, 10}, {0, 10}});
  const Ring tri = mm_ring({{0, 0}, {10, 1}, {3, 7}});
  for (int a = -180; a <= 360; a += 5) {
    CHECK(is_monotone(square, a));
    CHECK(is_monotone(tri, a));
    CHECK(is_monotone(tranche::test::reversed(square), a));
  }
}

TEST_CASE("monotone: a U shape is monotone only for lines across its arms") {
  // Opening at the top: vertical lines meet it once, horizontal lines through the arms twice.
  const Ring u = mm_ring({{0, 0}, {30, 0}, {30, 20}, {20, 20}, {20, 10}, {10, 10}, {10, 20}, {0, 20}});
  CHECK(is_monotone(u, 90));
  CHECK_FALSE(is_monotone(u, 0));
  CHECK_FALSE(is_monotone(u, 45));
}

TEST_CASE("monotone: collinear vertices and edges parallel to the fill lines") {
  const Ring r = mm_ring({{0, 0}, {5, 0}, {10, 0}, {10, 5}, {10, 10}, {5, 10}, {0, 10}, {0, 5}});
  CHECK(is_monotone(r, 0));
  CHECK(is_monotone(r, 90));
  CHECK(is_monotone(r, 45));
  // A notch whose bottom is exactly parallel to the fill lines still turns back.
  const Ring notch = mm_ring({{0, 0}, {10, 0}, {10, 10}, {6, 10}, {6, 5}, {4, 5}, {4, 10}, {0, 10}});
  CHECK_FALSE(is_monotone(notch, 0));
  CHECK(is_monotone(notch, 90));
}

TEST_CASE("monotone: degenerate and self-touching rings are not monotone") {
  CHECK_FALSE(is_monotone(mm_ring({{0, 0}, {10, 0}}), 0));
  CHECK_FALSE(is_monotone(mm_ring({{0, 0}, {5, 0}, {10, 0}}), 0));
  // Bow tie: one top, one bottom, but the chains cross.
  CHECK_FALSE(is_monotone(mm_ring({{0, 0}, {10, 10}, {10, 0}, {0, 10}}), 90));
  // Two triangles sharing a vertex, walked as one ring.
  CHECK_FALSE(is_monotone(mm_ring({{0, 0}, {10, 0}, {5, 5}, {10, 10}, {0, 10}, {5, 5}}), 0));
  // A diamond rotated so that its vertices lie exactly on sweep lines.
  CHECK(is_monotone(mm_ring({{5, 0}, {10, 5}, {5, 10}, {0, 5}}), 0));
  CHECK(is_monotone(mm_ring({{5, 0}, {10, 5}, {5, 10}, {0, 5}}), 45));
}
