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
// Offsets first drop the vertices of their input that lie within this of the chord of their
// neighbours (a tenth of the arc tolerance, below the G-code's resolution). Booleans and earlier
// offsets leave runs of vertices a few µm apart turning by noise; moved by a millimetre, each
// such turn that closes is a detour through the vertex crossing its neighbours', and the union
// that cleans the raw curve spent nearly all of its time on them (a skin grown by a bead and a
// quarter on the bunny: 160 ms, 12 ms with this).
constexpr geo::coord_t kInputTolerance = 500;  // 0.5 µm

Rings boolean(const Rings& a, const Rings& b, ClipperLib::ClipType op) {
  Rings out;
  if (a.empty() && op != ClipperLib::ctUnion) return out;
  Clipper c;
  c.AddPaths(a, ClipperLib::ptSubject, true);
  c.AddPaths(b, ClipperLib::ptClip, true);
  c.Execute(op, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return out;
}

// The raw offset curve of one closed ring by `delta` units (> 0: to the right of travel, out of
// a counter-clockwise outer), for a positive-winding union to clean: each edge moved along its
// normal, round joins where the offset opens (arcs to `steps_per_rad`), and where it closes
// (the two moved edges overlap) the point where they cross when it lies within half of each,
// else a detour through the vertex, whose loop the union drops. Clipper's own ClipperOffset
// takes that detour at every closing vertex: on outlines sliced from curved meshes (most
// vertices) it triples the points and makes every detour cross its neighbours, which was most of
// the union's time.
// Where the offset opens by so small a turn that the mitre point lies within `mitre_tol` units
// outside the arc, that one point is the join (a curved outline's vertices would each leave two
// points a few µm apart, for every later boolean and offset to carry).
void raw_offset(const geo::Ring& ring, double delta, double steps_per_rad, double mitre_tol, Rings& out) {
  // Consecutive duplicates carry no direction.
  geo::Ring p;
  p.reserve(ring.size());
  for (const auto& q : ring)
    if (p.empty() || q != p.back()) p.push_back(q);
  while (p.size() > 1 && p.front() == p.back()) p.pop_back();
  const size_t n = p.size();
  if (n < 3) return;
  struct Normal {
    double x, y, len;
  };
  std::vector<Normal> nrm(n);  // nrm[i]: edge p[i] → p[i + 1]
  for (size_t i = 0; i < n; ++i) {
    const geo::Point& a = p[i];
    const geo::Point& b = p[(i + 1) % n];
    const double dx = double(b.X - a.X), dy = double(b.Y - a.Y), len = std::sqrt(dx * dx + dy * dy);
    nrm[i] = {dy / len, -dx / len, len};
  }
  // Joins whose turn needs no point between the two ends (one chord is within tolerance).
  const double one_step = 1.5 / steps_per_rad;
  const double cos_one_step = std::cos(one_step);
  geo::Ring r;
  r.reserve(n + n / 4 + 8);
  auto at = [&](const geo::Point& v, double nx, double ny) {
    r.emplace_back(static_cast<geo::coord_t>(std::llround(double(v.X) + nx * delta)),
                   static_cast<geo::coord_t>(std::llround(double(v.Y) + ny * delta)));
  };
  for (size_t j = 0; j < n; ++j) {
    const size_t k = j == 0 ? n - 1 : j - 1;  // edge k enters vertex j, edge j leaves it
    const Normal& a = nrm[k];
    const Normal& b = nrm[j];
    const geo::Point& v = p[j];
    const double sin_a = std::clamp(a.x * b.y - b.x * a.y, -1.0, 1.0);
    const double cos_a = a.x * b.x + a.y * b.y;
    if (std::abs(sin_a * delta) < 1.0 && cos_a > 0) {  // straight on, to within a unit
      at(v, a.x, a.y);
      continue;
    }
    if (sin_a * delta < 0) {  // the moved edges overlap
      if (cos_a > 0) {
        // From each end to the crossing: within half of each edge, so that what is left of
        // every moved edge runs forward (a curve tighter than the offset turns them back, and
        // the crossings would trace a spurious loop: a disc shrunk past its radius).
        const double back = std::abs(delta) * std::abs(sin_a) / (1 + cos_a);
        if (2 * back <= a.len && 2 * back <= b.len) {
          const double f = 1 / (1 + cos_a);
          at(v, (a.x + b.x) * f, (a.y + b.y) * f);
          continue;
        }
      }
      at(v, a.x, a.y);
      r.push_back(v);
      at(v, b.x, b.y);
      continue;
    }
    // Round join from a to b; a mitre when it lies within mitre_tol of the arc:
    // |delta| (1 / cos(turn / 2) − 1) ≤ mitre_tol.
    if (cos_a > 0 && std::abs(delta) <= (mitre_tol + std::abs(delta)) * std::sqrt(0.5 * (1 + cos_a))) {
      const double f = 1 / (1 + cos_a);
      at(v, (a.x + b.x) * f, (a.y + b.y) * f);
      continue;
    }
    at(v, a.x, a.y);
    if (cos_a < cos_one_step) {
      const double turn = std::atan2(sin_a, cos_a);
      const int steps = std::max(static_cast<int>(std::lround(steps_per_rad * std::abs(turn))), 1);
      const double c = std::cos(turn / steps), s = std::sin(turn / steps);
      double x = a.x, y = a.y;
      for (int i = 1; i < steps; ++i) {
        const double x2 = x * c - y * s;
        y = x * s + y * c;
        x = x2;
        at(v, x, y);
      }
    }
    at(v, b.x, b.y);
  }
  out.push_back(std::move(r));
}

Rings offset_with(const Rings& region, double mm, double arc_tolerance) {
  Rings out;
  if (region.empty()) return out;
  const double delta = mm * geo::kUnitsPerMm;
  const double ad = std::abs(delta);
  // Rings are counter-clockwise outers and clockwise holes; if the outermost is not, the whole
  // list is the other way round (as Clipper's offset assumes too). The result is oriented as
  // usual either way.
  const geo::Ring* lowest = nullptr;
  geo::coord_t low_y = 0, low_x = 0;
  for (const auto& r : region)
    for (const auto& q : r)
      if (!lowest || q.Y > low_y || (q.Y == low_y && q.X < low_x)) lowest = &r, low_y = q.Y, low_x = q.X;
  const bool flip = lowest && !ClipperLib::Orientation(*lowest);
  Rings raw;
  raw.reserve(region.size());
  if (ad < 1.0) {  // no offset: the rings themselves, turned the usual way round, united
    for (const auto& r : region)
      if (r.size() >= 3) raw.push_back(flip ? geo::Ring(r.rbegin(), r.rend()) : r);
  } else {
    double tol = arc_tolerance > 0 ? std::min(arc_tolerance, 0.25 * ad) : 0.25 * ad;
    double steps = M_PI / std::acos(1 - tol / ad);  // per full turn
    steps = std::min(steps, ad * M_PI);
    const double steps_per_rad = steps / (2 * M_PI);
    for (const auto& r : region) {
      geo::Ring clean = delta > 0 ? simplify(r, kInputTolerance) : r;
      if (clean.empty()) clean = r;
      if (flip) std::reverse(clean.begin(), clean.end());
      raw_offset(clean, delta, steps_per_rad, 0.2 * tol, raw);
    }
  }
  if (raw.empty()) return out;
  Clipper c;
  c.AddPaths(raw, ClipperLib::ptSubject, true);
  if (delta > 0) {
    c.Execute(ClipperLib::ctUnion, out, ClipperLib::pftPositive, ClipperLib::pftPositive);
  } else {
    // Shrinking: the raw curves reversed inside a frame, whose negative winding is the result
    // (the frame comes out first).
    const ClipperLib::IntRect b = c.GetBounds();
    geo::Ring frame{{b.left - 10, b.bottom + 10}, {b.right + 10, b.bottom + 10}, {b.right + 10, b.top - 10},
                    {b.left - 10, b.top - 10}};
    c.AddPath(frame, ClipperLib::ptSubject, true);
    c.ReverseSolution(true);
    c.Execute(ClipperLib::ctUnion, out, ClipperLib::pftNegative, ClipperLib::pftNegative);
    if (!out.empty()) out.erase(out.begin());
  }
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
