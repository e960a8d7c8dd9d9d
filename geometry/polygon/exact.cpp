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

}  // namespace

int orientation_cgal(const Point& a, const Point& b, const Point& c) {
  return sign(CGAL::orientation(cg(a), cg(b), cg(c)));
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
