// Convex polygons in the bed's plane (mm), for footprints, arrangement and the bed check:
// counter-clockwise vertex lists without repeats, in doubles (placement needs no exact topology).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace tranche::plate {

using Vec2 = Eigen::Vector2d;
using Convex = std::vector<Vec2>;  // counter-clockwise, no collinear or repeated vertices

// The convex hull of `points` (Andrew's monotone chain); fewer than 3 vertices when they are
// all on one line.
Convex convex_hull(std::vector<Vec2> points);

// Area, mm² (positive for counter-clockwise).
double area(const Convex& c);

// The polygon with at most `k` vertices circumscribing `c` (its support lines in k directions,
// evenly spaced): a little larger than `c`, never smaller. `c` is returned when it is small enough.
Convex circumscribe(const Convex& c, int k);

// The Minkowski sum a ⊕ b of two convex polygons, in O(|a| + |b|).
Convex minkowski_sum(const Convex& a, const Convex& b);

// -c: every vertex negated (still counter-clockwise).
Convex negated(const Convex& c);

// `c` grown by at least `d` mm in every direction (the sum with a 16-gon of inradius d).
Convex inflated(const Convex& c, double d);

// The part of `c` where n·p <= offset (Sutherland-Hodgman on one half-plane).
Convex clip(const Convex& c, const Vec2& n, double offset);

// True when `p` is inside `c` by more than `eps` mm (points on the boundary are not inside).
bool strictly_inside(const Convex& c, const Vec2& p, double eps);

// True when `p` is inside `c` or within `eps` mm of it.
bool inside_or_on(const Convex& c, const Vec2& p, double eps);

struct Box2 {
  Vec2 min{1e300, 1e300}, max{-1e300, -1e300};
  void add(const Vec2& p) { min = min.cwiseMin(p); max = max.cwiseMax(p); }
  void add(const Box2& b) { min = min.cwiseMin(b.min); max = max.cwiseMax(b.max); }
  bool empty() const { return min.x() > max.x(); }
  Vec2 size() const { return max - min; }
  Vec2 center() const { return (min + max) / 2; }
};

Box2 bounds(const Convex& c);

}  // namespace tranche::plate
