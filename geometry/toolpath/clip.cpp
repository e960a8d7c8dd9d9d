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
__extension__ typedef __int128 Wide;  // exact cross products of coordinates
// Offsets that grow first drop the vertices of their input that lie within this of the chord of
// their neighbours (a tenth of the arc tolerance, below the G-code's resolution). Booleans and
// earlier offsets leave runs of vertices a few µm apart turning by noise; moved by a millimetre,
// each such turn that closes is a detour through the vertex crossing its neighbours', and the
// union that cleans the raw curve spent nearly all of its time on them (a skin grown by a bead
// and a quarter on the bunny: 160 ms, 12 ms with this). Shrinking is left exact: a simplified
// sliver can turn inside out and shrink into a spurious bead.
constexpr geo::coord_t kInputTolerance = 500;  // 0.5 µm
// simplify() for an input grown, less the choices that would make the ring cross itself where it
// turns back (defined below dp()).
geo::Ring simplify_input(const geo::Ring& ring, geo::coord_t tol);

Rings boolean(const Rings& a, const Rings& b, ClipperLib::ClipType op) {
  Rings out;
  if (a.empty() && op != ClipperLib::ctUnion) return out;
  Clipper c;
  c.AddPaths(a, ClipperLib::ptSubject, true);
  c.AddPaths(b, ClipperLib::ptClip, true);
  c.Execute(op, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return out;
}

// `p` less each vertex that ends an edge shorter than 10 µm and lies within 1 µm of the chord
// between its neighbours, between the chord's ends (no spike's tip goes), never two in a row (so
// each is within 1 µm of the edge that replaces it, and the ring moves by less than 1 µm).
// Not inlined: GCC 12, inlining it into raw_offset, takes its push_back for a free of a non-heap
// pointer (-Wfree-nonheap-object, a false positive).
[[gnu::noinline]] geo::Ring without_short_edges(const geo::Ring& p) {
  constexpr double kShort = 10000, kNear = 1000;  // nm
  auto len2 = [](const geo::Point& a, const geo::Point& b) {
    const double dx = double(b.X - a.X), dy = double(b.Y - a.Y);
    return dx * dx + dy * dy;
  };
  geo::Ring q;
  q.reserve(p.size());
  q.push_back(p[0]);
  bool dropped = false;
  for (size_t j = 1; j + 1 < p.size(); ++j) {
    const geo::Point &a = q.back(), &v = p[j], &b = p[j + 1];
    if (!dropped && (len2(a, v) < kShort * kShort || len2(v, b) < kShort * kShort)) {
      const double dx = double(b.X - a.X), dy = double(b.Y - a.Y), l2 = dx * dx + dy * dy;
      const double t = l2 > 0 ? (double(v.X - a.X) * dx + double(v.Y - a.Y) * dy) / l2 : -1;
      const double c = double(v.X - a.X) * dy - double(v.Y - a.Y) * dx;
      if (t > 0 && t < 1 && c * c < kNear * kNear * l2) {
        dropped = true;
        continue;
      }
    }
    dropped = false;
    q.push_back(v);
  }
  q.push_back(p.back());
  return q;
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
// With `trim`, the trimmed curve below or nothing (`trimmed` false); else the curve with detours.
void raw_offset(const geo::Ring& ring, double delta, double steps_per_rad, double mitre_tol, Rings& out, bool trim,
                bool& trimmed) {
  // Consecutive duplicates carry no direction.
  geo::Ring p;
  p.reserve(ring.size());
  for (const auto& q : ring)
    if (p.empty() || q != p.back()) p.push_back(q);
  while (p.size() > 1 && p.front() == p.back()) p.pop_back();
  // For the trimmed curve, edges of a few µm go (without_short_edges): outlines sliced from meshes
  // pair most of their vertices a few µm apart, each one more segment (and join) to trim, for no
  // visible change. The curve with detours keeps every vertex (a sliver of no area must stay one).
  if (trim && p.size() > 3) {
    geo::Ring q = without_short_edges(p);
    if (q.size() >= 3) p.swap(q);
  }
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
  // Round join from a to b; a mitre when it lies within mitre_tol of the arc:
  // |delta| (1 / cos(turn / 2) − 1) ≤ mitre_tol.
  auto mitre = [&](double cos_a) {
    return cos_a > 0 && std::abs(delta) <= (mitre_tol + std::abs(delta)) * std::sqrt(0.5 * (1 + cos_a));
  };
  auto arc = [&](const geo::Point& v, const Normal& a, double sin_a, double cos_a) {  // between a's and b's ends
    if (cos_a >= cos_one_step) return;
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
  };
  // First the trimmed curve. It is made of segments: the moved edges and the chords of the round
  // joins, each a line with the part of it kept. Where two overlap (the curve would turn back
  // across itself) it takes their crossing; a segment wholly behind its neighbours' crossing (a
  // short edge of a tessellated curve, shorter than the overlap; an arc whose vertex a moved edge
  // passes) is dropped and its neighbours are crossed instead, as the union would leave them; so
  // is one that would follow a segment it does not start from, or turn back on it, where it lies
  // wholly within |delta| of that segment's edge or vertex (none of it is on the offset).
  // Segments stack up as they come; a consumed one is the top one, whose only point is its start.
  // It gives up (the detours below then, for the union) where the bottom segment (the longest
  // edge) would go, where a segment would follow one it does not start from by turning the way
  // the offset opens, or where the lines nearly turn back (more than 177°).
  if (trim) {
    struct Seg {
      double ox, oy;     // its point at 0 along it
      double nx, ny;     // its unit normal; its direction is (-ny, nx)
      double s, e, lim;  // kept from s to e along it (units); it ends at lim
      size_t at;         // its points start at r[at]
      size_t src;        // the edge it is moved from, or the vertex its arc is round
      bool chord;
    };
    size_t j0 = 0;  // the longest edge first: the last to be consumed
    for (size_t i = 1; i < n; ++i)
      if (nrm[i].len > nrm[j0].len) j0 = i;
    auto edge = [&](size_t e) {
      return Seg{double(p[e].X) + nrm[e].x * delta, double(p[e].Y) + nrm[e].y * delta, nrm[e].x, nrm[e].y, 0,
                 nrm[e].len, nrm[e].len, 0, e, false};
    };
    // Whether `x` lies wholly within |delta| of what `t` is made from (an edge, or the vertex of
    // its arc): then none of it is on the offset, which lies |delta| from the ring.
    auto covered = [&](const Seg& t, const Seg& x) {
      const double reach = std::abs(delta) - 1, r2 = reach * reach;
      auto inside = [&](double qx, double qy) {
        const geo::Point& a = p[t.src];
        double cx = double(a.X), cy = double(a.Y);
        if (!t.chord) {
          const geo::Point& b = p[(t.src + 1) % n];
          const double ex = double(b.X) - cx, ey = double(b.Y) - cy;
          const double u = std::clamp(((qx - cx) * ex + (qy - cy) * ey) / (ex * ex + ey * ey), 0.0, 1.0);
          cx += u * ex, cy += u * ey;
        }
        return (qx - cx) * (qx - cx) + (qy - cy) * (qy - cy) < r2;
      };
      const double s0 = std::min(x.s, 0.0);
      return inside(x.ox - x.ny * s0, x.oy + x.nx * s0) && inside(x.ox - x.ny * x.lim, x.oy + x.nx * x.lim);
    };
    auto emit = [&](double x, double y) {
      r.emplace_back(static_cast<geo::coord_t>(std::llround(x)), static_cast<geo::coord_t>(std::llround(y)));
    };
    std::vector<Seg> st;
    st.reserve(64);
    st.push_back(edge(j0));
    st[0].s = -1e300;
    // Puts `x` on the stack after the segment before it, which ends where `x` starts (at (px, py),
    // `x.s` along `x`) unless they overlap; `last`: `x` is the bottom segment, come round again.
    // Where `x` overlaps, the segments it consumes (their crossing with it lies before their start)
    // go, and it starts at its crossing with the first that stays; if that crossing lies past its
    // end, `x` is wholly behind and goes itself instead (it consumes nothing), and the next one
    // does not start where the top segment ends.
    bool connected = true;  // the top segment is the one before the next
    auto feed = [&](Seg x, double px, double py, bool last) {
      size_t k = st.size() - 1;  // the top once those consumed go
      for (;;) {
        Seg& t = st[k];
        const double sin_a = std::clamp(t.nx * x.ny - x.nx * t.ny, -1.0, 1.0);
        const double cos_a = t.nx * x.nx + t.ny * x.ny;
        const bool straight = std::abs(sin_a * delta) < 1.0 && cos_a > 0;
        if (sin_a * delta < 0 && !straight) {  // overlap: cross
          if (cos_a < -0.999 && !last && (covered(t, x) || covered(st.back(), x))) {  // x wholly behind
            connected = false;
            return true;
          }
          if (cos_a < -0.999) return false;  // nearly back: the crossing is far and ill-conditioned
          const double dtx = -t.ny, dty = t.nx, dxx = -x.ny, dxy = x.nx;  // directions
          const double den = dtx * dxy - dty * dxx;
          const double wx = x.ox - t.ox, wy = x.oy - t.oy;
          const double ta = (wx * dxy - wy * dxx) / den, tb = (wx * dty - wy * dtx) / den;
          if (ta < t.s) {  // t is consumed
            if (k == 0) return false;
            --k;
            continue;
          }
          if (ta > t.lim + 1.0) return false;  // crossing past t's end: only a consumed segment's would be
          if (tb > x.lim && !last) {  // x wholly behind
            connected = false;
            return true;
          }
          if (k + 1 < st.size()) {
            r.resize(st[k + 1].at);
            st.resize(k + 1);
          }
          t.e = ta;
          x.s = tb;
          px = t.ox + dtx * ta;
          py = t.oy + dty * ta;
        } else {  // straight on or opening: from where t ends
          if ((k + 1 < st.size() || !connected) && !last && (covered(t, x) || covered(st.back(), x))) {
            connected = false;  // x wholly behind
            return true;
          }
          if (k + 1 < st.size() || !connected) return false;
          t.e = t.lim;
        }
        if (last && (st.size() == 1 || x.s > st[0].e)) return false;
        if (!last) {
          x.at = r.size();
          st.push_back(x);
        }
        connected = true;
        emit(px, py);
        return true;
      }
    };
    bool ok = true;
    for (size_t m = 1; m <= n && ok; ++m) {
      const size_t b = (j0 + m) % n, a = (b + n - 1) % n;
      const Normal &na = nrm[a], &nb = nrm[b];
      const geo::Point& v = p[b];
      const double vx = double(v.X), vy = double(v.Y);
      const double sin_a = std::clamp(na.x * nb.y - nb.x * na.y, -1.0, 1.0);
      const double cos_a = na.x * nb.x + na.y * nb.y;
      Seg x = edge(b);
      const bool last = m == n;
      if (std::abs(sin_a * delta) < 1.0 && cos_a > 0) {  // straight on: a's end
        ok = feed(x, vx + na.x * delta, vy + na.y * delta, last);
      } else if (sin_a * delta < 0) {  // the moved edges overlap
        ok = feed(x, 0, 0, last);
      } else if (mitre(cos_a)) {  // both lines to their crossing
        const double ext = sin_a * delta / (1 + cos_a), f = delta / (1 + cos_a);
        if (connected) st.back().lim += ext;
        x.s = -ext;
        ok = feed(x, vx + (na.x + nb.x) * f, vy + (na.y + nb.y) * f, last);
      } else {  // the arc's chords, then b
        double qx = vx + na.x * delta, qy = vy + na.y * delta;
        auto chord = [&](double x2, double y2) {
          const double dx = x2 - qx, dy = y2 - qy, len = std::sqrt(dx * dx + dy * dy);
          if (len > 0) {
            const Seg c{qx, qy, dy / len, -dx / len, 0, len, len, 0, b, true};
            if (!feed(c, qx, qy, false)) return false;
          }
          qx = x2, qy = y2;
          return true;
        };
        if (cos_a < cos_one_step) {
          const double turn = std::atan2(sin_a, cos_a);
          const int steps = std::max(static_cast<int>(std::lround(steps_per_rad * std::abs(turn))), 1);
          const double c = std::cos(turn / steps), s = std::sin(turn / steps);
          double ux = na.x, uy = na.y;
          for (int i = 1; i < steps && ok; ++i) {
            const double u2 = ux * c - uy * s;
            uy = ux * s + uy * c;
            ux = u2;
            ok = chord(vx + ux * delta, vy + uy * delta);
          }
        }
        ok = ok && chord(vx + nb.x * delta, vy + nb.y * delta) && feed(x, qx, qy, last);
      }
    }
    if (ok && r.size() >= 3)
      out.push_back(std::move(r));
    else
      trimmed = false;
    return;
  }
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
    // Round join from a to b, or its mitre.
    if (mitre(cos_a)) {
      const double f = 1 / (1 + cos_a);
      at(v, (a.x + b.x) * f, (a.y + b.y) * f);
      continue;
    }
    at(v, a.x, a.y);
    arc(v, a, sin_a, cos_a);
    at(v, b.x, b.y);
  }
  out.push_back(std::move(r));
}

// Whether the raw curves can be the offset as they are, without the union that cleans them: no
// two edges meet but consecutive ones at their common end (exact integer tests; a spike, an
// edge turning back along the one before, counts as a meeting), and the rings nested as a
// region's are (below). Edges are swept by x; a sweep that would compare far more pairs than
// there are edges gives up (false) rather than become quadratic.
bool simple_as_is(const Rings& raw) {
  struct Edge {
    geo::coord_t x0, x1, y0, y1;
    uint32_t ring, i;
  };
  size_t n = 0;
  for (const auto& r : raw) {
    if (r.size() < 3) return false;
    n += r.size();
  }
  if (raw.size() > 16) return false;
  std::vector<Edge> edges;
  edges.reserve(n);
  for (uint32_t ri = 0; ri < raw.size(); ++ri) {
    const auto& r = raw[ri];
    for (uint32_t i = 0; i < r.size(); ++i) {
      const geo::Point& a = r[i];
      const geo::Point& b = r[(i + 1) % r.size()];
      edges.push_back({std::min(a.X, b.X), std::max(a.X, b.X), std::min(a.Y, b.Y), std::max(a.Y, b.Y), ri, i});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) { return a.x0 < b.x0; });
  auto cross = [](const geo::Point& o, const geo::Point& a, const geo::Point& b) {
    const Wide v = Wide(a.X - o.X) * Wide(b.Y - o.Y) - Wide(a.Y - o.Y) * Wide(b.X - o.X);
    return v > 0 ? 1 : v < 0 ? -1 : 0;
  };
  auto on = [](const geo::Point& a, const geo::Point& b, const geo::Point& q) {  // q on ab, collinear
    return std::min(a.X, b.X) <= q.X && q.X <= std::max(a.X, b.X) && std::min(a.Y, b.Y) <= q.Y &&
           q.Y <= std::max(a.Y, b.Y);
  };
  auto meet = [&](const geo::Point& a, const geo::Point& b, const geo::Point& c, const geo::Point& d) {
    const int d1 = cross(c, d, a), d2 = cross(c, d, b), d3 = cross(a, b, c), d4 = cross(a, b, d);
    if (d1 * d2 < 0 && d3 * d4 < 0) return true;
    return (d1 == 0 && on(c, d, a)) || (d2 == 0 && on(c, d, b)) || (d3 == 0 && on(a, b, c)) ||
           (d4 == 0 && on(a, b, d));
  };
  std::vector<uint32_t> active;
  size_t budget = 16 * n + 1024;
  for (uint32_t k = 0; k < edges.size(); ++k) {
    const Edge& e = edges[k];
    const auto& re = raw[e.ring];
    const geo::Point& a = re[e.i];
    const geo::Point& b = re[(e.i + 1) % re.size()];
    for (size_t j = 0; j < active.size();) {
      const Edge& f = edges[active[j]];
      if (f.x1 < e.x0) {  // ended left of this one: out of the sweep
        active[j] = active.back();
        active.pop_back();
        continue;
      }
      ++j;
      if (f.y1 < e.y0 || e.y1 < f.y0) continue;
      if (budget-- == 0) return false;
      const auto& rf = raw[f.ring];
      const geo::Point& c = rf[f.i];
      const geo::Point& d = rf[(f.i + 1) % rf.size()];
      if (f.ring == e.ring) {
        const uint32_t m = static_cast<uint32_t>(re.size());
        if ((f.i + 1) % m == e.i || (e.i + 1) % m == f.i) {
          // Consecutive: they share an end; they meet elsewhere only if one turns back along the other.
          const geo::Point& shared = (f.i + 1) % m == e.i ? a : c;
          const geo::Point& p = (f.i + 1) % m == e.i ? c : a;  // the other end of the first
          const geo::Point& q = (f.i + 1) % m == e.i ? b : d;  // the other end of the second
          if (cross(shared, p, q) == 0 &&
              Wide(p.X - shared.X) * Wide(q.X - shared.X) + Wide(p.Y - shared.Y) * Wide(q.Y - shared.Y) > 0)
            return false;
          continue;
        }
      }
      if (meet(a, b, c, d)) return false;
    }
    active.push_back(k);
  }
  // No two rings cross: each is wholly inside or outside each other one, and the union keeps them
  // all as they are when every outer (counter-clockwise) is inside no other ring, or inside as
  // many holes as outers, and every hole inside one outer more than holes: one point of each
  // ring tells (exact winding numbers).
  if (raw.size() > 1) {
    auto winding = [&](const geo::Point& q, const geo::Ring& r) {
      int w = 0;
      for (size_t i = 0; i < r.size(); ++i) {
        const geo::Point& a = r[i];
        const geo::Point& b = r[(i + 1) % r.size()];
        if (a.Y <= q.Y) {
          if (b.Y > q.Y && cross(a, b, q) > 0) ++w;
        } else if (b.Y <= q.Y && cross(a, b, q) < 0) {
          --w;
        }
      }
      return w;
    };
    for (size_t i = 0; i < raw.size(); ++i) {
      int w = 0;
      for (size_t j = 0; j < raw.size(); ++j)
        if (j != i) w += winding(raw[i][0], raw[j]);
      if (w != (ClipperLib::Area(raw[i]) > 0 ? 0 : 1)) return false;
    }
  } else if (ClipperLib::Area(raw[0]) <= 0) {
    return false;
  }
  return true;
}

// The raw rings as the union gives them when they are simple: consecutive duplicates and points
// in line with their neighbours dropped (simple_as_is() then checks what is left).
Rings cleaned(Rings raw) {
  for (auto& r : raw) {
    geo::Ring out;
    out.reserve(r.size());
    const size_t n = r.size();
    for (size_t i = 0; i < n; ++i) {
      const geo::Point& prev = out.empty() ? r[(i + n - 1) % n] : out.back();
      const geo::Point& cur = r[i];
      const geo::Point& next = r[(i + 1) % n];
      if (cur == prev) continue;
      const Wide c = Wide(cur.X - prev.X) * (next.Y - cur.Y) - Wide(cur.Y - prev.Y) * (next.X - cur.X);
      if (c == 0) continue;
      out.push_back(cur);
    }
    auto in_line = [](const geo::Point& p0, const geo::Point& p1, const geo::Point& p2) {
      return p1 == p0 || Wide(p1.X - p0.X) * (p2.Y - p1.Y) - Wide(p1.Y - p0.Y) * (p2.X - p1.X) == 0;
    };
    while (out.size() >= 3 && in_line(out[out.size() - 2], out.back(), out.front())) out.pop_back();
    while (out.size() >= 3 && in_line(out.back(), out.front(), out[1])) out.erase(out.begin());
    r = std::move(out);
  }
  std::erase_if(raw, [](const geo::Ring& r) { return r.size() < 3; });
  return raw;
}

// Whether `raw`, cleaned, is the union's result already (no ring lost to the cleaning,
// simple_as_is): then it is left in `out` (else `out` is empty).
bool as_is(Rings raw, Rings& out) {
  const size_t n = raw.size();
  out = cleaned(std::move(raw));
  if (out.size() == n && simple_as_is(out)) return true;
  out.clear();
  return false;
}

// Whether `v`, between `a` and `b`, is the end of a spike of no width: the ring goes back from it
// along the line it came by (exact test).
bool turns_back(const geo::Point& a, const geo::Point& v, const geo::Point& b) {
  // Going back along a line, the dot product is minus the lengths' product: its sign in doubles
  // is exact there, and rules out nearly every vertex before the exact test.
  if (double(v.X - a.X) * double(b.X - v.X) + double(v.Y - a.Y) * double(b.Y - v.Y) >= 0) return false;
  return Wide(v.X - a.X) * Wide(b.Y - v.Y) == Wide(v.Y - a.Y) * Wide(b.X - v.X);
}

// `ring` less its spikes of no width (out along a line and back along it: no point of the region
// lies on either side, so the offset has nothing there; the curves of both Clipper's offset and
// ours went round them, growing each into a stadium, and shrinking opened one pointing in into a
// channel) and repeated vertices, in `out`; false (and `out` untouched) when it has none, or when
// nothing with an area would be left (a ring that is a line is grown as its line).
bool without_spikes(const geo::Ring& ring, geo::Ring& out) {
  const size_t n = ring.size();
  if (n < 3) return false;
  bool any = false;
  const geo::Point *a = &ring[n - 2], *v = &ring[n - 1];
  double ex = double(v->X - a->X), ey = double(v->Y - a->Y);  // the edge into v
  for (const geo::Point& b : ring) {
    const coord_t fx = b.X - v->X, fy = b.Y - v->Y;
    const double gx = double(fx), gy = double(fy);
    if ((fx == 0 && fy == 0) || (ex * gx + ey * gy < 0 && turns_back(*a, *v, b))) {
      any = true;
      break;
    }
    a = v, v = &b, ex = gx, ey = gy;
  }
  if (!any) return false;
  geo::Ring s;
  s.reserve(n);
  for (const geo::Point& q : ring) {
    if (!s.empty() && s.back() == q) continue;
    bool dup = false;
    while (s.size() >= 2 && turns_back(s[s.size() - 2], s.back(), q)) {
      s.pop_back();
      if (s.back() == q) {
        dup = true;
        break;
      }
    }
    if (!dup) s.push_back(q);
  }
  // Where the ring closes.
  while (s.size() >= 3) {
    if (s.back() == s.front() || turns_back(s[s.size() - 2], s.back(), s.front()))
      s.pop_back();
    else if (turns_back(s.back(), s[0], s[1]))
      s.erase(s.begin());
    else
      break;
  }
  if (s.size() < 3 || ClipperLib::Area(s) == 0) return false;
  out = std::move(s);
  return true;
}

// Whether a ring of the trimmed curve `out` is no part of the offset: its first vertex lies
// closer than `reach` units to an edge of `region` (every vertex of the offset lies
// the distance from the region's border, to the arcs' tolerance). Where the trimmed curve is
// simple and nested as a region's, a loop left by segments that cross where none of them is on
// the offset still can be: a star with arms narrower than twice the distance, shrunk, kept a
// triangle of 0.2 mm² where Clipper's offset and the exact one are empty.
bool off_the_offset(const Rings& out, const std::vector<const geo::Ring*>& region, double reach) {
  if (reach <= 0) return false;
  const double r2 = reach * reach;
  const coord_t rc = static_cast<coord_t>(reach);
  for (const geo::Ring& o : out) {
    {
      const geo::Point* q = &o[0];
      const double qx = double(q->X), qy = double(q->Y);
      const coord_t y0 = q->Y - rc, y1 = q->Y + rc, x0 = q->X - rc, x1 = q->X + rc;
      for (const geo::Ring* rp : region) {
        const geo::Ring& r = *rp;
        for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
          const geo::Point &pa = r[j], &pb = r[i];
          if ((pa.Y < y0 && pb.Y < y0) || (pa.Y > y1 && pb.Y > y1) || (pa.X < x0 && pb.X < x0) ||
              (pa.X > x1 && pb.X > x1))
            continue;
          const double ax = double(pa.X), ay = double(pa.Y), bx = double(pb.X), by = double(pb.Y);
          const double ex = bx - ax, ey = by - ay, l2 = ex * ex + ey * ey;
          const double t = l2 > 0 ? std::clamp(((qx - ax) * ex + (qy - ay) * ey) / l2, 0.0, 1.0) : 0.0;
          const double dx = ax + t * ex - qx, dy = ay + t * ey - qy;
          if (dx * dx + dy * dy < r2) return true;
        }
      }
    }
  }
  return false;
}

Rings offset_with(const Rings& region, double mm, double arc_tolerance, bool* as_built = nullptr) {
  if (as_built) *as_built = false;
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
    // Most offsets of real outlines, trimmed where moved edges overlap, are simple curves: they
    // are the offset, no union needed. Anything else (a trim given up, a crossing, a hole, rings
    // inside others) is built again with detours for the union, as Clipper's offset does.
    // The rings less their spikes of no width (copies only where there are some).
    Rings fixed(region.size());
    std::vector<const geo::Ring*> rings(region.size());
    for (size_t i = 0; i < region.size(); ++i) rings[i] = without_spikes(region[i], fixed[i]) ? &fixed[i] : &region[i];
    for (int pass = 0; pass < 2; ++pass) {
      const bool trim = pass == 0;
      bool trimmed = true;
      raw.clear();
      for (const geo::Ring* rp : rings) {
        const geo::Ring& r = *rp;
        geo::Ring clean = delta > 0 ? simplify_input(r, kInputTolerance) : r;
        if (clean.empty()) clean = r;
        if (flip) std::reverse(clean.begin(), clean.end());
        raw_offset(clean, delta, steps_per_rad, 0.2 * tol, raw, trim, trimmed);
        if (!trimmed) break;
      }
      if (trim && trimmed && !raw.empty() && as_is(std::move(raw), out)) {  // raw is built again below
        if (off_the_offset(out, rings, ad - 2.5 * tol - 2000)) {
          out.clear();
          continue;
        }
        if (as_built) *as_built = true;
        return out;
      }
    }
  }
  if (raw.empty()) return out;
  if (ad < 1.0 && as_is(raw, out)) return out;
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

bool is_clean_region(const Rings& rings) {
  if (rings.empty()) return true;
  for (const auto& r : rings)
    for (size_t i = 0; i < r.size(); ++i)
      if (r[i] == r[(i + 1) % r.size()]) return false;
  return simple_as_is(rings);
}

Rings offset(const Rings& region, double mm) { return offset_with(region, mm, kArcTolerance); }
Rings offset(const Rings& region, double mm, bool& as_built) {
  return offset_with(region, mm, kArcTolerance, &as_built);
}
Rings offset_coarse(const Rings& region, double mm) { return offset_with(region, mm, 25000); }

Rings offset_open(const Rings& region, double mm, double open_mm) {
  return offset(offset(region, mm - open_mm), open_mm);
}

Rings buffer_loops(const Rings& loops, double mm) {
  // Each loop's band is the loop (as a region) grown by mm less the loop shrunk by mm: the grown
  // rings as they are and the shrunk ones turned have winding 1 in the band, 0 elsewhere (the
  // shrunk lies within the grown). Two of our offsets, which mostly skip the union, instead of
  // Clipper's line offset, which unites both sides of every loop.
  Rings out, odd;
  geo::Ring unused;
  for (const geo::Ring& loop : loops) {
    // No region (a line or a point), or a spike of no width, which the offsets leave out of a
    // region but a bead following the loop goes out along and back: Clipper's line offset.
    if (loop.size() < 3 || ClipperLib::Area(loop) == 0 || without_spikes(loop, unused)) {
      odd.push_back(loop);
      continue;
    }
    Rings r{loop};
    if (!ClipperLib::Orientation(r[0])) ClipperLib::ReversePath(r[0]);
    Rings grown = offset(r, mm), shrunk = offset(r, -mm);
    for (geo::Ring& g : grown) out.push_back(std::move(g));
    for (geo::Ring& s : shrunk) {
      ClipperLib::ReversePath(s);
      out.push_back(std::move(s));
    }
  }
  if (!odd.empty()) {
    ClipperOffset co(2.0, kArcTolerance);
    co.AddPaths(odd, ClipperLib::jtRound, ClipperLib::etClosedLine);
    Rings line;
    co.Execute(line, mm * geo::kUnitsPerMm);
    for (geo::Ring& l : line) out.push_back(std::move(l));
  }
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

Rings clip_loops(const Rings& loops, const Rings& region, bool inside) {
  Clipper c;
  for (const geo::Ring& r : loops) {
    if (r.size() < 2) continue;
    geo::Ring line = r;
    line.push_back(r.front());  // as an open line: the whole loop
    c.AddPath(line, ClipperLib::ptSubject, false);
  }
  c.AddPaths(region, ClipperLib::ptClip, true);
  ClipperLib::PolyTree tree;
  c.Execute(inside ? ClipperLib::ctIntersection : ClipperLib::ctDifference, tree, ClipperLib::pftNonZero,
            ClipperLib::pftNonZero);
  Rings lines;
  ClipperLib::OpenPathsFromPolyTree(tree, lines);
  return lines;
}

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

namespace {
// Douglas-Peucker's choice of vertices for `ring` (n >= 4): the loop split at vertex 0 and the
// vertex farthest from it.
std::vector<char> simplified(const geo::Ring& ring, coord_t tol) {
  const size_t n = ring.size();
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
  return keep;
}

geo::Ring kept(const geo::Ring& ring, const std::vector<char>& keep) {
  geo::Ring out;
  out.reserve(ring.size());
  for (size_t k = 0; k < ring.size(); ++k)
    if (keep[k]) out.push_back(ring[k]);
  if (out.size() < 3) return {};
  return out;
}
}  // namespace

geo::Ring simplify(const geo::Ring& ring, coord_t tol) {
  if (ring.size() < 4 || tol <= 0) return ring;
  return kept(ring, simplified(ring, tol));
}

namespace {
// Douglas-Peucker drops a vertex within `tol` of its chord whatever the ring does next to it. Next
// to a spike, a hairline loop or any turn back, that can make the ring cross itself: a star's tip
// going out 3 µm and back, its first tip vertex 0.4 µm off the chord to the spike's end, became a
// ring that runs past the tip, turns back, and crosses its own incoming edge, turning round the
// tip clockwise. Every join there is then a detour through the vertex (no round cap), and the
// union of the grown curve missed the tip's cap, 3 mm² of it grown by 1.5 mm. Where the ring turns
// back by more than 120° to within 4 tolerances of where it came from, the vertex and its
// neighbours stay, so the edges next to the turn are the ring's own (where Douglas-Peucker keeps
// them all anyway, its result as it is: the same G-code on every model we slice).
geo::Ring simplify_input(const geo::Ring& ring, coord_t tol) {
  const size_t n = ring.size();
  if (n < 4 || tol <= 0) return ring;
  std::vector<char> keep = simplified(ring, tol);
  auto next = [n](size_t i) { return i + 1 < n ? i + 1 : 0; };
  auto prev = [n](size_t i) { return i > 0 ? i - 1 : n - 1; };
  auto turns_back_near = [&](size_t i) {
    const geo::Point &a = ring[prev(i)], &v = ring[i], &b = ring[next(i)];
    if (v == a || v == b) return true;
    const double cx = double(b.X - a.X), cy = double(b.Y - a.Y);
    if (cx * cx + cy * cy >= 16.0 * double(tol) * double(tol)) return false;
    const double ax = double(v.X - a.X), ay = double(v.Y - a.Y), bx = double(b.X - v.X), by = double(b.Y - v.Y);
    const double dot = ax * bx + ay * by;
    return dot < 0 && 4 * dot * dot > (ax * ax + ay * ay) * (bx * bx + by * by);  // by more than 120°
  };
  // Only a dropped vertex can matter: it or a neighbour turning back near it.
  bool dropped = false;
  for (size_t k = 0; k < n && !dropped; ++k)
    dropped = !keep[k] && (turns_back_near(prev(k)) || turns_back_near(k) || turns_back_near(next(k)));
  if (!dropped) return kept(ring, keep);
  std::vector<char> pin(n, 0);
  for (size_t i = 0; i < n; ++i)
    if (turns_back_near(i)) pin[prev(i)] = pin[i] = pin[next(i)] = 1;
  // Douglas-Peucker between consecutive pinned vertices, from the first (kept in the ring's order).
  size_t first = 0;
  while (!pin[first]) ++first;
  geo::Ring rot(ring.begin() + static_cast<std::ptrdiff_t>(first), ring.end());
  rot.insert(rot.end(), ring.begin(), ring.begin() + static_cast<std::ptrdiff_t>(first));
  std::vector<char> rkeep(n, 0);
  const double tol2 = double(tol) * double(tol);
  size_t from = 0;
  for (size_t k = 1; k <= n; ++k) {
    if (k < n && !pin[(k + first) % n]) continue;
    rkeep[from] = 1;
    dp(rot, from, k, tol2, rkeep);
    from = k;
  }
  for (size_t k = 0; k < n; ++k) keep[(k + first) % n] = rkeep[k];
  return kept(ring, keep);
}
}  // namespace

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
