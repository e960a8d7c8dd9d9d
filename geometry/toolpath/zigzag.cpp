#include "geometry/toolpath/zigzag.h"

#include <algorithm>
#include <cmath>
#include <numbers>

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

struct UV {
  double u, v;
};

struct Ring2 {
  std::vector<UV> pts;          // inset vertices in the rotated frame (units)
  std::vector<EdgeKind> kinds;  // per edge
};

struct Interval {
  double u0, u1;    // left and right ends on the line
  uint32_t r0, r1;  // rings of the left and right ends
  uint32_t e0, e1;  // edges of the left and right ends
};

// Walking round a ring of n vertices from a point on edge `from` (forward: increasing indices),
// `count` vertices: calls f(vertex, edge just walked along) for each, and stops early, returning
// false, when f does. `steps` counts the vertices between a point on edge `from` and one on edge
// `to` (0 on the same edge).
uint32_t steps(uint32_t n, uint32_t from, uint32_t to, bool forward) {
  return forward ? (to + n - from) % n : (from + n - to) % n;
}
template <class F>
bool walk_ring(uint32_t n, uint32_t from, uint32_t count, bool forward, F&& f) {
  for (uint32_t k = 0; k < count; ++k) {
    uint32_t v = forward ? (from + 1 + k) % n : (from + n - k) % n;
    if (!f(v, forward ? (v + n - 1) % n : v)) return false;
  }
  return true;
}

Border border_of(EdgeKind k) { return k == EdgeKind::Real ? Border::Real : Border::Artificial; }

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

}  // namespace

std::vector<FillPath> zigzag(const FillShape& shape, const FillSpec& spec) {
  std::vector<FillPath> out;
  const double a = spec.angle_deg * std::numbers::pi / 180.0;
  const double c = std::cos(a), s = std::sin(a);
  const double pitch = spec.pitch_mm * geo::kUnitsPerMm;
  if (!(pitch > 0)) return out;
  const double d = spec.artificial_inset_mm * geo::kUnitsPerMm;

  std::vector<Ring2> rings;
  double vmin = 1e300, vmax = -1e300;
  for (size_t r = 0; r < shape.rings.size(); ++r) {
    static const std::vector<EdgeKind> kNone;
    Ring2 r2 = inset(shape.rings[r], r < shape.kinds.size() ? shape.kinds[r] : kNone, d, c, s);
    if (r2.pts.size() < 3) continue;
    for (const auto& p : r2.pts) vmin = std::min(vmin, p.v), vmax = std::max(vmax, p.v);
    rings.push_back(std::move(r2));
  }
  if (rings.empty() || vmax <= vmin) return out;

  // Scan line positions (v), ascending, on the grid origin + k·pitch.
  std::vector<double> lines;
  const double delta = 1.0;  // 1 nm inside the extremes, off the extreme vertices
  const double origin = spec.origin_mm * geo::kUnitsPerMm;
  // Lines within a few nm of the extremes (a grid line on the region's border) move just inside.
  for (double k = std::ceil((vmin - 4 * delta - origin) / pitch); origin + k * pitch <= vmax + 4 * delta;
       k += 1)
    lines.push_back(std::clamp(origin + k * pitch, vmin + delta, vmax - delta));
  lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
  if (lines.empty()) return out;

  // Crossings of every edge with the lines, bucketed per line (half-open in v).
  struct X {
    double u;
    uint32_t ring, edge;
  };
  std::vector<std::vector<X>> hits(lines.size());
  for (uint32_t r = 0; r < rings.size(); ++r) {
    const auto& pts = rings[r].pts;
    size_t n = pts.size();
    for (uint32_t i = 0; i < n; ++i) {
      UV p = pts[i], q = pts[(i + 1) % n];
      if (p.v == q.v) continue;
      double lo = std::min(p.v, q.v), hi = std::max(p.v, q.v);
      auto it = std::lower_bound(lines.begin(), lines.end(), lo);
      for (; it != lines.end() && *it < hi; ++it) {
        double u = p.u + (*it - p.v) * (q.u - p.u) / (q.v - p.v);
        hits[static_cast<size_t>(it - lines.begin())].push_back({u, r, i});
      }
    }
  }

  // Runs of intervals on consecutive lines, linked by connectors along a ring.
  struct Run {
    std::vector<Interval> iv;
    size_t last_line;
  };
  std::vector<Run> runs;
  std::vector<size_t> open;  // runs that ended on the previous line
  auto walk_ok = [&](const Interval& from, const Interval& to, bool right, double v0, double v1) {
    uint32_t ring = right ? from.r1 : from.r0;
    if (ring != (right ? to.r1 : to.r0)) return false;
    const auto& pts = rings[ring].pts;
    uint32_t n = static_cast<uint32_t>(pts.size());
    uint32_t e_from = right ? from.e1 : from.e0, e_to = right ? to.e1 : to.e0;
    return walk_ring(n, e_from, steps(n, e_from, e_to, right), right,
                     [&](uint32_t v, uint32_t) { return pts[v].v >= v0 - 1 && pts[v].v <= v1 + 1; });
  };
  for (size_t li = 0; li < lines.size(); ++li) {
    auto& h = hits[li];
    std::sort(h.begin(), h.end(), [](const X& x, const X& y) { return x.u < y.u; });
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
        if (!walk_ok(prev, iv, right, lines[li - 1], lines[li])) continue;
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

  // Runs to polylines, still in the rotated frame: each end remembers the ring edge it lies on.
  struct End {
    uint32_t ring, edge;
    UV p;
  };
  struct Poly {
    std::vector<UV> pts;
    std::vector<Border> border;  // per piece
    End first, last;
    double area = 0;  // units²
    int runs = 1;
  };
  // Stretches of each ring that links lie on, as (start, length) in arc length from the ring's
  // vertex 0, forward: a link may not run over another one. (It may run over the lines' own
  // connectors, as PrusaSlicer's infill anchors do: along the island's border a solid link and
  // connector are both laid at half flow.)
  const double limit = spec.link_max_mm * geo::kUnitsPerMm;
  struct Stretch {
    double start, len;
  };
  std::vector<std::vector<double>> cum(rings.size());  // arc length at each vertex, then the total
  std::vector<std::vector<Stretch>> covered(rings.size());
  if (limit > 0)
    for (size_t r = 0; r < rings.size(); ++r) {
      const auto& pts = rings[r].pts;
      cum[r].assign(1, 0.0);
      for (size_t i = 0; i < pts.size(); ++i) {
        const UV &p0 = pts[i], &p1 = pts[(i + 1) % pts.size()];
        cum[r].push_back(cum[r].back() + std::hypot(p1.u - p0.u, p1.v - p0.v));
      }
    }
  auto param = [&](uint32_t r, uint32_t edge, UV x) {  // along the edge: 0 at its start, 1 at its end
    const auto& pts = rings[r].pts;
    const UV &p = pts[edge], &q = pts[(edge + 1) % pts.size()];
    double du = q.u - p.u, dv = q.v - p.v, l2 = du * du + dv * dv;
    return l2 > 0 ? std::clamp(((x.u - p.u) * du + (x.v - p.v) * dv) / l2, 0.0, 1.0) : 0.0;
  };
  auto arc = [&](uint32_t r, uint32_t edge, UV x) {
    return cum[r][edge] + param(r, edge, x) * (cum[r][edge + 1] - cum[r][edge]);
  };
  // The stretch walked from a to b (forward: increasing vertex indices), `whole` when the walk
  // goes all the way round.
  auto stretch = [&](uint32_t r, double sa, double sb, bool forward, bool whole) {
    const double L = cum[r].back();
    double from = forward ? sa : sb, to = forward ? sb : sa;
    double len = whole ? L : std::fmod(to - from + L, L);
    return Stretch{from, len};
  };
  auto overlaps = [&](uint32_t r, const Stretch& x) {
    const double L = cum[r].back(), eps = 1e3;  // 1 µm
    for (const Stretch& other : covered[r]) {
      if (std::fmod(other.start - x.start + L, L) < x.len - eps) return true;
      if (std::fmod(x.start - other.start + L, L) < other.len - eps) return true;
    }
    return false;
  };
  std::vector<Poly> polys;
  polys.reserve(runs.size());
  for (const auto& run : runs) {
    Poly P;
    auto add = [&](UV p, Border b) {
      if (!P.pts.empty()) P.border.push_back(b);
      P.pts.push_back(p);
    };
    size_t li0 = run.last_line + 1 - run.iv.size();
    for (size_t k = 0; k < run.iv.size(); ++k) {
      const Interval& iv = run.iv[k];
      double v = lines[li0 + k];
      bool ltr = k % 2 == 0;
      UV first{ltr ? iv.u0 : iv.u1, v}, last{ltr ? iv.u1 : iv.u0, v};
      add(first, k == 0 ? Border::None : border_of(rings[ltr ? iv.r0 : iv.r1].kinds[ltr ? iv.e0 : iv.e1]));
      add(last, Border::None);
      P.area += (iv.u1 - iv.u0) * pitch;
      if (k == 0) P.first = {ltr ? iv.r0 : iv.r1, ltr ? iv.e0 : iv.e1, first};
      if (k + 1 == run.iv.size()) {
        P.last = {ltr ? iv.r1 : iv.r0, ltr ? iv.e1 : iv.e0, last};
        break;
      }
      // Connector from this line's end to the next line's start, along the ring.
      const Interval& nx = run.iv[k + 1];
      const auto& ring = rings[ltr ? iv.r1 : iv.r0];
      uint32_t n = static_cast<uint32_t>(ring.pts.size());
      uint32_t e_from = ltr ? iv.e1 : iv.e0, e_to = ltr ? nx.e1 : nx.e0;
      walk_ring(n, e_from, steps(n, e_from, e_to, ltr), ltr, [&](uint32_t vi, uint32_t edge) {
        add(ring.pts[vi], border_of(ring.kinds[edge]));
        return true;
      });
    }
    polys.push_back(std::move(P));
  }

  // Links along the border: the walk from `from` to `b` on their common ring, the shorter way
  // round of those that run over no other link, if it is at most `limit` units long (points
  // after `from`, up to and including `b`; `st`: the stretch it covers).
  auto walk = [&](const End& from, const End& b, std::vector<UV>& pts, std::vector<Border>& kinds,
                  Stretch& st) {
    constexpr double kNo = 1e300;
    if (from.ring != b.ring || std::hypot(b.p.u - from.p.u, b.p.v - from.p.v) > limit) return kNo;
    const uint32_t r = from.ring;
    const Ring2& ring = rings[r];
    const uint32_t n = static_cast<uint32_t>(ring.pts.size());
    const double ta = param(r, from.edge, from.p), tb = param(r, b.edge, b.p);
    const double sa = arc(r, from.edge, from.p), sb = arc(r, b.edge, b.p);
    double best = kNo;
    for (int dir : {1, -1}) {
      bool direct = from.edge == b.edge && (dir > 0 ? ta <= tb : ta >= tb);
      uint32_t count = direct ? 0 : steps(n, from.edge, b.edge, dir > 0);
      if (!direct && count == 0) count = n;  // same edge, the wrong way: all the way round
      Stretch here = stretch(r, sa, sb, dir > 0, count == n);
      if (here.len > limit || overlaps(r, here)) continue;
      std::vector<UV> p;
      std::vector<Border> k;
      double len = 0;
      UV at = from.p;
      auto step = [&](UV to, uint32_t edge) {
        len += std::hypot(to.u - at.u, to.v - at.v);
        p.push_back(to);
        k.push_back(border_of(ring.kinds[edge]));
        at = to;
      };
      walk_ring(n, from.edge, count, dir > 0, [&](uint32_t v, uint32_t edge) {
        step(ring.pts[v], edge);
        return len <= limit;
      });
      step(b.p, b.edge);
      if (len <= limit && len < best) best = len, pts = std::move(p), kinds = std::move(k), st = here;
    }
    return best;
  };
  auto reverse = [](Poly& P) {
    std::reverse(P.pts.begin(), P.pts.end());
    std::reverse(P.border.begin(), P.border.end());
    std::swap(P.first, P.last);
  };
  std::vector<Poly> chains;
  if (limit > 0 && polys.size() > 1) {
    std::vector<char> used(polys.size(), 0);
    for (size_t i = 0; i < polys.size(); ++i) {
      if (used[i]) continue;
      used[i] = 1;
      Poly cur = std::move(polys[i]);
      for (int flipped = 0; flipped < 2;) {
        double bl = 1e300;
        size_t bj = 0;
        bool bend = false;
        std::vector<UV> bp, tp;
        std::vector<Border> bk, tk;
        Stretch bs{0, 0}, ts{0, 0};
        for (size_t j = 0; j < polys.size(); ++j) {
          if (used[j]) continue;
          for (bool at_end : {false, true}) {
            double l = walk(cur.last, at_end ? polys[j].last : polys[j].first, tp, tk, ts);
            if (l < bl) bl = l, bj = j, bend = at_end, bp = std::move(tp), bk = std::move(tk), bs = ts;
          }
        }
        if (bl > limit) {  // nothing from this end: try the other one, once
          reverse(cur);
          ++flipped;
          continue;
        }
        used[bj] = 1;
        covered[cur.last.ring].push_back(bs);
        Poly& nx = polys[bj];
        if (bend) reverse(nx);
        // The walk ends on nx's first point.
        cur.pts.insert(cur.pts.end(), bp.begin(), bp.end());
        cur.border.insert(cur.border.end(), bk.begin(), bk.end());
        cur.pts.insert(cur.pts.end(), nx.pts.begin() + 1, nx.pts.end());
        cur.border.insert(cur.border.end(), nx.border.begin(), nx.border.end());
        cur.last = nx.last;
        cur.area += nx.area;
        cur.runs += nx.runs;
      }
      chains.push_back(std::move(cur));
    }
  } else {
    chains = std::move(polys);
  }

  // Polylines to paths in bed coordinates (points that round together merged).
  auto to_xy = [&](UV p) {
    return geo::Point(static_cast<coord_t>(std::llround(p.u * c - p.v * s)),
                      static_cast<coord_t>(std::llround(p.u * s + p.v * c)));
  };
  for (const Poly& P : chains) {
    FillPath fp;
    for (size_t k = 0; k < P.pts.size(); ++k) {
      geo::Point q = to_xy(P.pts[k]);
      if (!fp.pts.empty()) {
        if (fp.pts.back() == q) continue;
        fp.border.push_back(P.border[k - 1]);
      }
      fp.pts.push_back(q);
    }
    fp.area_mm2 = P.area * geo::kMmPerUnit * geo::kMmPerUnit;
    fp.runs = P.runs;
    if (fp.pts.size() >= 2) out.push_back(std::move(fp));
  }
  return out;
}

}  // namespace tranche::toolpath
