// Exact predicates on integer coordinates (1 unit = 1 nm). Every topological decision of the
// polygon stage goes through here (which side of an edge a vertex is, whether two edges touch,
// the angular order of edges around a vertex): with coordinates up to 2^31 a cross product needs
// up to 2^65, so int64 arithmetic overflows and doubles round.
//
// The sign predicates are 128-bit integer arithmetic, exact for |coordinates| < 2^62. CGAL's
// filtered predicates (Epick) give the same signs but were 10x slower on sliced layers, where
// exactly collinear points are common and each one falls through to multiprecision arithmetic.
// CGAL does what needs exact constructions (snap rounding) and cross-checks the predicates in
// tests; exact.cpp is the only translation unit that includes it.
#pragma once

#include <cstdint>

#include "geometry/core/geom.h"

namespace tranche::geo::exact {

__extension__ typedef __int128 i128;  // exact doubled areas of rings (sum of 2^63-sized terms)

// Turn a -> b -> c: +1 counter-clockwise (c left of a->b), -1 clockwise, 0 collinear.
inline int orientation(const Point& a, const Point& b, const Point& c) {
  const i128 d = static_cast<i128>(b.X - a.X) * (c.Y - a.Y) - static_cast<i128>(b.Y - a.Y) * (c.X - a.X);
  return (d > 0) - (d < 0);
}

// True when p lies on the open segment (a, b): collinear and strictly between the endpoints.
inline bool strictly_between(const Point& a, const Point& p, const Point& b) {
  if (p == a || p == b || orientation(a, p, b) != 0) return false;
  const i128 dot = static_cast<i128>(p.X - a.X) * (b.X - p.X) + static_cast<i128>(p.Y - a.Y) * (b.Y - p.Y);
  return dot > 0;
}

// The same orientation computed by CGAL's Epick kernel (tests compare the two; |coords| < 2^52).
int orientation_cgal(const Point& a, const Point& b, const Point& c);

// How the closed segments [a, b] and [c, d] meet.
enum class Contact : uint8_t {
  None,     // no common point
  Cross,    // the interiors cross at a single point
  Touch,    // a single common point that is an endpoint of one of them
  Overlap,  // collinear with a common piece of positive length
};
inline Contact contact(const Point& a, const Point& b, const Point& c, const Point& d) {
  const int o1 = orientation(a, b, c), o2 = orientation(a, b, d);
  if (o1 * o2 > 0) return Contact::None;
  const int o3 = orientation(c, d, a), o4 = orientation(c, d, b);
  if (o3 * o4 > 0) return Contact::None;
  if (o1 == 0 && o2 == 0) {
    // Collinear: compare the intervals; lexicographic order is the order along the line.
    auto less = [](const Point& p, const Point& q) { return p.X < q.X || (p.X == q.X && p.Y < q.Y); };
    const Point lo1 = less(b, a) ? b : a, hi1 = less(b, a) ? a : b;
    const Point lo2 = less(d, c) ? d : c, hi2 = less(d, c) ? c : d;
    const Point& lo = less(lo1, lo2) ? lo2 : lo1;
    const Point& hi = less(hi1, hi2) ? hi1 : hi2;
    if (less(hi, lo)) return Contact::None;
    return lo == hi ? Contact::Touch : Contact::Overlap;
  }
  if (o1 != 0 && o2 != 0 && o3 != 0 && o4 != 0) return Contact::Cross;
  return Contact::Touch;
}

// Angular order of the directions u - o and v - o around o, counter-clockwise starting at +x
// (inclusive): true when u comes strictly before v. u, v != o.
inline bool angle_less(const Point& o, const Point& u, const Point& v) {
  // Half 0: directions in [0, pi) from +x; half 1: [pi, 2 pi). Within a half a cross product decides.
  const int hu = (u.Y > o.Y || (u.Y == o.Y && u.X > o.X)) ? 0 : 1;
  const int hv = (v.Y > o.Y || (v.Y == o.Y && v.X > o.X)) ? 0 : 1;
  if (hu != hv) return hu < hv;
  return orientation(o, u, v) > 0;
}

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
