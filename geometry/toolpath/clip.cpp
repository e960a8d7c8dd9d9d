#include "geometry/toolpath/clip.h"

#include <algorithm>
#include <cmath>

namespace tranche::toolpath {

using ClipperLib::Clipper;
using ClipperLib::ClipperOffset;
using geo::coord_t;
using geo::Rings;

namespace {
constexpr double kArcTolerance = 5000;  // 5 µm

Rings boolean(const Rings& a, const Rings& b, ClipperLib::ClipType op) {
  Rings out;
  if (a.empty() && op != ClipperLib::ctUnion) return out;
  Clipper c;
  c.AddPaths(a, ClipperLib::ptSubject, true);
  c.AddPaths(b, ClipperLib::ptClip, true);
  c.Execute(op, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return out;
}

Rings offset_with(const Rings& region, double mm, double arc_tolerance) {
  Rings out;
  if (region.empty()) return out;
  ClipperOffset co(2.0, arc_tolerance);
  co.AddPaths(region, ClipperLib::jtRound, ClipperLib::etClosedPolygon);
  co.Execute(out, mm * geo::kUnitsPerMm);
  return out;
}
}  // namespace

Rings offset(const Rings& region, double mm) { return offset_with(region, mm, kArcTolerance); }
Rings offset_coarse(const Rings& region, double mm) { return offset_with(region, mm, 25000); }

Rings offset_open(const Rings& region, double mm, double open_mm) {
  return offset(offset(region, mm - open_mm), open_mm);
}

Rings buffer_loops(const Rings& loops, double mm) {
  Rings out;
  if (loops.empty()) return out;
  ClipperOffset co(2.0, kArcTolerance);
  co.AddPaths(loops, ClipperLib::jtRound, ClipperLib::etClosedLine);
  co.Execute(out, mm * geo::kUnitsPerMm);
  return out;
}

Rings intersection(const Rings& a, const Rings& b) {
  if (a.empty() || b.empty()) return {};
  return boolean(a, b, ClipperLib::ctIntersection);
}
Rings difference(const Rings& a, const Rings& b) {
  if (b.empty()) return a;
  return boolean(a, b, ClipperLib::ctDifference);
}
Rings union_of(const Rings& a, const Rings& b) { return boolean(a, b, ClipperLib::ctUnion); }

double area_mm2(const Rings& rings) {
  double a = 0;
  for (const auto& r : rings) a += ClipperLib::Area(r);
  return a * geo::kMmPerUnit * geo::kMmPerUnit;
}

geo::BBox2 bbox(const Rings& rings) {
  geo::BBox2 b;
  for (const auto& r : rings)
    for (const auto& p : r) b.add(p);
  return b;
}

Rings near(const Rings& rings, const geo::BBox2& box) {
  Rings out;
  for (const auto& r : rings) {
    geo::BBox2 rb = geo::bbox(r);
    if (rb.max_x < box.min_x || rb.min_x > box.max_x || rb.max_y < box.min_y || rb.min_y > box.max_y)
      continue;
    out.push_back(r);
  }
  return out;
}

namespace {
// Douglas-Peucker on pts[i..j] (open chain), marking kept vertices.
void dp(const geo::Ring& pts, size_t i, size_t j, double tol2, std::vector<char>& keep) {
  while (j > i + 1) {
    const auto& a = pts[i];
    const auto& b = pts[j % pts.size()];
    double ex = double(b.X - a.X), ey = double(b.Y - a.Y), len2 = ex * ex + ey * ey;
    double best = -1;
    size_t bi = i;
    for (size_t k = i + 1; k < j; ++k) {
      const auto& p = pts[k];
      double d2;
      if (len2 == 0) {
        d2 = double(p.X - a.X) * double(p.X - a.X) + double(p.Y - a.Y) * double(p.Y - a.Y);
      } else {
        double cr = ex * double(p.Y - a.Y) - ey * double(p.X - a.X);
        d2 = cr * cr / len2;
      }
      if (d2 > best) best = d2, bi = k;
    }
    if (best <= tol2) return;
    keep[bi] = 1;
    dp(pts, i, bi, tol2, keep);
    i = bi;
  }
}
}  // namespace

geo::Ring simplify(const geo::Ring& ring, coord_t tol) {
  size_t n = ring.size();
  if (n < 4 || tol <= 0) return ring;
  // Split the loop at vertex 0 and the vertex farthest from it.
  size_t far = 0;
  double best = -1;
  for (size_t k = 1; k < n; ++k) {
    double d = double(ring[k].X - ring[0].X) * double(ring[k].X - ring[0].X) +
               double(ring[k].Y - ring[0].Y) * double(ring[k].Y - ring[0].Y);
    if (d > best) best = d, far = k;
  }
  std::vector<char> keep(n, 0);
  keep[0] = keep[far] = 1;
  double tol2 = double(tol) * double(tol);
  dp(ring, 0, far, tol2, keep);
  dp(ring, far, n, tol2, keep);
  geo::Ring out;
  out.reserve(n);
  for (size_t k = 0; k < n; ++k)
    if (keep[k]) out.push_back(ring[k]);
  if (out.size() < 3) return {};
  return out;
}

Rings simplify(const Rings& rings, coord_t tol) {
  Rings out;
  out.reserve(rings.size());
  for (const auto& r : rings) {
    auto s = simplify(r, tol);
    if (s.size() >= 3) out.push_back(std::move(s));
  }
  return out;
}

Rings convex_hull(geo::Ring pts) {
  if (pts.size() < 3) return {};
  std::sort(pts.begin(), pts.end(), [](const geo::Point& a, const geo::Point& b) {
    return a.X < b.X || (a.X == b.X && a.Y < b.Y);
  });
  auto cross = [](const geo::Point& o, const geo::Point& a, const geo::Point& b) {
    return static_cast<double>(a.X - o.X) * static_cast<double>(b.Y - o.Y) -
           static_cast<double>(a.Y - o.Y) * static_cast<double>(b.X - o.X);
  };
  geo::Ring h(2 * pts.size());
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], pts[i - 1]) <= 0) --k;
    h[k++] = pts[i - 1];
  }
  h.resize(k - 1);
  return {h};
}

geo::Ring offset_polyline(const geo::Ring& pts, bool closed, double mm) {
  const size_t n = pts.size();
  if (n < 2 || mm == 0) return pts;
  const double d = mm * geo::kUnitsPerMm;
  closed = closed && pts.front() == pts.back();
  const size_t m = closed ? n - 1 : n;  // distinct points
  auto normal = [&](size_t i) {         // left normal of segment i -> i+1 (cyclic when closed)
    const geo::Point& a = pts[i % m];
    const geo::Point& b = pts[(i + 1) % (closed ? m : n)];
    double dx = double(b.X - a.X), dy = double(b.Y - a.Y), len = std::hypot(dx, dy);
    return len > 0 ? std::pair<double, double>(-dy / len, dx / len) : std::pair<double, double>(0, 0);
  };
  geo::Ring out(n);
  for (size_t i = 0; i < m; ++i) {
    std::pair<double, double> nin, nout;
    if (closed) {
      nin = normal((i + m - 1) % m);
      nout = normal(i);
    } else {
      nin = normal(i == 0 ? 0 : i - 1);
      nout = normal(i + 1 < n ? i : i - 1);
    }
    double sx = nin.first + nout.first, sy = nin.second + nout.second;
    double dot = 1 + nin.first * nout.first + nin.second * nout.second;  // 1 + cos(turn)
    double k = dot > 0.2 ? d * 2 / dot : d * 10;                         // miter, capped at sharp turns
    out[i] = geo::Point(pts[i].X + std::llround(sx * k * 0.5 * (dot > 0.2 ? 1 : 0.2)),
                        pts[i].Y + std::llround(sy * k * 0.5 * (dot > 0.2 ? 1 : 0.2)));
  }
  if (closed) out[n - 1] = out[0];
  return out;
}

}  // namespace tranche::toolpath
