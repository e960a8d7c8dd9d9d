#include "geometry/toolpath/infill_patterns.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <unordered_map>

#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/edge_grid.h"
#include "geometry/toolpath/zigzag_ring.h"

namespace tranche::toolpath {

using geo::coord_t;
using schema::Border;
using schema::InfillPattern;
using zigzag_detail::End;
using zigzag_detail::Poly;
using zigzag_detail::Ring2;
using zigzag_detail::UV;

namespace {

constexpr double kPi = std::numbers::pi;
// Average length of the gyroid's horizontal section per unit area, times its period (measured
// over 32 heights of one period: 2.451; PrusaSlicer's FillGyroid uses 2.44).
constexpr double kGyroidLength = 2.45;
// The gyroid's period as PrusaSlicer's FillGyroid's, 2π·spacing/(2.44·density) (its DensityAdjust),
// so that a density lays the plastic it does there: 2.45 · 2.44 / 2π = 0.951 × density (a
// period of 2.45·spacing/density, density itself, laid 5 % more than PrusaSlicer's gyroid).
constexpr double kGyroidDensityAdjust = 2.44;
double gyroid_period(double spacing, double density) {
  return 2 * kPi * spacing / (kGyroidDensityAdjust * density);
}

// Rounded to the nearest unit (half away from zero, as llround, without its cost in the
// gyroid's thousands of points per layer).
coord_t round_units(double v) { return static_cast<coord_t>(v < 0 ? v - 0.5 : v + 0.5); }
geo::Point to_pt(double x, double y) { return geo::Point(round_units(x), round_units(y)); }
// Plain length: std::hypot's care for overflow costs more than the rest of the loop here.
double norm(double x, double y) { return std::sqrt(x * x + y * y); }

// Lines of a pattern in its own frame (u along the pattern's angle, v across, mm), turned into
// bed units at the end.
class Frame {
 public:
  Frame(double angle_deg, double x0, double y0, double x1, double y1)
      : c_(std::cos(angle_deg * kPi / 180)), s_(std::sin(angle_deg * kPi / 180)) {
    for (double x : {x0, x1})
      for (double y : {y0, y1}) {
        const double u = x * c_ + y * s_, v = -x * s_ + y * c_;
        u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
      }
    // The box's corners in order round it, in the frame.
    const double xs[4] = {x0, x1, x1, x0}, ys[4] = {y0, y0, y1, y1};
    for (int i = 0; i < 4; ++i) corner_[i] = {xs[i] * c_ + ys[i] * s_, -xs[i] * s_ + ys[i] * c_};
  }
  geo::Point bed(double u, double v) const {
    return to_pt((u * c_ - v * s_) * geo::kUnitsPerMm, (u * s_ + v * c_) * geo::kUnitsPerMm);
  }
  // The extent [lo, hi] along u (along v when `across`) of the part of the box whose v (u) lies
  // in [a, b], widened by a micrometre; false when that part is empty. Pattern lines run across
  // the frame's box, which at 45° is twice the box: their pieces outside it are left out before
  // they are drawn (they would be clipped away: the box holds the region with a margin).
  bool extent_within(bool across, double a, double b, double& lo, double& hi) const {
    lo = 1e300, hi = -1e300;
    auto take = [&](double along, double at) {
      if (at >= a && at <= b) lo = std::min(lo, along), hi = std::max(hi, along);
    };
    for (int i = 0; i < 4; ++i) {
      const auto& p = corner_[i];
      const auto& q = corner_[(i + 1) % 4];
      const double pa = across ? p.second : p.first, pc = across ? p.first : p.second;
      const double qa = across ? q.second : q.first, qc = across ? q.first : q.second;
      take(pa, pc);
      for (double c : {a, b})  // where the side crosses c
        if ((pc - c) * (qc - c) < 0) take(pa + (qa - pa) * (c - pc) / (qc - pc), c);
    }
    if (lo > hi) return false;
    lo -= 1e-3, hi += 1e-3;
    return true;
  }
  double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;  // the box's extent in the frame (mm)

 private:
  double c_, s_;
  std::pair<double, double> corner_[4];  // (u, v)
};

// Straight lines at `dir_deg` (from +x), `pitch` apart, through the points whose distance across
// them is offset + k·pitch, covering the box; consecutive lines run opposite ways.
void line_family(geo::Rings& out, double dir_deg, double pitch, double offset, double x0, double y0, double x1,
                 double y1) {
  Frame f(dir_deg, x0, y0, x1, y1);
  const double k0 = std::ceil((f.v0 - offset) / pitch), k1 = std::floor((f.v1 - offset) / pitch);
  for (double k = k0; k <= k1; k += 1) {
    const double v = offset + k * pitch;
    const bool back = static_cast<long long>(k) % 2 != 0;
    geo::Point a = f.bed(back ? f.u1 : f.u0, v), b = f.bed(back ? f.u0 : f.u1, v);
    out.push_back({a, b});
  }
}

// Trapezoid waves drawing flat-topped hexagons of side `a` (mm), plateaus of neighbouring waves
// `gap` apart (one bead: the shared edges printed twice side by side). The plateaus, moved half
// a gap off the hexagon's edge, run on by lo/√3 at each end, so that the slopes keep the
// hexagon's 60° (as PrusaSlicer's FillHoneycomb's do).
void honeycomb(geo::Rings& out, double angle, double a, double gap, double x0, double y0, double x1, double y1) {
  Frame f(angle, x0, y0, x1, y1);
  const double h = a * std::sqrt(3.0) / 2, period = 3 * a;
  const double lo = std::min(0.5 * gap, 0.45 * h), hi = h - lo;  // plateau heights within a wave
  const double e = lo / std::sqrt(3.0);                           // the plateaus' run-on
  const double j0 = std::floor(f.v0 / h) - 1, j1 = std::ceil(f.v1 / h);
  const double n0 = std::floor(f.u0 / period) - 1, n1 = std::ceil(f.u1 / period) + 1;
  for (double j = j0; j <= j1; j += 1) {
    const double base = j * h;
    const double shift = static_cast<long long>(j) % 2 == 0 ? 0.0 : 1.5 * a;  // odd waves mirrored
    // Only the periods that reach the box, and one more on each side.
    double ulo, uhi;
    if (!f.extent_within(false, base + lo, base + hi, ulo, uhi)) continue;
    const double na = std::max(n0, std::floor((ulo - shift - 2.5 * a - e) / period) - 1);
    const double nb = std::min(n1, std::ceil((uhi - shift + e) / period) + 1);
    if (na > nb) continue;
    geo::Ring w;
    w.reserve(static_cast<size_t>(4 * (nb - na + 1)));
    for (double n = na; n <= nb; n += 1) {
      const double u = n * period + shift;
      w.push_back(f.bed(u - e, base + lo));
      w.push_back(f.bed(u + a + e, base + lo));
      w.push_back(f.bed(u + 1.5 * a - e, base + hi));
      w.push_back(f.bed(u + 2.5 * a + e, base + hi));
    }
    if (static_cast<long long>(j) % 2 != 0) std::reverse(w.begin(), w.end());
    out.push_back(std::move(w));
  }
}

// One branch of the gyroid's section at height gz (radians): the coordinate solved for, t, as a
// function of the other one, s (radians), on family `fam` (0 or 1). With |cos gz| ≥ |sin gz|
// it solves sin s cos t + sin t cos gz + sin gz cos s = 0 for t (always solvable then), else
// the same equation with s and t swapped, for s: each curve is then a graph over the free
// coordinate, defined everywhere.
struct GyroidBranch {
  double gz;
  bool swap;
  int fam;
  double cz = std::cos(gz), sz = std::sin(gz);
  double operator()(double s) const {
    double A, B, C;  // A sin t + B cos t = C
    if (!swap) {     // sin s cos t + cos gz sin t = −sin gz cos s
      A = cz, B = std::sin(s), C = -sz * std::cos(s);
    } else {  // cos s sin t + sin gz cos t = −sin s cos gz  (t: x, s: y)
      A = std::cos(s), B = sz, C = -std::sin(s) * cz;
    }
    const double R = norm(A, B), phi = std::atan2(B, A);  // A sin t + B cos t = R sin(t + φ)
    const double q = std::asin(std::clamp(C / R, -1.0, 1.0));
    return (fam == 0 ? q : kPi - q) - phi;
  }
};

// The gyroid's section, period `period` mm, at height z (mm), in the frame at `angle`.
void gyroid(geo::Rings& out, double angle, double period, double z, double x0, double y0, double x1, double y1) {
  Frame f(angle, x0, y0, x1, y1);
  const double w = 2 * kPi / period, gz = w * z;
  const bool swap = std::abs(std::cos(gz)) < std::abs(std::sin(gz));
  // Free coordinate s runs along u (curves t = v(u)) or, swapped, along v (curves u(v)).
  const double s0 = (swap ? f.v0 : f.u0) * w, s1 = (swap ? f.v1 : f.u1) * w;
  const double t0 = (swap ? f.u0 : f.v0) * w, t1 = (swap ? f.u1 : f.v1) * w;
  // Chords within 50 µm of the curve (an eighth of a bead; PrusaSlicer's FillGyroid allows up
  // to 0.2 mm), from steps of an eighth of a period refined where the curve bends: about 9.5
  // points a period, against 16.5 from steps of π/8 at 20 µm, which doubled the G-code's moves
  // (and the clipping's, linking's and writer's work) with no visible change.
  const double tol = 0.05 * w;  // in radians
  auto add = [&](geo::Ring& ring, double s, double t) {
    ring.push_back(swap ? f.bed(t / w, s / w) : f.bed(s / w, t / w));
  };
  const double step = kPi / 4;
  for (int fam = 0; fam < 2; ++fam) {
    GyroidBranch g{gz, swap, fam};
    // The branch once, unwrapped (continuous), then copied for every period across.
    std::vector<std::pair<double, double>> pts;
    auto unwrap = [](double t, double near) { return t + 2 * kPi * std::round((near - t) / (2 * kPi)); };
    double s = s0 - step, t = g(s);
    pts.push_back({s, t});
    // Refines the piece from (sa, ta) to (sb, tb) until its middle lies within tol of the chord.
    auto refine = [&](auto&& self, double sa, double ta, double sb, double tb, int depth) -> void {
      const double sm = 0.5 * (sa + sb), tm = unwrap(g(sm), 0.5 * (ta + tb));
      const double dev = std::abs(tm - 0.5 * (ta + tb)) * (sb - sa) / norm(sb - sa, tb - ta);
      if (depth < 12 && dev > tol) {
        self(self, sa, ta, sm, tm, depth + 1);
        self(self, sm, tm, sb, tb, depth + 1);
      } else {
        pts.push_back({sb, tb});
      }
    };
    while (s < s1 + step) {
      const double sn = s + step, tn = unwrap(g(sn), t);
      refine(refine, s, t, sn, tn, 0);
      s = sn, t = tn;
    }
    // Copies 2π apart, those that reach [t0, t1] only.
    double lo = 1e300, hi = -1e300;
    for (const auto& q : pts) lo = std::min(lo, q.second), hi = std::max(hi, q.second);
    for (double k = std::floor((t0 - hi) / (2 * kPi)); k <= std::ceil((t1 - lo) / (2 * kPi)); k += 1) {
      const double dt = 2 * kPi * k;
      if (hi + dt < t0 || lo + dt > t1) continue;
      // The points whose s reaches the box across this copy's range of t, and one more each side
      // (pts run by increasing s).
      double slo, shi;
      if (!f.extent_within(swap, (lo + dt) / w, (hi + dt) / w, slo, shi)) continue;
      auto first = std::lower_bound(pts.begin(), pts.end(), slo * w,
                                    [](const std::pair<double, double>& q, double v) { return q.first < v; });
      auto last = std::upper_bound(pts.begin(), pts.end(), shi * w,
                                   [](double v, const std::pair<double, double>& q) { return v < q.first; });
      if (first != pts.begin()) --first;
      if (last != pts.end()) ++last;
      if (last - first < 2) continue;
      geo::Ring ring;
      ring.reserve(static_cast<size_t>(last - first));
      for (auto it = first; it != last; ++it) add(ring, it->first, it->second + dt);
      out.push_back(std::move(ring));
    }
  }
}

// Whether a ring edge lies near a point, over a grid of the rings' edges (1 mm cells, or coarser
// over a large box; each edge listed in the cells its box grown by `reach` meets).
class NearEdges {
 public:
  NearEdges(const std::vector<Ring2>& rings, double reach) : rings_(rings) {
    double x1 = -1e300, y1 = -1e300;
    for (const auto& r : rings)
      for (const UV& q : r.pts) x0_ = std::min(x0_, q.u), y0_ = std::min(y0_, q.v), x1 = std::max(x1, q.u), y1 = std::max(y1, q.v);
    if (x0_ > x1) return;
    x0_ -= reach, y0_ -= reach, x1 += reach, y1 += reach;
    cell_ = std::max(1e6, std::sqrt((x1 - x0_) * (y1 - y0_) / 4e6));
    nx_ = static_cast<long long>((x1 - x0_) / cell_) + 1;
    ny_ = static_cast<long long>((y1 - y0_) / cell_) + 1;
    start_.assign(static_cast<size_t>(nx_ * ny_ + 1), 0);
    auto each = [&](auto&& f) {
      for (uint32_t r = 0; r < rings.size(); ++r) {
        const auto& p = rings[r].pts;
        for (uint32_t i = 0; i < p.size(); ++i) {
          const UV &a = p[i], &b = p[(i + 1) % p.size()];
          const long long cx0 = cx(std::min(a.u, b.u) - reach), cx1 = cx(std::max(a.u, b.u) + reach);
          const long long cy0 = cy(std::min(a.v, b.v) - reach), cy1 = cy(std::max(a.v, b.v) + reach);
          for (long long y = cy0; y <= cy1; ++y)
            for (long long x = cx0; x <= cx1; ++x) f(static_cast<size_t>(y * nx_ + x), r, i);
        }
      }
    };
    each([&](size_t c, uint32_t, uint32_t) { ++start_[c + 1]; });
    for (size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    items_.resize(start_.back());
    std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
    each([&](size_t c, uint32_t r, uint32_t i) { items_[fill[c]++] = {r, i}; });
  }
  // Whether an edge lies within `d` of p (d at most the reach).
  bool within(UV p, double d) const {
    if (start_.empty() || p.u < x0_ || p.v < y0_) return false;
    const long long x = static_cast<long long>((p.u - x0_) / cell_), y = static_cast<long long>((p.v - y0_) / cell_);
    if (x >= nx_ || y >= ny_) return false;
    const size_t c = static_cast<size_t>(y * nx_ + x);
    for (uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
      const auto& pts = rings_[items_[k].first].pts;
      const uint32_t i = items_[k].second;
      if (distance(p, pts[i], pts[(i + 1) % pts.size()]) <= d) return true;
    }
    return false;
  }
  static double distance(UV p, UV a, UV b) {
    const double du = b.u - a.u, dv = b.v - a.v, l2 = du * du + dv * dv;
    const double t = l2 > 0 ? std::clamp(((p.u - a.u) * du + (p.v - a.v) * dv) / l2, 0.0, 1.0) : 0.0;
    return std::hypot(p.u - a.u - t * du, p.v - a.v - t * dv);
  }

 private:
  long long cx(double u) const { return std::clamp(static_cast<long long>((u - x0_) / cell_), 0LL, nx_ - 1); }
  long long cy(double v) const { return std::clamp(static_cast<long long>((v - y0_) / cell_), 0LL, ny_ - 1); }
  const std::vector<Ring2>& rings_;
  double x0_ = 1e300, y0_ = 1e300, cell_ = 1e6;
  long long nx_ = 0, ny_ = 0;
  std::vector<uint32_t> start_;  // CSR: the edges of cell c are items_[start_[c] .. start_[c + 1])
  std::vector<std::pair<uint32_t, uint32_t>> items_;
};

std::vector<Ring2> to_ring2(const geo::Rings& rings) {
  std::vector<Ring2> out;
  for (const auto& r : rings) {
    Ring2 q;
    for (const auto& p : r) q.pts.push_back({static_cast<double>(p.X), static_cast<double>(p.Y)});
    q.kinds.assign(q.pts.size(), geo::EdgeKind::Real);
    out.push_back(std::move(q));
  }
  return out;
}

// The region the lines are clipped to: the shape (its rings disjoint, outer ones counter-clockwise)
// less a band `inset` wide along its artificial edges; each of its edges is artificial when it
// runs along such a band.
std::vector<Ring2> clip_rings(const FillShape& shape, double inset, geo::Rings& rings) {
  // Runs of artificial edges as open polylines (a ring artificial all round: a closed line), so
  // that the band is one offset per run: offset edge by edge, the round ends of every two
  // neighbours overlapped, and the union that cleaned them was most of the clipping's cost.
  geo::Rings cuts, closed_cuts;
  for (size_t r = 0; r < shape.rings.size(); ++r) {
    const auto& ring = shape.rings[r];
    const size_t n = ring.size();
    if (r >= shape.kinds.size() || n < 3) continue;
    const auto& kinds = shape.kinds[r];
    auto artificial = [&](size_t i) { return kinds[i % n] == geo::EdgeKind::Artificial; };
    size_t start = n;  // a real edge: runs start after it
    for (size_t i = 0; i < n && start == n; ++i)
      if (!artificial(i)) start = i;
    if (start == n) {
      closed_cuts.push_back(ring);
      continue;
    }
    geo::Ring run;
    for (size_t k = 1; k <= n; ++k) {
      const size_t i = (start + k) % n;
      if (artificial(i)) {
        if (run.empty()) run.push_back(ring[i]);
        run.push_back(ring[(i + 1) % n]);
      } else if (!run.empty()) {
        cuts.push_back(std::move(run));
        run.clear();
      }
    }
    if (!run.empty()) cuts.push_back(std::move(run));
  }
  rings = shape.rings;  // disjoint rings (region_shape's): the clipping reads them even-odd
  if ((cuts.empty() && closed_cuts.empty()) || inset <= 0) return to_ring2(rings);
  geo::Rings band;
  ClipperLib::ClipperOffset co(2.0, 5000);
  co.AddPaths(cuts, ClipperLib::jtRound, ClipperLib::etOpenRound);
  co.AddPaths(closed_cuts, ClipperLib::jtRound, ClipperLib::etClosedLine);
  co.Execute(band, inset);
  // The runs as rings for the edge index (which closes every ring): an open run there and back.
  for (auto& c : cuts)
    for (size_t i = c.size() - 1; i-- > 1;) c.push_back(c[i]);
  cuts.insert(cuts.end(), closed_cuts.begin(), closed_cuts.end());
  rings = difference(rings, band);
  std::vector<Ring2> out = to_ring2(rings);
  const std::vector<Ring2> cut2 = to_ring2(cuts);
  const NearEdges near_cut(cut2, inset + 2e4);
  for (auto& q : out)
    for (size_t i = 0; i < q.pts.size(); ++i) {
      const UV &a = q.pts[i], &b = q.pts[(i + 1) % q.pts.size()];
      if (near_cut.within({0.5 * (a.u + b.u), 0.5 * (a.v + b.v)}, inset + 1e4)) q.kinds[i] = geo::EdgeKind::Artificial;
    }
  return out;
}

// The cells of a fine grid over a region's bounding box that no edge's bounding box meets: a
// segment whose bounding box lies in such cells only crosses no edge. A pattern's segments are
// short (a gyroid's half a millimetre, a honeycomb's side): most lie away from the border, and
// this answers them without the edge grid's walk (whose cells are sized for the edges).
class ClearCells {
 public:
  ClearCells(const geo::Rings& region, const geo::BBox2& box) : x0_(box.min_x), y0_(box.min_y) {
    const double w = static_cast<double>(box.max_x - box.min_x) + 1, h = static_cast<double>(box.max_y - box.min_y) + 1;
    cell_ = static_cast<geo::coord_t>(std::max({kCell, std::sqrt(w * h / 4e6), 1.0}));  // at most ~4M cells
    nx_ = static_cast<long long>(w / static_cast<double>(cell_)) + 1;
    ny_ = static_cast<long long>(h / static_cast<double>(cell_)) + 1;
    touched_.assign(static_cast<size_t>(nx_ * ny_), 0);
    // Each edge in pieces a cell long at most, each piece's box (2 units wider, against the
    // rounding of its ends) marked: the cells along the edge and few more, where the edge's own
    // box would mark a square across a diagonal edge.
    const double c = static_cast<double>(cell_);
    for (const geo::Ring& r : region)
      for (size_t i = 0; i < r.size(); ++i) {
        const geo::Point &a = r[i], &b = r[(i + 1) % r.size()];
        const double ax = static_cast<double>(a.X), ay = static_cast<double>(a.Y);
        const double dx = static_cast<double>(b.X - a.X), dy = static_cast<double>(b.Y - a.Y);
        const int pieces = std::max(1, static_cast<int>(std::ceil(std::max(std::abs(dx), std::abs(dy)) / c)));
        for (int k = 0; k < pieces; ++k) {
          const double t0 = static_cast<double>(k) / pieces, t1 = static_cast<double>(k + 1) / pieces;
          const double xa = ax + dx * t0, xb = ax + dx * t1, ya = ay + dy * t0, yb = ay + dy * t1;
          mark(std::min(xa, xb) - 2, std::min(ya, yb) - 2, std::max(xa, xb) + 2, std::max(ya, yb) + 2);
        }
      }
  }
  // Whether segment ab lies in the box and in untouched cells only.
  bool clear(const geo::Point& a, const geo::Point& b) const {
    const geo::coord_t lx = std::min(a.X, b.X), hx = std::max(a.X, b.X);
    const geo::coord_t ly = std::min(a.Y, b.Y), hy = std::max(a.Y, b.Y);
    if (lx < x0_ || ly < y0_) return false;
    const long long c0 = (lx - x0_) / cell_, c1 = (hx - x0_) / cell_, r0 = (ly - y0_) / cell_, r1 = (hy - y0_) / cell_;
    if (c1 >= nx_ || r1 >= ny_) return false;
    for (long long y = r0; y <= r1; ++y)
      for (long long x = c0; x <= c1; ++x)
        if (touched_[static_cast<size_t>(y * nx_ + x)]) return false;
    return true;
  }

 private:
  static constexpr double kCell = 1e6;  // 1 mm
  void mark(double lx, double ly, double hx, double hy) {
    const double c = static_cast<double>(cell_), x0 = static_cast<double>(x0_), y0 = static_cast<double>(y0_);
    const long long c0 = std::clamp(static_cast<long long>(std::floor((lx - x0) / c)), 0LL, nx_ - 1);
    const long long c1 = std::clamp(static_cast<long long>(std::floor((hx - x0) / c)), 0LL, nx_ - 1);
    const long long r0 = std::clamp(static_cast<long long>(std::floor((ly - y0) / c)), 0LL, ny_ - 1);
    const long long r1 = std::clamp(static_cast<long long>(std::floor((hy - y0) / c)), 0LL, ny_ - 1);
    for (long long y = r0; y <= r1; ++y)
      for (long long x = c0; x <= c1; ++x) touched_[static_cast<size_t>(y * nx_ + x)] = 1;
  }
  geo::coord_t x0_, y0_, cell_ = 1;
  long long nx_ = 0, ny_ = 0;
  std::vector<uint8_t> touched_;
};

// Open polylines cut into the pieces inside `region` (its edge grid `grid`): each piece's ends
// lie on the ring edges the polyline crosses there (or on none, for a polyline that starts or
// ends inside). Between two crossings a piece is in or out by the middle of the stretch (exact
// even-odd test), so a polyline through a vertex or along an edge is cut right as well.
std::vector<Poly> clip_lines(const geo::Rings& lines, const geo::Rings& region, const EdgeGrid& grid, uint32_t& lone,
                             double pitch_units) {
  std::vector<Poly> polys;
  auto at = [](const geo::Point& a, const geo::Point& b, double t) {
    return UV{static_cast<double>(a.X) + t * static_cast<double>(b.X - a.X),
              static_cast<double>(a.Y) + t * static_cast<double>(b.Y - a.Y)};
  };
  const geo::BBox2 box = bbox(region);
  const ClearCells clear(region, box);
  auto outside_box = [&](const geo::Point& a, const geo::Point& b) {
    return std::max(a.X, b.X) < box.min_x || std::min(a.X, b.X) > box.max_x || std::max(a.Y, b.Y) < box.min_y ||
           std::min(a.Y, b.Y) > box.max_y;
  };
  for (const geo::Ring& line : lines) {
    if (line.size() < 2) continue;
    bool in = grid.inside(line[0]);
    Poly cur;
    double len = 0;
    auto add = [&](UV p) {
      if (!cur.pts.empty()) {
        len += norm(p.u - cur.pts.back().u, p.v - cur.pts.back().v);
        cur.border.push_back(Border::None);
      }
      cur.pts.push_back(p);
    };
    auto close = [&](End e) {
      e.p = cur.pts.back();
      cur.last = e;
      if (cur.pts.size() >= 2 && len >= 1e3) {  // a micrometre: a line grazing a corner
        cur.area = len * pitch_units;
        polys.push_back(std::move(cur));
      }
      cur = Poly{};
      len = 0;
    };
    if (in) {
      add({static_cast<double>(line[0].X), static_cast<double>(line[0].Y)});
      cur.first = End{lone++, 0, cur.pts[0]};
    }
    for (size_t i = 0; i + 1 < line.size(); ++i) {
      const geo::Point &a = line[i], &b = line[i + 1];
      if (a == b) continue;
      if (!in && outside_box(a, b)) continue;  // no crossing out there
      if (clear.clear(a, b)) {                  // nor there
        if (in) add({static_cast<double>(b.X), static_cast<double>(b.Y)});
        continue;
      }
      const std::vector<EdgeGrid::Hit> hs = grid.hits(a, b);
      for (size_t h = 0; h < hs.size(); ++h) {
        const double t = hs[h].t, next = h + 1 < hs.size() ? hs[h + 1].t : 1.0;
        if (next - t < 1e-12 && h + 1 < hs.size()) continue;  // a vertex: decided by the next hit
        const UV mid = at(a, b, 0.5 * (t + next));
        const bool after = grid.inside(geo::Point(static_cast<coord_t>(std::llround(mid.u)),
                                                  static_cast<coord_t>(std::llround(mid.v))));
        if (after == in) continue;
        const UV p = at(a, b, t);
        if (in) {
          add(p);
          close(End{hs[h].ring, hs[h].edge, p});
        } else {
          add(p);
          cur.first = End{hs[h].ring, hs[h].edge, p};
        }
        in = after;
      }
      if (in) add({static_cast<double>(b.X), static_cast<double>(b.Y)});
    }
    if (in && !cur.pts.empty()) close(End{lone++, 0, cur.pts.back()});
  }
  return polys;
}

// Open polylines to paths along the border: clipped to the region, each end put on its ring
// edge, joined by links along the border, merged points dropped.
std::vector<FillPath> clip_and_link(const geo::Rings& lines, const FillShape& shape, const PatternSpec& spec,
                                    double pitch_mm) {
  geo::Rings region;
  const std::vector<Ring2> rings = clip_rings(shape, spec.artificial_inset_mm * geo::kUnitsPerMm, region);
  if (region.empty()) return {};
  const EdgeGrid grid(region);
  uint32_t lone = static_cast<uint32_t>(rings.size());  // ends on no edge: never linked
  std::vector<Poly> polys = clip_lines(lines, region, grid, lone, pitch_mm * geo::kUnitsPerMm);
  const double u = geo::kUnitsPerMm;
  polys = zigzag_detail::link_along_border(std::move(polys), rings, spec.link_max_mm * u, true,
                                          spec.anchor_mm * u, 0.5 * spec.spacing_mm * u);
  return zigzag_detail::to_fill_paths(polys, [](UV p) { return to_pt(p.u, p.v); });
}

// The point of ring r nearest to p: inserted as a vertex, the ring turned to start there.
geo::Ring start_nearest(const geo::Ring& r, const geo::Point& p) {
  double best = 1e300;
  size_t at = 0;
  geo::Point q = r[0];
  for (size_t i = 0; i < r.size(); ++i) {
    const UV a{static_cast<double>(r[i].X), static_cast<double>(r[i].Y)};
    const UV b{static_cast<double>(r[(i + 1) % r.size()].X), static_cast<double>(r[(i + 1) % r.size()].Y)};
    const double du = b.u - a.u, dv = b.v - a.v, l2 = du * du + dv * dv;
    const double pu = static_cast<double>(p.X), pv = static_cast<double>(p.Y);
    const double t = l2 > 0 ? std::clamp(((pu - a.u) * du + (pv - a.v) * dv) / l2, 0.0, 1.0) : 0.0;
    const double d = std::hypot(pu - a.u - t * du, pv - a.v - t * dv);
    if (d < best) best = d, at = i, q = to_pt(a.u + t * du, a.v + t * dv);
  }
  geo::Ring out{q};
  for (size_t k = 1; k <= r.size(); ++k) {
    const geo::Point& v = r[(at + k) % r.size()];
    if (v != out.back()) out.push_back(v);
  }
  if (out.back() != q) out.push_back(q);  // closed: back to the start
  return out;
}

// Whether `ring` lies between two parallel lines less than `width` units apart, across x, y or
// a diagonal: a disc of diameter `width` cannot fit in it then. (Sums and differences only: it
// runs on every ring before every shrink.)
bool thinner_than(const geo::Ring& ring, double width) {
  if (ring.empty()) return true;
  geo::coord_t lo[4], hi[4];
  for (int k = 0; k < 4; ++k) lo[k] = std::numeric_limits<geo::coord_t>::max(), hi[k] = std::numeric_limits<geo::coord_t>::min();
  for (const geo::Point& p : ring) {
    const geo::coord_t v[4] = {p.X, p.Y, p.X + p.Y, p.Y - p.X};
    for (int k = 0; k < 4; ++k) lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]);
  }
  const double diag = width * std::sqrt(2.0);  // the diagonal sums measure √2 × the width
  return static_cast<double>(hi[0] - lo[0]) < width || static_cast<double>(hi[1] - lo[1]) < width ||
         static_cast<double>(hi[2] - lo[2]) < diag || static_cast<double>(hi[3] - lo[3]) < diag;
}

// `region` (counter-clockwise outers, clockwise holes) less the parts that shrinking by `d`
// units leaves empty for certain: each outer ring too thin for a disc of radius d
// (thinner_than) and every ring inside it (its holes and whatever they hold, thinner still).
// Shrinking a region past its inscribed radius is the costliest offset there is: every moved
// edge crosses every other, and the union that cleans them is quadratic (a sphere's innermost
// loops: 4 ms for a 36-point circle, more than all its other loops).
geo::Rings shrinkable(const geo::Rings& region, double d) {
  std::vector<const geo::Ring*> thin;
  for (const geo::Ring& r : region)
    if (ClipperLib::Area(r) > 0 && thinner_than(r, 2 * d)) thin.push_back(&r);
  if (thin.empty()) return region;
  geo::Rings out;
  for (const geo::Ring& r : region) {
    if (r.empty()) continue;
    bool inside_thin = false;
    for (const geo::Ring* t : thin)
      if (t == &r || ClipperLib::PointInPolygon(r[0], *t) != 0) inside_thin = true;
    if (!inside_thin) out.push_back(r);
  }
  return out;
}

// Concentric loops, outermost first, each joined to the next when the crossing is short and
// stays inside the region.
std::vector<FillPath> concentric(const FillShape& shape, double spacing_mm, double pitch_mm) {
  const geo::Rings region = union_of(shape.rings);
  if (region.empty()) return {};
  const EdgeGrid border(region);
  std::vector<FillPath> out;
  // The first loop half a bead inside the border, touching the walls (as PrusaSlicer's and
  // Cura's concentric infill), the others pitch_mm apart: a narrow region still gets a loop, and
  // the region gets (pitch − spacing) / 2 × its border's length of bead more than the density's.
  // Loop k is the border of the region shrunk by d_k = first + k·pitch, less the parts of it
  // narrower than a bead (whose border would run back over itself): the region shrunk by
  // d_k + half a bead, grown back by half a bead. Erosions by discs add up, so the shrunk region
  // is carried from loop to loop (a pitch further each time) and each loop costs two offsets of
  // that region. Each step starts from a copy
  // simplified to 10 µm: a finely tessellated curve shrunk by many times its edges' length would
  // make every offset edge cross its neighbours'. Infill needs no arc finer than 25 µm
  // (offset_coarse's), and its loops are simplified to 10 µm: the offsets of
  // a finely sliced mesh's outline would otherwise give the G-code five times PrusaSlicer's
  // moves, and the linking and the writer their cost.
  const double first = 0.5 * spacing_mm, half = 0.5 * spacing_mm;
  constexpr geo::coord_t kTol = 10000;
  const double d0 = first + half;
  geo::Rings eroded = offset_coarse(shrinkable(simplify(region, kTol), d0 * geo::kUnitsPerMm), -d0), next;
  for (int k = 0; k < 100000 && !eroded.empty(); ++k, eroded = std::move(next)) {
    // The loop (grown by half a bead) and the next shrunk region, from the same simplified copy.
    const geo::Rings src = simplify(eroded, kTol);
    geo::Rings loops = simplify(offset_coarse(src, half), kTol);
    next = offset_coarse(shrinkable(src, pitch_mm * geo::kUnitsPerMm), -pitch_mm);
    if (loops.empty()) break;
    std::stable_sort(loops.begin(), loops.end(),
                     [](const geo::Ring& a, const geo::Ring& b) { return ClipperLib::Area(a) > ClipperLib::Area(b); });
    for (const geo::Ring& r : loops) {
      if (r.size() < 3) continue;
      // The path whose end is nearest, if the crossing to this loop is short and inside.
      FillPath* join = nullptr;
      geo::Ring loop;
      double best = 1.5 * pitch_mm * geo::kUnitsPerMm;
      const geo::BBox2 rb = geo::bbox(r);
      for (FillPath& fp : out) {
        const geo::Point& e = fp.pts.back();
        const double dx = static_cast<double>(std::max({rb.min_x - e.X, e.X - rb.max_x, geo::coord_t{0}}));
        const double dy = static_cast<double>(std::max({rb.min_y - e.Y, e.Y - rb.max_y, geo::coord_t{0}}));
        if (std::hypot(dx, dy) > best) continue;  // the loop's box is further than the best crossing
        geo::Ring cand = start_nearest(r, e);
        const double d = std::hypot(static_cast<double>(cand[0].X - fp.pts.back().X),
                                    static_cast<double>(cand[0].Y - fp.pts.back().Y));
        if (d <= best && !border.crosses(fp.pts.back(), cand[0])) best = d, join = &fp, loop = std::move(cand);
      }
      if (!join) {
        out.push_back({});
        join = &out.back();
        loop = start_nearest(r, r[0]);
      }
      double len = 0;
      for (size_t i = 0; i < loop.size(); ++i) {
        if (!join->pts.empty()) {
          if (join->pts.back() == loop[i]) continue;
          join->border.push_back(Border::None);
          len += std::hypot(static_cast<double>(loop[i].X - join->pts.back().X),
                            static_cast<double>(loop[i].Y - join->pts.back().Y));
        }
        join->pts.push_back(loop[i]);
      }
      join->area_mm2 += len * geo::kMmPerUnit * pitch_mm;
    }
  }
  std::erase_if(out, [](const FillPath& fp) { return fp.pts.size() < 2; });
  return out;
}

// Honeycomb: half the distance between a hexagon's opposite flat edges (mm), spacing / density
// as PrusaSlicer's FillHoneycomb (see plastic_fraction).
double honeycomb_apothem(double spacing, double density) { return spacing / std::min(density, 1.0); }

}  // namespace

// Honeycomb, hexagons of apothem d = s/ρ: per column d wide and 2√3·d long, two slopes
// 2(d − s)/√3 long and two plateaus (2d + s)/√3 long, (8d − 2s)/√3 of line over 2√3·d² of area:
// ρ(4 − ρ)/3 of it covered with bead (1 at ρ = 1).
double plastic_fraction(schema::InfillPattern pattern, double density) {
  if (!(density > 0)) return 0;
  const double rho = std::min(density, 1.0);
  if (pattern == InfillPattern::Gyroid) return rho * kGyroidLength / gyroid_period(1.0, 1.0);
  return pattern == InfillPattern::Honeycomb ? rho * (4 - rho) / 3 : rho;
}

geo::Rings pattern_lines(const PatternSpec& spec, double x0, double y0, double x1, double y1) {
  geo::Rings out;
  const double s = spec.spacing_mm, rho = spec.density;
  if (!(rho > 0 && s > 0)) return out;
  double angle = std::fmod(spec.angle_deg, 90.0);
  if (angle < 0) angle += 90;
  switch (spec.pattern) {
    case InfillPattern::Grid:
      for (double a : {0.0, 90.0}) line_family(out, angle + a, 2 * s / rho, 0, x0, y0, x1, y1);
      break;
    case InfillPattern::Triangles:
      for (double a : {0.0, 60.0, 120.0}) line_family(out, angle + a, 3 * s / rho, 0, x0, y0, x1, y1);
      break;
    case InfillPattern::Cubic: {
      // The three face directions of cubes standing on a corner cut the plane z in lines that
      // move across by z/√2 as z rises; the horizontal parts of the faces' normals sum to zero,
      // so with the normals at +90°, +150°, +210° of the lines the middle set moves the other way.
      const double pitch = 3 * s / rho, shift = spec.z_mm / std::sqrt(2.0);
      const double shifts[3] = {shift, -shift, shift};
      for (int i = 0; i < 3; ++i)
        line_family(out, angle + 60.0 * i, pitch, std::fmod(shifts[i], pitch), x0, y0, x1, y1);
      break;
    }
    case InfillPattern::Honeycomb:
      honeycomb(out, angle, 2 * honeycomb_apothem(s, rho) / std::sqrt(3.0), s, x0, y0, x1, y1);
      break;
    case InfillPattern::Gyroid:
      gyroid(out, angle, gyroid_period(s, rho), spec.z_mm, x0, y0, x1, y1);
      break;
    case InfillPattern::Zigzag:
    case InfillPattern::Concentric:
    case InfillPattern::Lightning:
      break;
  }
  return out;
}

std::vector<FillPath> clip_fill_lines(const geo::Rings& lines, const FillShape& shape, const PatternSpec& spec) {
  if (!(spec.density > 0 && spec.spacing_mm > 0) || shape.rings.empty() || lines.empty()) return {};
  return clip_and_link(lines, shape, spec, spec.spacing_mm / std::min(spec.density, 1.0));
}

std::vector<FillPath> pattern_fill(const FillShape& shape, const PatternSpec& spec) {
  if (!(spec.density > 0 && spec.spacing_mm > 0) || shape.rings.empty()) return {};
  // Area per length of line: the pattern lays plastic_fraction × area of bead.
  const double pitch = spec.spacing_mm / plastic_fraction(spec.pattern, spec.density);
  if (spec.pattern == InfillPattern::Concentric) return concentric(shape, spec.spacing_mm, pitch);
  const geo::BBox2 b = bbox(shape.rings);
  if (b.empty()) return {};
  const double m = 1.0;  // mm of margin: every line crosses the whole region
  const geo::Rings lines = pattern_lines(spec, geo::to_mm(b.min_x) - m, geo::to_mm(b.min_y) - m,
                                         geo::to_mm(b.max_x) + m, geo::to_mm(b.max_y) + m);
  if (lines.empty()) return {};
  return clip_and_link(lines, shape, spec, pitch);
}

}  // namespace tranche::toolpath
