// The exact offset of a region, judged point by point, for the offset tests: neither Clipper nor
// toolpath::offset is used to decide what is right.
//
// A region is the set of points whose winding number in its rings is non-zero (or positive).
// Grown by d it is the set of points within d of it (Minkowski sum with a disc); shrunk by d, the
// points whose d-disc lies inside it. Both follow from the distance to the region's boundary,
// which is found here exactly: every edge is cut where another edge crosses or touches it, and
// each piece is boundary when the winding just to its left and just to its right differ in
// being inside (pieces of zero width, such as a spike that goes out and back along itself, have
// the region on neither side and are not boundary).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "fixtures.h"
#include "geometry/core/geom.h"

namespace tranche::test {

class ExactRegion {
 public:
  explicit ExactRegion(const geo::Rings& rings, bool positive = false) : rings_(rings), positive_(positive) {
    struct E {
      geo::Point a, b;
    };
    std::vector<E> edges;
    for (const auto& r : rings)
      for (size_t i = 0; i < r.size(); ++i)
        if (r[i] != r[(i + 1) % r.size()]) edges.push_back({r[i], r[(i + 1) % r.size()]});
    __extension__ typedef __int128 W;
    auto cross = [](const geo::Point& o, const geo::Point& a, const geo::Point& b) {
      const W v = W(a.X - o.X) * W(b.Y - o.Y) - W(a.Y - o.Y) * W(b.X - o.X);
      return v > 0 ? 1 : v < 0 ? -1 : 0;
    };
    // Where along a→b (0..1) the point q lies, q on the line.
    auto along = [](const geo::Point& a, const geo::Point& b, const geo::Point& q) {
      const long double dx = b.X - a.X, dy = b.Y - a.Y;
      return ((q.X - a.X) * dx + (q.Y - a.Y) * dy) / (dx * dx + dy * dy);
    };
    std::vector<std::vector<long double>> cuts(edges.size());
    for (size_t i = 0; i < edges.size(); ++i) {
      for (size_t j = i + 1; j < edges.size(); ++j) {
        const E &e = edges[i], &f = edges[j];
        if (std::max(e.a.X, e.b.X) < std::min(f.a.X, f.b.X) || std::max(f.a.X, f.b.X) < std::min(e.a.X, e.b.X) ||
            std::max(e.a.Y, e.b.Y) < std::min(f.a.Y, f.b.Y) || std::max(f.a.Y, f.b.Y) < std::min(e.a.Y, e.b.Y))
          continue;
        const int d1 = cross(f.a, f.b, e.a), d2 = cross(f.a, f.b, e.b), d3 = cross(e.a, e.b, f.a),
                  d4 = cross(e.a, e.b, f.b);
        if (d1 * d2 < 0 && d3 * d4 < 0) {  // a proper crossing
          const long double ex = e.b.X - e.a.X, ey = e.b.Y - e.a.Y, fx = f.b.X - f.a.X, fy = f.b.Y - f.a.Y;
          const long double den = ex * fy - ey * fx;
          const long double wx = f.a.X - e.a.X, wy = f.a.Y - e.a.Y;
          cuts[i].push_back((wx * fy - wy * fx) / den);
          cuts[j].push_back((wx * ey - wy * ex) / den);
          continue;
        }
        // An end of one on the other (touching, or collinear overlap).
        auto on = [&](const E& s, const geo::Point& q, int side, std::vector<long double>& c) {
          if (side != 0) return;
          const long double t = along(s.a, s.b, q);
          if (t > 0 && t < 1) c.push_back(t);
        };
        on(f, e.a, d1, cuts[j]);
        on(f, e.b, d2, cuts[j]);
        on(e, f.a, d3, cuts[i]);
        on(e, f.b, d4, cuts[i]);
      }
    }
    for (size_t i = 0; i < edges.size(); ++i) {
      auto& c = cuts[i];
      c.push_back(0);
      c.push_back(1);
      std::sort(c.begin(), c.end());
      const E& e = edges[i];
      const long double dx = e.b.X - e.a.X, dy = e.b.Y - e.a.Y, len = std::sqrt(dx * dx + dy * dy);
      for (size_t k = 0; k + 1 < c.size(); ++k) {
        if (c[k + 1] - c[k] <= 0) continue;
        const long double ax = e.a.X + dx * c[k], ay = e.a.Y + dy * c[k];
        const long double bx = e.a.X + dx * c[k + 1], by = e.a.Y + dy * c[k + 1];
        const long double mx = (ax + bx) / 2, my = (ay + by) / 2;
        // A step aside far below a unit: no other edge passes between the piece and the probe
        // (edges have integer ends; pieces shorter than that are left to their neighbours).
        const long double piece = len * (c[k + 1] - c[k]);
        if (piece < 1e-3) continue;
        const long double eps = std::min<long double>(1e-3, piece * 1e-3);
        const long double nx = -dy / len * eps, ny = dx / len * eps;
        if (in(winding(mx + nx, my + ny)) != in(winding(mx - nx, my - ny)))
          boundary_.push_back({double(ax), double(ay), double(bx), double(by)});
      }
    }
  }

  // Whether (x, y) (units) is in the region.
  bool inside(double x, double y) const { return in(winding(x, y)); }

  // The distance (units) from (x, y) to the region's boundary.
  double distance(double x, double y) const {
    double best = std::numeric_limits<double>::infinity();
    for (const Seg& s : boundary_) {
      const double ex = s.bx - s.ax, ey = s.by - s.ay, l2 = ex * ex + ey * ey;
      const double t = l2 > 0 ? std::clamp(((x - s.ax) * ex + (y - s.ay) * ey) / l2, 0.0, 1.0) : 0;
      const double qx = s.ax + t * ex - x, qy = s.ay + t * ey - y;
      best = std::min(best, qx * qx + qy * qy);
    }
    return std::sqrt(best);
  }

  // Whether (x, y) is in the region offset by `delta` units (grown > 0, shrunk < 0), and whether
  // it lies farther than `band` units from the offset's border (else `clear` is false: within the
  // arcs' tolerance either answer is right).
  bool in_offset(double x, double y, double delta, double band, bool& clear) const {
    const bool inner = inside(x, y);
    const double dist = distance(x, y);
    if (delta >= 0) {
      clear = inner ? dist > band - delta : std::abs(dist - delta) > band;
      return inner || dist <= delta;
    }
    clear = inner ? std::abs(dist + delta) > band : dist > band + delta;
    return inner && dist >= -delta;
  }

  size_t boundary_pieces() const { return boundary_.size(); }

  // The winding number of (x, y) in `rings` (any point not on an edge).
  static int winding_in(const geo::Rings& rings, long double x, long double y) {
    int w = 0;
    for (const auto& r : rings)
      for (size_t i = 0; i < r.size(); ++i) {
        const geo::Point& a = r[i];
        const geo::Point& b = r[(i + 1) % r.size()];
        const long double c = (b.X - a.X) * (y - a.Y) - (b.Y - a.Y) * (x - a.X);
        if (a.Y <= y) {
          if (b.Y > y && c > 0) ++w;
        } else if (b.Y <= y && c < 0) {
          --w;
        }
      }
    return w;
  }

 private:
  struct Seg {
    double ax, ay, bx, by;
  };
  bool in(int w) const { return positive_ ? w > 0 : w != 0; }
  int winding(long double x, long double y) const { return winding_in(rings_, x, y); }

  geo::Rings rings_;
  bool positive_;
  std::vector<Seg> boundary_;
};

// How a computed offset compares with the exact one: sample points, those decided (farther than
// the band from the exact border) and, of those, the ones the offset puts on the wrong side
// (`missing`: in the exact offset, not in the computed one; `extra`: the reverse).
struct OffsetCheck {
  int samples = 0, decided = 0, missing = 0, extra = 0;
  double area_per_sample = 0;  // mm² each sample stands for
  double wrong_mm2() const { return (missing + extra) * area_per_sample; }
};

// `samples` points spread evenly (a jittered grid from `seed`) over `box` (units), each judged in
// `computed` (non-zero fill) against `exact` offset by `mm`, with a band of `band_mm`.
inline OffsetCheck check_offset(const ExactRegion& exact, const geo::Rings& computed, double mm, const geo::BBox2& box,
                                int samples, uint32_t seed, double band_mm = 0.008) {
  OffsetCheck out;
  const int side = std::max(1, static_cast<int>(std::sqrt(double(samples))));
  const double w = double(box.max_x - box.min_x), h = double(box.max_y - box.min_y);
  out.area_per_sample = w * h * geo::kMmPerUnit * geo::kMmPerUnit / (side * side);
  Lcg rnd{seed};
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      // Half a unit off the grid of integer coordinates: never on an edge's end.
      const double x = std::floor(box.min_x + w * (i + rnd()) / side) + 0.5;
      const double y = std::floor(box.min_y + h * (j + rnd()) / side) + 0.5;
      ++out.samples;
      bool clear = false;
      const bool want = exact.in_offset(x, y, mm * geo::kUnitsPerMm, band_mm * geo::kUnitsPerMm, clear);
      if (!clear) continue;
      ++out.decided;
      const bool got = ExactRegion::winding_in(computed, x, y) != 0;
      if (want && !got) ++out.missing;
      if (got && !want) ++out.extra;
    }
  return out;
}

}  // namespace tranche::test
