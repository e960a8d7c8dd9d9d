#include "geometry/polygon/exact.h"

#include <CGAL/Cartesian.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/MP_Float.h>
#include <CGAL/Quotient.h>
#include <CGAL/Snap_rounding_2.h>
#include <CGAL/Snap_rounding_traits_2.h>

#include <cmath>
#include <list>

namespace tranche::geo::exact {
namespace {

// Filtered exact predicates: doubles hold our integer coordinates exactly, and the kernel falls
// back to exact arithmetic whenever the interval filter cannot decide a sign.
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

K::Point_2 cg(const Point& p) { return {static_cast<double>(p.X), static_cast<double>(p.Y)}; }

int sign(CGAL::Orientation o) { return o == CGAL::LEFT_TURN ? 1 : o == CGAL::RIGHT_TURN ? -1 : 0; }

// Lexicographic order: the order along the line for collinear points.
bool lex_less(const Point& a, const Point& b) { return a.X < b.X || (a.X == b.X && a.Y < b.Y); }

}  // namespace

int orientation(const Point& a, const Point& b, const Point& c) {
  return sign(CGAL::orientation(cg(a), cg(b), cg(c)));
}

bool strictly_between(const Point& a, const Point& p, const Point& b) {
  // CGAL's ordering test assumes collinear points; check that first.
  const auto pa = cg(a), pp = cg(p), pb = cg(b);
  return CGAL::collinear(pa, pp, pb) && CGAL::collinear_are_strictly_ordered_along_line(pa, pp, pb);
}

Contact contact(const Point& a, const Point& b, const Point& c, const Point& d) {
  const int o1 = orientation(a, b, c), o2 = orientation(a, b, d);
  if (o1 * o2 > 0) return Contact::None;
  const int o3 = orientation(c, d, a), o4 = orientation(c, d, b);
  if (o3 * o4 > 0) return Contact::None;
  if (o1 == 0 && o2 == 0) {
    // Collinear: compare the two intervals along the line (lexicographic order is the line order).
    Point lo1 = a, hi1 = b, lo2 = c, hi2 = d;
    if (lex_less(hi1, lo1)) std::swap(lo1, hi1);
    if (lex_less(hi2, lo2)) std::swap(lo2, hi2);
    const Point& lo = lex_less(lo1, lo2) ? lo2 : lo1;
    const Point& hi = lex_less(hi1, hi2) ? hi1 : hi2;
    if (lex_less(hi, lo)) return Contact::None;
    return lo == hi ? Contact::Touch : Contact::Overlap;
  }
  if (o1 != 0 && o2 != 0 && o3 != 0 && o4 != 0) return Contact::Cross;
  return Contact::Touch;
}

bool angle_less(const Point& o, const Point& u, const Point& v) {
  // Half 0: directions in [0, pi) from +x; half 1: [pi, 2 pi). Within a half a cross product decides.
  auto half = [&](const Point& p) { return (p.Y > o.Y || (p.Y == o.Y && p.X > o.X)) ? 0 : 1; };
  const int hu = half(u), hv = half(v);
  if (hu != hv) return hu < hv;
  return orientation(o, u, v) > 0;
}

Rings snap_round(const Rings& rings) {
  // Snap rounding constructs intersection points, so it needs an exact-constructions kernel.
  using SK = CGAL::Cartesian<CGAL::Quotient<CGAL::MP_Float>>;
  using Traits = CGAL::Snap_rounding_traits_2<SK>;
  std::list<SK::Segment_2> segments;
  std::vector<size_t> sizes;
  for (const Ring& input : rings) {
    Ring r;  // zero-length segments upset the snap rounding
    for (const Point& p : input) {
      if (r.empty() || !(r.back() == p)) r.push_back(p);
    }
    while (r.size() > 1 && r.front() == r.back()) r.pop_back();
    if (r.size() < 2) continue;
    sizes.push_back(r.size());
    for (size_t i = 0; i < r.size(); ++i) {
      const Point& a = r[i];
      const Point& b = r[(i + 1) % r.size()];
      segments.emplace_back(SK::Point_2(static_cast<double>(a.X), static_cast<double>(a.Y)),
                            SK::Point_2(static_cast<double>(b.X), static_cast<double>(b.Y)));
    }
  }
  std::list<std::list<SK::Point_2>> polylines;
  // Pixel size 1 with integer output: pixel [k, k+1) maps to k, so integer vertices stay put.
  CGAL::snap_rounding_2<Traits>(segments.begin(), segments.end(), polylines, 1.0, true, true, 1);
  Rings out;
  auto it = polylines.begin();
  for (size_t n : sizes) {
    Ring ring;
    for (size_t i = 0; i < n; ++i, ++it) {
      for (auto p = it->begin(); p != it->end(); ++p) {
        if (std::next(p) == it->end()) break;  // the next polyline starts there
        const Point q(std::llround(CGAL::to_double(p->x())), std::llround(CGAL::to_double(p->y())));
        if (ring.empty() || !(ring.back() == q)) ring.push_back(q);
      }
    }
    while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
    out.push_back(std::move(ring));
  }
  return out;
}

}  // namespace tranche::geo::exact
