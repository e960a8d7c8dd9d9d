// Exact predicates on integer coordinates (1 unit = 1 nm). Every topological decision of the
// polygon stage goes through here: with coordinates up to 2^31 a cross product needs up to 2^65,
// so int64 arithmetic overflows and doubles round. The implementation (exact.cpp) is the only
// translation unit that includes CGAL; Point coordinates must stay within ±2^52 (exact doubles).
#pragma once

#include <cstdint>

#include "geometry/core/geom.h"

namespace tranche::geo::exact {

__extension__ typedef __int128 i128;  // exact doubled areas of rings (sum of 2^63-sized terms)

// Turn a -> b -> c: +1 counter-clockwise (c left of a->b), -1 clockwise, 0 collinear.
int orientation(const Point& a, const Point& b, const Point& c);

// True when p lies on the open segment (a, b): collinear and strictly between the endpoints.
bool strictly_between(const Point& a, const Point& p, const Point& b);

// How the closed segments [a, b] and [c, d] meet.
enum class Contact : uint8_t {
  None,     // no common point
  Cross,    // the interiors cross at a single point
  Touch,    // a single common point that is an endpoint of one of them
  Overlap,  // collinear with a common piece of positive length
};
Contact contact(const Point& a, const Point& b, const Point& c, const Point& d);

// Angular order of the directions u - o and v - o around o, counter-clockwise starting at +x
// (inclusive): true when u comes strictly before v. u, v != o.
bool angle_less(const Point& o, const Point& u, const Point& v);

// Iterated snap rounding (CGAL) of the rings' edges on the 1-unit grid: every edge is re-routed
// through the unit pixels of the vertices and crossings it passes, so that afterwards no two edges
// cross (they meet at shared vertices or overlap). Vertices stay where they are; crossing points
// move by less than 1.5 units. Each output ring follows its input ring (rings with fewer than 2
// distinct points are dropped). Slow (exact
// constructions): a fallback for what rounding of intersection points left behind.
Rings snap_round(const Rings& rings);

// Twice the signed area of a ring (positive counter-clockwise), exact.
inline i128 area2(const Ring& ring) {
  i128 a = 0;
  for (size_t i = 0, n = ring.size(); i < n; ++i) {
    const Point& p = ring[i];
    const Point& q = ring[(i + 1) % n];
    a += static_cast<i128>(p.X) * q.Y - static_cast<i128>(q.X) * p.Y;
  }
  return a;
}

}  // namespace tranche::geo::exact
