#include "geometry/toolpath/gap_fill.h"

#include <algorithm>
#include <cmath>

#include "geometry/polygon/medial_axis.h"
#include "geometry/toolpath/clip.h"

namespace tranche::toolpath {

std::vector<VarBead> axis_beads_only(const geo::Rings& region, const BeadSpec& spec);
std::vector<VarBead> blob_loops(const geo::Rings& region, const std::vector<VarBead>& beads, const BeadSpec& spec);

namespace {

double dist_mm(const geo::Point& a, const geo::Point& b) {
  return std::hypot(geo::to_mm(b.X - a.X), geo::to_mm(b.Y - a.Y));
}

double bead_length(const VarBead& b) {
  double l = 0;
  for (size_t i = 1; i < b.pts.size(); ++i) l += dist_mm(b.pts[i - 1], b.pts[i]);
  return l;
}

// Closes `cur` into `out` when it is a bead worth printing: at least half as long as it is wide
// (shorter, it is a dot of plastic whose direction means nothing).
void flush(VarBead& cur, std::vector<VarBead>& out) {
  if (cur.pts.size() >= 2 && bead_length(cur) >= 0.5 * cur.mean_width()) out.push_back(std::move(cur));
  cur = VarBead{};
}

constexpr double kJunctionTrim = 0.25;

// Removes `mm` of length from the start of `b` (cutting a piece where it falls).
void trim_start(VarBead& b, double mm) {
  while (mm > 0 && b.pts.size() >= 2) {
    const double l = dist_mm(b.pts[0], b.pts[1]);
    if (l > mm + 1e-6) {
      const double t = mm / l;
      b.pts[0] = geo::Point(b.pts[0].X + std::llround(t * double(b.pts[1].X - b.pts[0].X)),
                            b.pts[0].Y + std::llround(t * double(b.pts[1].Y - b.pts[0].Y)));
      if (b.pts[0] == b.pts[1]) {
        b.pts.erase(b.pts.begin());
        b.widths.erase(b.widths.begin());
      }
      return;
    }
    mm -= l;
    b.pts.erase(b.pts.begin());
    b.widths.erase(b.widths.begin());
  }
  if (b.pts.size() < 2) {
    b.pts.clear();
    b.widths.clear();
  }
}

}  // namespace

double VarBead::mean_width() const {
  double l = 0, a = 0;
  for (size_t i = 0; i + 1 < pts.size() && i < widths.size(); ++i) {
    const double d = dist_mm(pts[i], pts[i + 1]);
    l += d;
    a += d * widths[i];
  }
  return l > 0 ? a / l : (widths.empty() ? 0.0 : widths.front());
}

std::vector<VarBead> axis_beads(const geo::Rings& region, const BeadSpec& spec) {
  std::vector<VarBead> out = axis_beads_only(region, spec);
  std::vector<VarBead> blobs = blob_loops(region, out, spec);
  out.insert(out.end(), std::make_move_iterator(blobs.begin()), std::make_move_iterator(blobs.end()));
  return out;
}

std::vector<VarBead> axis_beads_only(const geo::Rings& region, const BeadSpec& spec) {
  std::vector<VarBead> out;
  if (!(spec.min_width > 0) || !(spec.max_width >= spec.min_width) || !(spec.height > 0)) return out;
  const double extra = spec.height * (1 - M_PI / 4);
  const double step = std::max(spec.width_step, 1e-3);
  const int max_beads = std::clamp(spec.max_beads, 1, 16);
  for (const geo::AxisPath& a : geo::medial_axis(region)) {
    // Points with their local widths (2r), each axis edge split so that the width changes by
    // at most `step` along a piece; duplicate points dropped.
    geo::Ring pts;
    std::vector<double> wid;
    // Points closer than 5 µm to the previous one are dropped (the last one replaces it), so that
    // offsets across the axis cannot turn a kink into a backtrack.
    auto add = [&](const geo::Point& p, double w, bool last = false) {
      if (!pts.empty() && dist_mm(pts.back(), p) < 0.005) {
        if (!last || pts.size() < 2) return;
        pts.pop_back();
        wid.pop_back();
      }
      pts.push_back(p);
      wid.push_back(w);
    };
    for (size_t i = 0; i < a.pts.size(); ++i) {
      if (i > 0) {
        const double w0 = 2 * a.radius_mm[i - 1], w1 = 2 * a.radius_mm[i];
        const int n = std::clamp(static_cast<int>(std::ceil(std::abs(w1 - w0) / step)), 1, 200);
        for (int k = 1; k < n; ++k) {
          const double t = double(k) / n;
          add(geo::Point(a.pts[i - 1].X + std::llround(t * double(a.pts[i].X - a.pts[i - 1].X)),
                         a.pts[i - 1].Y + std::llround(t * double(a.pts[i].Y - a.pts[i - 1].Y))),
              w0 + t * (w1 - w0));
        }
      }
      add(a.pts[i], 2 * a.radius_mm[i], i + 1 == a.pts.size());
    }
    const size_t np = pts.size();
    if (np < 2) continue;
    const bool closed = a.closed && pts.front() == pts.back();
    // Unit normal (left of travel) at each point, from its neighbours.
    auto normal = [&](size_t i) {
      size_t lo = i > 0 ? i - 1 : (closed ? np - 2 : 0);
      size_t hi = i + 1 < np ? i + 1 : (closed ? 1 : np - 1);
      const double dx = double(pts[hi].X - pts[lo].X), dy = double(pts[hi].Y - pts[lo].Y);
      const double l = std::hypot(dx, dy);
      return l > 0 ? std::pair<double, double>{-dy / l, dx / l} : std::pair<double, double>{0, 0};
    };
    // Runs of pieces with the same bead count; 0 where the part is too thin to print.
    auto count = [&](double t) {
      if (!std::isfinite(t) || t < spec.min_width) return 0;
      if (max_beads == 1) return 1;
      const int n = std::clamp(static_cast<int>(std::ceil((t + extra) / spec.max_width)), 1, max_beads);
      return t / n < spec.min_width ? std::max(1, static_cast<int>(t / spec.min_width)) : n;
    };
    size_t i = 0;
    while (i + 1 < np) {
      const int n = count(0.5 * (wid[i] + wid[i + 1]));
      size_t j = i + 1;
      while (j + 1 < np && count(0.5 * (wid[j] + wid[j + 1])) == n) ++j;
      // Pieces i .. j-1 (points i .. j) have n beads.
      for (int b = 0; b < n; ++b) {
        VarBead cur;
        for (size_t k = i; k <= j; ++k) {
          geo::Point p = pts[k];
          if (n > 1) {
            const double off = (-0.5 + (b + 0.5) / n) * wid[k] * geo::kUnitsPerMm;
            const auto [nx, ny] = normal(k);
            p = geo::Point(p.X + std::llround(nx * off), p.Y + std::llround(ny * off));
          }
          if (!cur.pts.empty()) {
            if (cur.pts.back() == p) continue;
            // Offset inside a bend tighter than the offset: the point would step backwards.
            const double ax = double(pts[k].X - pts[k - 1].X), ay = double(pts[k].Y - pts[k - 1].Y);
            if (n > 1 && ax * double(p.X - cur.pts.back().X) + ay * double(p.Y - cur.pts.back().Y) <= 0) continue;
            const double t = 0.5 * (wid[k - 1] + wid[k]);
            cur.widths.push_back(static_cast<float>(std::min(t / n + extra, spec.max_width)));
          }
          cur.pts.push_back(p);
        }
        if (cur.widths.size() + 1 != cur.pts.size()) continue;
        // At a free end of the axis the region goes on t/2 beyond it. A bead's round end (a
        // half disc t/(2n) across) reaches t/(2n) and holds less plastic than the square end it
        // stands for: each bead is lengthened by t/2 − t/(2n) + (t/n)·(1 − π/4)/2, so that
        // the plastic matches the region's.
        if (cur.pts.size() >= 2) {
          auto extend = [&](size_t at, size_t from, double t) {
            const geo::Point& p = cur.pts[at];
            const geo::Point& q = cur.pts[from];
            const double l = dist_mm(q, p), e = t * (n - 1) / (2.0 * n) + t / n * (1 - M_PI / 4) / 2;
            if (l <= 0) return p;
            return geo::Point(p.X + std::llround(double(p.X - q.X) * e / l), p.Y + std::llround(double(p.Y - q.Y) * e / l));
          };
          if (i == 0 && a.free_start) {
            cur.pts.insert(cur.pts.begin(), extend(0, 1, wid[0]));
            cur.widths.insert(cur.widths.begin(), cur.widths.front());
          }
          if (j + 1 == np && a.free_end) {
            cur.pts.push_back(extend(cur.pts.size() - 1, cur.pts.size() - 2, wid[np - 1]));
            cur.widths.push_back(cur.widths.back());
          }
          // Where axis paths meet, the beads of each end a quarter of the width short of the
          // junction: the round ends of three or more beads would otherwise pile up on it.
          if (i == 0 && !a.free_start && !closed) trim_start(cur, kJunctionTrim * wid[0]);
          if (j + 1 == np && !a.free_end && !closed) {
            std::reverse(cur.pts.begin(), cur.pts.end());
            std::reverse(cur.widths.begin(), cur.widths.end());
            trim_start(cur, kJunctionTrim * wid[np - 1]);
            std::reverse(cur.pts.begin(), cur.pts.end());
            std::reverse(cur.widths.begin(), cur.widths.end());
          }
        }
        flush(cur, out);
      }
      i = j;
    }
  }
  return out;
}

std::vector<VarBead> blob_loops(const geo::Rings& region, const std::vector<VarBead>& beads, const BeadSpec& spec) {
  std::vector<VarBead> out;
  ClipperLib::Clipper c;
  c.AddPaths(region, ClipperLib::ptSubject, true);
  ClipperLib::PolyTree tree;
  c.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  const double extra = spec.height * (1 - M_PI / 4);
  for (const geo::Polygon& poly : geo::to_polygons(tree)) {
    bool has = false;
    for (const auto& b : beads) {
      for (const auto& p : b.pts)
        if (ClipperLib::PointInPolygon(p, poly.outer) != 0) {
          has = true;
          break;
        }
      if (has) break;
    }
    if (has) continue;
    geo::Rings rings{poly.outer};
    rings.insert(rings.end(), poly.holes.begin(), poly.holes.end());
    double len = 0;
    for (const auto& r : rings) len += geo::length_mm(r);
    const double r_in = len > 0 ? 2 * area_mm2(rings) / len : 0;  // a disc's radius, a square's half side
    if (!(r_in >= spec.min_width)) continue;  // the bead would be narrower than min_width
    const float w = static_cast<float>(std::min(r_in + extra, spec.max_width));
    for (geo::Ring& ring : offset(rings, -0.5 * r_in)) {
      if (ring.size() < 3) continue;
      VarBead b;
      b.pts = std::move(ring);
      b.pts.push_back(b.pts.front());
      b.widths.assign(b.pts.size() - 1, w);
      out.push_back(std::move(b));
    }
  }
  return out;
}

geo::Rings uncovered(const geo::Rings& island, const geo::Rings& covered, double min_width) {
  geo::Rings gaps = difference(island, covered);
  if (gaps.empty()) return gaps;
  return offset_open(gaps, 0, 0.49 * min_width);
}

}  // namespace tranche::toolpath
