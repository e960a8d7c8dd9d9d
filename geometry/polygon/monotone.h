// Monotonicity with respect to a fill direction: a ring is monotone for angle θ when every line
// parallel to d = (cos θ, sin θ) meets it in at most one interval, so one zig-zag fills it.
#pragma once

#include <cstdint>

#include "geometry/core/geom.h"

namespace tranche::geo {

// The fill direction as an exact integer vector, d ≈ 2^20 (cos θ, sin θ): every sweep decision is
// then integer arithmetic. Multiples of 45° are represented exactly; other angles within 1e-6 rad.
// Points are ordered along the sweep by `across` (position perpendicular to the fill lines,
// larger first), ties by `along` (smaller first): a strict total order on distinct points, which
// treats edges exactly parallel to d as very slightly tilted.
struct FillDirection {
  int64_t dx = 1 << 20, dy = 0;

  FillDirection() = default;
  explicit FillDirection(double angle_deg);  // any angle; θ and θ + 180° are the same fill

  // Both need |coordinates| < 2^31 units (±2147 mm): |result| < 2^52.
  int64_t across(const Point& p) const { return dx * p.Y - dy * p.X; }
  int64_t along(const Point& p) const { return dx * p.X + dy * p.Y; }
  // True when a is swept before b ("above" it in the frame where d is horizontal).
  bool before(const Point& a, const Point& b) const {
    const int64_t ya = across(a), yb = across(b);
    return ya > yb || (ya == yb && along(a) < along(b));
  }
};

// Coordinates the sweep accepts (|x|, |y| below this, in units).
inline constexpr coord_t kMaxSweepCoord = coord_t{1} << 31;

// Exact test that `ring` (either orientation; repeated consecutive points are ignored) is a simple
// polygon that every line parallel to the fill direction meets in at most one interval. Edges
// exactly on a fill line are allowed anywhere. Rings touching themselves are not monotone.
bool is_monotone(const Ring& ring, double angle_deg);
bool is_monotone(const Ring& ring, const FillDirection& dir);

}  // namespace tranche::geo
