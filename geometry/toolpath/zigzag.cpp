#include "geometry/toolpath/zigzag.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/toolpath/zigzag_ring.h"

namespace tranche::toolpath {

using geo::coord_t;
using geo::EdgeKind;
using schema::Border;

std::pair<double, double> across_range(const geo::Rings& rings, double angle_deg) {
  const double a = angle_deg * std::numbers::pi / 180.0, c = std::cos(a), s = std::sin(a);
  double lo = 1e300, hi = -1e300;
  for (const auto& r : rings)
    for (const auto& p : r) {
      double v = (-static_cast<double>(p.X) * s + static_cast<double>(p.Y) * c) * geo::kMmPerUnit;
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
  return {lo, hi};
}

SolidGrid region_grid(std::pair<double, double> range, double pitch_mm) {
  double h = range.second - range.first;
  int n = static_cast<int>(std::lround(h / pitch_mm));
  if (n <= 0) return {0.5 * (range.first + range.second), 1e6, 1.0};  // one line, in the middle
  double p = h / n;
  return {range.first, p, p / pitch_mm};
}

FillShape fill_shape(const geo::Rings& rings, EdgeKind kind) {
  FillShape s;
  s.rings = rings;
  for (const auto& r : rings) s.kinds.emplace_back(r.size(), kind);
  return s;
}

namespace {

using zigzag_detail::border_of;
using zigzag_detail::link_along_border;
using zigzag_detail::Poly;
using zigzag_detail::Ring2;
using zigzag_detail::steps;
using zigzag_detail::UV;
using zigzag_detail::walk_ring;

struct Interval {
  double u0, u1;    // left and right ends on the line
  uint32_t r0, r1;  // rings of the left and right ends
  uint32_t e0, e1;  // edges of the left and right ends
};

// Moves every artificial edge inward (to the left) by `d`; vertices go to the intersection of
// their two offset edges, capped at 3·d from where they were.
Ring2 inset(const geo::Ring& ring, const std::vector<EdgeKind>& kinds, double d, double c, double s) {
  Ring2 out;
  size_t n = ring.size();
  std::vector<UV> p;
  std::vector<EdgeKind> k;
  p.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    const auto& a = ring[i];
    if (ring[(i + 1) % n] == a) continue;  // zero-length edge
    double x = static_cast<double>(a.X), y = static_cast<double>(a.Y);
    // Rounded to 1/1024 unit so that rotation noise cannot tilt an edge parallel to the lines.
    p.push_back({std::round((x * c + y * s) * 1024) / 1024, std::round((-x * s + y * c) * 1024) / 1024});
    k.push_back(i < kinds.size() ? kinds[i] : EdgeKind::Real);
  }
  n = p.size();
  out.kinds = k;
  out.pts = p;
  if (n < 3 || d <= 0) return out;
  bool any = std::any_of(k.begin(), k.end(), [](EdgeKind e) { return e == EdgeKind::Artificial; });
  if (!any) return out;
  // Per edge: d·|sin θ| with θ its angle to the lines, so that line ends stop d short of it.
  std::vector<double> dist(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    if (k[i] != EdgeKind::Artificial) continue;
    const UV &a = p[i], &b = p[(i + 1) % n];
    double len = std::hypot(b.u - a.u, b.v - a.v);
    dist[i] = len > 0 ? d * std::abs(b.v - a.v) / len : 0.0;
  }
  for (size_t i = 0; i < n; ++i) {
    size_t ip = (i + n - 1) % n;
    double dp = dist[ip], dn = dist[i];
    if (dp == 0 && dn == 0) continue;
    UV P = p[i], A = p[ip], B = p[(i + 1) % n];
    double tpu = P.u - A.u, tpv = P.v - A.v, lp = std::hypot(tpu, tpv);
    double tnu = B.u - P.u, tnv = B.v - P.v, ln = std::hypot(tnu, tnv);
    tpu /= lp, tpv /= lp, tnu /= ln, tnv /= ln;
    UV a{P.u - tpv * dp, P.v + tpu * dp}, b{P.u - tnv * dn, P.v + tnu * dn};
    double cr = tpu * tnv - tpv * tnu;
    UV q;
    if (std::abs(cr) < 1e-6) {
      q = {0.5 * (a.u + b.u), 0.5 * (a.v + b.v)};
    } else {
      double lam = ((b.u - a.u) * tnv - (b.v - a.v) * tnu) / cr;
      q = {a.u + tpu * lam, a.v + tpv * lam};
    }
    double mu = q.u - P.u, mv = q.v - P.v, m = std::hypot(mu, mv), cap = 3 * d;
    if (m > cap) q = {P.u + mu / m * cap, P.v + mv / m * cap};
    out.pts[i] = q;
  }
  return out;
}

// A crossing of a ring edge with a scan line.
struct Crossing {
  double u;
  uint32_t ring, edge;
};

// Intervals on consecutive lines, linked by connectors along a ring.
struct Run {
  std::vector<Interval> iv;
  size_t last_line;
};

// The phases of zigzag() and what they share: the rotated frame, the inset rings and the scan
// lines.
class Zigzag {
 public:
  explicit Zigzag(const FillSpec& spec)
      : spec_(spec),
        a_(spec.angle_deg * std::numbers::pi / 180.0),
        c_(std::cos(a_)),
        s_(std::sin(a_)),
        pitch_(spec.pitch_mm * geo::kUnitsPerMm),
        d_(spec.artificial_inset_mm * geo::kUnitsPerMm),
        limit_(spec.link_max_mm * geo::kUnitsPerMm) {}

  // The fill paths of `shape`.
  std::vector<FillPath> run(const FillShape& shape);

 private:
  bool inset_rings(const FillShape& shape);
  bool place_lines();
  std::vector<std::vector<Crossing>> crossings() const;
  bool walk_ok(const Interval& from, const Interval& to, bool right, double v0, double v1) const;
  std::vector<Run> link_runs(std::vector<std::vector<Crossing>>& hits) const;
  Poly to_poly(const Run& run) const;
  std::vector<FillPath> to_paths(const std::vector<Poly>& chains) const;

  const FillSpec& spec_;
  const double a_, c_, s_;  // the fill angle (radians), its cosine and sine
  const double pitch_;      // units
  const double d_;          // inset of artificial edges, units
  const double limit_;      // longest link, units
  std::vector<Ring2> rings_;
  double vmin_ = 1e300, vmax_ = -1e300;  // extent of the rings across the lines, units
  std::vector<double> lines_;            // scan line positions (v), ascending
};

// The shape's rings inset and rotated into the line frame, and their extent across the lines;
// false when nothing is left to fill.
bool Zigzag::inset_rings(const FillShape& shape) {
  for (size_t r = 0; r < shape.rings.size(); ++r) {
    static const std::vector<EdgeKind> kNone;
    Ring2 r2 = inset(shape.rings[r], r < shape.kinds.size() ? shape.kinds[r] : kNone, d_, c_, s_);
    if (r2.pts.size() < 3) continue;
    for (const auto& p : r2.pts) vmin_ = std::min(vmin_, p.v), vmax_ = std::max(vmax_, p.v);
    rings_.push_back(std::move(r2));
  }
  return !(rings_.empty() || vmax_ <= vmin_);
}

// Scan line positions (v), ascending, on the grid origin + k·pitch; false when there are none.
bool Zigzag::place_lines() {
  const double delta = 1.0;  // 1 nm inside the extremes, off the extreme vertices
  const double origin = spec_.origin_mm * geo::kUnitsPerMm;
  // Lines within a few nm of the extremes (a grid line on the region's border) move just inside.
  for (double k = std::ceil((vmin_ - 4 * delta - origin) / pitch_); origin + k * pitch_ <= vmax_ + 4 * delta;
       k += 1)
    lines_.push_back(std::clamp(origin + k * pitch_, vmin_ + delta, vmax_ - delta));
  lines_.erase(std::unique(lines_.begin(), lines_.end()), lines_.end());
  return !lines_.empty();
}

// Crossings of every edge with the lines, bucketed per line (half-open in v).
std::vector<std::vector<Crossing>> Zigzag::crossings() const {
  std::vector<std::vector<Crossing>> hits(lines_.size());
  for (uint32_t r = 0; r < rings_.size(); ++r) {
    const auto& pts = rings_[r].pts;
    size_t n = pts.size();
    for (uint32_t i = 0; i < n; ++i) {
      UV p = pts[i], q = pts[(i + 1) % n];
      if (p.v == q.v) continue;
      double lo = std::min(p.v, q.v), hi = std::max(p.v, q.v);
      auto it = std::lower_bound(lines_.begin(), lines_.end(), lo);
      for (; it != lines_.end() && *it < hi; ++it) {
        double u = p.u + (*it - p.v) * (q.u - p.u) / (q.v - p.v);
        hits[static_cast<size_t>(it - lines_.begin())].push_back({u, r, i});
      }
    }
  }
  return hits;
}

// Whether the connector from `from` (line v0) to `to` (line v1) along their ring, on the right
// or left ends, stays between the two lines.
bool Zigzag::walk_ok(const Interval& from, const Interval& to, bool right, double v0, double v1) const {
  uint32_t ring = right ? from.r1 : from.r0;
  if (ring != (right ? to.r1 : to.r0)) return false;
  const auto& pts = rings_[ring].pts;
  uint32_t n = static_cast<uint32_t>(pts.size());
  uint32_t e_from = right ? from.e1 : from.e0, e_to = right ? to.e1 : to.e0;
  return walk_ring(n, e_from, steps(n, e_from, e_to, right), right,
                   [&](uint32_t v, uint32_t) { return pts[v].v >= v0 - 1 && pts[v].v <= v1 + 1; });
}

// Runs of intervals on consecutive lines, linked by connectors along a ring (sorts `hits`).
std::vector<Run> Zigzag::link_runs(std::vector<std::vector<Crossing>>& hits) const {
  std::vector<Run> runs;
  std::vector<size_t> open;  // runs that ended on the previous line
  for (size_t li = 0; li < lines_.size(); ++li) {
    auto& h = hits[li];
    std::sort(h.begin(), h.end(), [](const Crossing& x, const Crossing& y) { return x.u < y.u; });
    std::vector<size_t> next_open;
    std::vector<char> taken(open.size(), 0);
    for (size_t j = 0; j + 1 < h.size(); j += 2) {
      Interval iv{h[j].u, h[j + 1].u, h[j].ring, h[j + 1].ring, h[j].edge, h[j + 1].edge};
      bool linked = false;
      for (size_t o = 0; o < open.size() && !linked; ++o) {
        if (taken[o]) continue;
        Run& run = runs[open[o]];
        const Interval& prev = run.iv.back();
        bool right = run.iv.size() % 2 == 1;  // odd count: the last line ran left to right
        if (!walk_ok(prev, iv, right, lines_[li - 1], lines_[li])) continue;
        run.iv.push_back(iv);
        run.last_line = li;
        taken[o] = 1;
        next_open.push_back(open[o]);
        linked = true;
      }
      if (!linked) {
        runs.push_back({{iv}, li});
        next_open.push_back(runs.size() - 1);
      }
    }
    open = std::move(next_open);
  }
  return runs;
}

// A run as a polyline in the rotated frame: each end remembers the ring edge it lies on.
Poly Zigzag::to_poly(const Run& run) const {
  Poly P;
  auto add = [&](UV p, Border b) {
    if (!P.pts.empty()) P.border.push_back(b);
    P.pts.push_back(p);
  };
  size_t li0 = run.last_line + 1 - run.iv.size();
  for (size_t k = 0; k < run.iv.size(); ++k) {
    const Interval& iv = run.iv[k];
    double v = lines_[li0 + k];
    bool ltr = k % 2 == 0;
    UV first{ltr ? iv.u0 : iv.u1, v}, last{ltr ? iv.u1 : iv.u0, v};
    add(first, k == 0 ? Border::None : border_of(rings_[ltr ? iv.r0 : iv.r1].kinds[ltr ? iv.e0 : iv.e1]));
    add(last, Border::None);
    P.area += (iv.u1 - iv.u0) * pitch_;
    if (k == 0) P.first = {ltr ? iv.r0 : iv.r1, ltr ? iv.e0 : iv.e1, first};
    if (k + 1 == run.iv.size()) {
      P.last = {ltr ? iv.r1 : iv.r0, ltr ? iv.e1 : iv.e0, last};
      break;
    }
    // Connector from this line's end to the next line's start, along the ring.
    const Interval& nx = run.iv[k + 1];
    const auto& ring = rings_[ltr ? iv.r1 : iv.r0];
    uint32_t n = static_cast<uint32_t>(ring.pts.size());
    uint32_t e_from = ltr ? iv.e1 : iv.e0, e_to = ltr ? nx.e1 : nx.e0;
    walk_ring(n, e_from, steps(n, e_from, e_to, ltr), ltr, [&](uint32_t vi, uint32_t edge) {
      add(ring.pts[vi], border_of(ring.kinds[edge]));
      return true;
    });
  }
  return P;
}

// Polylines to paths in bed coordinates (points that round together merged).
std::vector<FillPath> Zigzag::to_paths(const std::vector<Poly>& chains) const {
  return zigzag_detail::to_fill_paths(chains, [&](UV p) {
    return geo::Point(static_cast<coord_t>(std::llround(p.u * c_ - p.v * s_)),
                      static_cast<coord_t>(std::llround(p.u * s_ + p.v * c_)));
  });
}

// Inset rings, scan lines, crossings, runs, polylines, links along the border, paths.
std::vector<FillPath> Zigzag::run(const FillShape& shape) {
  if (!(pitch_ > 0)) return {};
  if (!inset_rings(shape) || !place_lines()) return {};
  std::vector<std::vector<Crossing>> hits = crossings();
  std::vector<Run> runs = link_runs(hits);
  std::vector<Poly> polys;
  polys.reserve(runs.size());
  for (const auto& run : runs) polys.push_back(to_poly(run));
  return to_paths(link_along_border(std::move(polys), rings_, limit_));
}

}  // namespace

std::vector<FillPath> zigzag(const FillShape& shape, const FillSpec& spec) { return Zigzag(spec).run(shape); }

}  // namespace tranche::toolpath
