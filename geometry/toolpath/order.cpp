#include "geometry/toolpath/order.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <unordered_map>

namespace tranche::toolpath {

using geo::Point;

namespace {
// Turn at vertex i (radians, positive = left turn), from its neighbours.
double turn_at(const geo::Ring& r, size_t i) {
  size_t n = r.size();
  const Point& a = r[(i + n - 1) % n];
  const Point& b = r[i];
  const Point& c = r[(i + 1) % n];
  double ux = double(b.X - a.X), uy = double(b.Y - a.Y), vx = double(c.X - b.X), vy = double(c.Y - b.Y);
  return std::atan2(ux * vy - uy * vx, ux * vx + uy * vy);
}
}  // namespace

size_t choose_seam(const geo::Ring& loop, schema::Seam mode, const Point& from) {
  SeamOptions o;
  o.mode = mode;
  return choose_seam(loop, o, from);
}

namespace {

double edge_mm(const Point& a, const Point& b) { return std::sqrt(dist2(a, b)) * geo::kMmPerUnit; }

// The point at arclength `d` mm from vertex i, walking backwards (dir = -1) or forwards (+1).
Point along(const geo::Ring& r, size_t i, int dir, double d) {
  const size_t n = r.size();
  size_t cur = i;
  for (size_t steps = 0; steps < n; ++steps) {
    size_t next = dir > 0 ? (cur + 1) % n : (cur + n - 1) % n;
    double e = edge_mm(r[cur], r[next]);
    if (e >= d && e > 0) {
      double t = d / e;
      return Point(r[cur].X + static_cast<geo::coord_t>(std::llround(t * double(r[next].X - r[cur].X))),
                   r[cur].Y + static_cast<geo::coord_t>(std::llround(t * double(r[next].Y - r[cur].Y))));
    }
    d -= e;
    cur = next;
  }
  return r[cur];
}

// Turn at vertex i (radians, positive = left) between the points `d` mm before and after it.
double turn_over(const geo::Ring& r, size_t i, double d) {
  const Point a = along(r, i, -1, d), b = r[i], c = along(r, i, +1, d);
  double ux = double(b.X - a.X), uy = double(b.Y - a.Y), vx = double(c.X - b.X), vy = double(c.Y - b.Y);
  if ((ux == 0 && uy == 0) || (vx == 0 && vy == 0)) return 0;
  return std::atan2(ux * vy - uy * vx, ux * vx + uy * vy);
}

// The vertex nearest the point at a fraction u ∈ [0, 1) of the loop's length from vertex 0.
size_t at_fraction(const geo::Ring& loop, double u) {
  const size_t n = loop.size();
  double total = 0;
  for (size_t i = 0; i < n; ++i) total += edge_mm(loop[i], loop[(i + 1) % n]);
  double target = u * total, s = 0;
  for (size_t i = 0; i < n; ++i) {
    double e = edge_mm(loop[i], loop[(i + 1) % n]);
    if (s + e > target) return target - s <= s + e - target ? i : (i + 1) % n;
    s += e;
  }
  return 0;
}

}  // namespace

Point point_at_fraction(const geo::Ring& loop, double u) {
  const size_t n = loop.size();
  if (n == 0) return Point(0, 0);
  double total = 0;
  for (size_t i = 0; i < n; ++i) total += edge_mm(loop[i], loop[(i + 1) % n]);
  double target = u * total, s = 0;
  for (size_t i = 0; i < n; ++i) {
    const Point &a = loop[i], &b = loop[(i + 1) % n];
    double e = edge_mm(a, b);
    if (s + e > target && e > 0) {
      double t = (target - s) / e;
      return Point(a.X + static_cast<geo::coord_t>(std::llround(t * double(b.X - a.X))),
                   a.Y + static_cast<geo::coord_t>(std::llround(t * double(b.Y - a.Y))));
    }
    s += e;
  }
  return loop[0];
}

uint64_t seam_seed(int layer, int island, size_t loop) {
  // splitmix64 over the three numbers: nearby layers get unrelated seams.
  auto mix = [](uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  return mix(mix(mix(static_cast<uint64_t>(static_cast<uint32_t>(layer))) ^ static_cast<uint64_t>(static_cast<uint32_t>(island))) ^
             static_cast<uint64_t>(loop));
}

size_t choose_seam(const geo::Ring& loop, const SeamOptions& options, const Point& from) {
  size_t best = 0, n = loop.size();
  if (n == 0) return 0;
  schema::Seam mode = options.mode;
  if (mode == schema::Seam::Random) return at_fraction(loop, seam_fraction(options.seed));
  if (mode == schema::Seam::Point) {
    double bd = 1e300;
    for (size_t i = 0; i < n; ++i)
      if (double d = dist2(loop[i], options.toward); d < bd) bd = d, best = i;
    return best;
  }
  if (mode == schema::Seam::SharpestCorner) {
    constexpr double kReachMm = 0.5;
    constexpr double kMinTurn = 30.0 * std::numbers::pi / 180.0;
    double length = 0;
    for (size_t i = 0; i < n; ++i) length += edge_mm(loop[i], loop[(i + 1) % n]);
    const double reach = std::min(kReachMm, length / 8);
    double bs = -1e300;
    for (size_t i = 0; i < n; ++i) {
      double t = turn_over(loop, i, reach);
      if (std::abs(t) < kMinTurn) continue;
      // Material is on the left: a right turn is a concave corner. Corners within a degree of
      // each other are equal (slicing jitters them from layer to layer): the rearmost wins.
      double deg = std::round(std::abs(t) * 180.0 / std::numbers::pi);
      double score = (t < 0 ? deg : 0.5 * deg) * 1e4 + geo::to_mm(loop[i].Y) - 1e-6 * geo::to_mm(loop[i].X);
      if (score > bs) bs = score, best = i;
    }
    if (bs > -1e300) return best;
    mode = schema::Seam::Aligned;  // no corner: a smooth loop
  }
  if (mode == schema::Seam::Nearest) {
    double bd = 1e300;
    for (size_t i = 0; i < n; ++i) {
      double d = dist2(loop[i], from);
      if (d < bd) bd = d, best = i;
    }
    return best;
  }
  const bool corners = mode == schema::Seam::Aligned;
  double bs = -1e300;
  for (size_t i = 0; i < n; ++i) {
    double score = geo::to_mm(loop[i].Y) - 1e-6 * geo::to_mm(loop[i].X);
    if (corners) {
      double t = turn_at(loop, i);
      constexpr double kMin = 20.0 * std::numbers::pi / 180.0;
      // Material is on the left: a right turn is a concave corner.
      if (t < -kMin)
        score += 6.0 * (-t / std::numbers::pi);
      else if (t > kMin)
        score += 2.0 * (t / std::numbers::pi);
    }
    if (score > bs) bs = score, best = i;
  }
  return best;
}

namespace {
// Nearest point to p on segment a-b.
Point project(const Point& a, const Point& b, const Point& p) {
  double dx = double(b.X - a.X), dy = double(b.Y - a.Y), l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? std::clamp((double(p.X - a.X) * dx + double(p.Y - a.Y) * dy) / l2, 0.0, 1.0) : 0.0;
  return Point(a.X + static_cast<geo::coord_t>(std::llround(t * dx)),
               a.Y + static_cast<geo::coord_t>(std::llround(t * dy)));
}
}  // namespace

std::pair<double, Point> nearest_on_loop(const geo::Ring& loop, const Point& p) {
  double bd = 1e300;
  Point best = p;
  for (size_t i = 0, n = loop.size(); i < n; ++i) {
    Point q = project(loop[i], loop[(i + 1) % n], p);
    double d = dist2(q, p);
    if (d < bd) bd = d, best = q;
  }
  return {bd, best};
}

std::pair<double, Point> nearest_on_rings(const geo::Rings& rings, const Point& p) {
  std::pair<double, Point> best{1e300, p};
  for (const auto& r : rings)
    if (auto c = nearest_on_loop(r, p); c.first < best.first) best = c;
  return best;
}

size_t insert_vertex(geo::Ring& loop, const Point& q) {
  constexpr double kNear2 = 1e4 * 1e4;  // (10 µm)²
  size_t n = loop.size(), best_v = 0, best_e = 0;
  double dv = 1e300, de = 1e300;
  for (size_t i = 0; i < n; ++i) {
    double d = dist2(loop[i], q);
    if (d < dv) dv = d, best_v = i;
    double e = dist2(project(loop[i], loop[(i + 1) % n], q), q);
    if (e < de) de = e, best_e = i;
  }
  if (n == 0 || dv <= kNear2) return best_v;
  loop.insert(loop.begin() + static_cast<std::ptrdiff_t>(best_e + 1), q);
  return best_e + 1;
}

geo::Ring open_loop_at(const geo::Ring& loop, size_t start) {
  geo::Ring out;
  size_t n = loop.size();
  out.reserve(n + 1);
  for (size_t k = 0; k <= n; ++k) out.push_back(loop[(start + k) % n]);
  return out;
}

std::vector<Visit> chain_open(const std::vector<const geo::Ring*>& paths, const Point& from) {
  std::vector<Visit> order;
  std::vector<char> used(paths.size(), 0);
  Point pos = from;
  for (size_t step = 0; step < paths.size(); ++step) {
    double bd = 1e300;
    size_t bi = 0;
    bool brev = false;
    for (size_t i = 0; i < paths.size(); ++i) {
      if (used[i] || paths[i]->empty()) continue;
      double d0 = dist2(pos, paths[i]->front()), d1 = dist2(pos, paths[i]->back());
      if (d0 < bd) bd = d0, bi = i, brev = false;
      if (d1 < bd) bd = d1, bi = i, brev = true;
    }
    if (bd == 1e300) break;
    used[bi] = 1;
    order.push_back({bi, brev});
    pos = brev ? paths[bi]->front() : paths[bi]->back();
  }
  return order;
}

namespace {

// The paths' ends (index × 2 + 1 for a path's last point, where a reversed run starts) on a hash
// grid, for the greedy order's nearest ends first.
class EndGrid {
 public:
  EndGrid(const std::vector<const geo::Ring*>& paths, double cell) : cell_(cell) {
    for (size_t i = 0; i < paths.size(); ++i) {
      if (paths[i]->empty()) continue;
      for (bool rev : {false, true}) {
        const Point& p = rev ? paths[i]->back() : paths[i]->front();
        const int64_t x = of(p.X), y = of(p.Y);
        if (!any_) x0_ = x1_ = x, y0_ = y1_ = y, any_ = true;
        x0_ = std::min(x0_, x), x1_ = std::max(x1_, x), y0_ = std::min(y0_, y), y1_ = std::max(y1_, y);
        cells_[key(x, y)].push_back(2 * i + (rev ? 1 : 0));
      }
    }
  }
  // Calls visit(i, rev) for the unused ends in rings of cells round p, nearest rings first,
  // until stop(d) for d, a distance (units) no end of the next ring is nearer than.
  template <class Visit, class Stop>
  void scan(const Point& p, const std::vector<char>& used, Visit&& visit, Stop&& stop) const {
    if (!any_) return;
    const int64_t px = of(p.X), py = of(p.Y);
    const int64_t far = std::max({std::abs(px - x0_), std::abs(px - x1_), std::abs(py - y0_), std::abs(py - y1_)});
    for (int64_t r = 0; r <= far; ++r) {
      if (r > 0 && stop(static_cast<double>(r - 1) * cell_)) return;
      for (int64_t x = px - r; x <= px + r; ++x) {
        if (x < x0_ || x > x1_) continue;
        const int64_t dy = std::abs(x - px) == r ? 1 : 2 * r;  // whole column on the ring's sides
        for (int64_t y = py - r; y <= py + r; y += std::max<int64_t>(dy, 1)) {
          if (y < y0_ || y > y1_) continue;
          auto it = cells_.find(key(x, y));
          if (it == cells_.end()) continue;
          for (size_t e : it->second)
            if (!used[e / 2]) visit(e / 2, (e & 1) != 0);
        }
      }
    }
  }

 private:
  int64_t of(geo::coord_t v) const { return static_cast<int64_t>(std::floor(static_cast<double>(v) / cell_)); }
  static uint64_t key(int64_t x, int64_t y) {
    return (static_cast<uint64_t>(x) << 32) ^ static_cast<uint64_t>(static_cast<uint32_t>(y));
  }
  double cell_;
  bool any_ = false;
  int64_t x0_ = 0, x1_ = 0, y0_ = 0, y1_ = 0;
  std::unordered_map<uint64_t, std::vector<size_t>> cells_;
};

}  // namespace

std::vector<Visit> chain_open_best(const std::vector<const geo::Ring*>& paths, const Point& from,
                                   const StepCost& cost, size_t max_tries, const EndCost& end_cost,
                                   const LowerCost& lower, double cell_mm) {
  const size_t n = paths.size();
  auto start_of = [&](size_t i, bool rev) -> const Point& {
    return rev ? paths[i]->back() : paths[i]->front();
  };
  auto end_of = [&](size_t i, bool rev) -> const Point& {
    return rev ? paths[i]->front() : paths[i]->back();
  };
  std::vector<char> used(n);
  // With many paths and a lower bound, the greedy steps look at the nearest ends first.
  std::optional<EndGrid> grid;
  if (lower && n > max_tries && cell_mm > 0) grid.emplace(paths, cell_mm * geo::kUnitsPerMm);
  // Greedy from `first` (or from the cheapest first step when `first` is kStart); returns its cost.
  auto greedy = [&](size_t first, bool first_rev, std::vector<Visit>& order) {
    std::fill(used.begin(), used.end(), 0);
    order.clear();
    double total = 0;
    size_t cur = kStart;
    Point pos = from;
    for (size_t step = 0; step < n; ++step) {
      double bc = 1e300;
      size_t bi = kStart;
      bool brev = false;
      auto consider = [&](size_t i, bool rev) {
        double c = cost(cur, pos, i, start_of(i, rev));
        if (c < bc) bc = c, bi = i, brev = rev;
      };
      if (step == 0 && first != kStart) {
        consider(first, first_rev);
      } else if (grid) {
        // The same choice as the scan below: the cheapest, of equal ones the lowest index, its
        // own direction first.
        grid->scan(
            pos, used,
            [&](size_t i, bool rev) {
              const double c = cost(cur, pos, i, start_of(i, rev));
              if (c < bc || (c == bc && bi != kStart && (i < bi || (i == bi && !rev && brev))))
                bc = c, bi = i, brev = rev;
            },
            [&](double d) { return bi != kStart && lower(d * geo::kMmPerUnit) > bc; });
      } else {
        for (size_t i = 0; i < n; ++i)
          if (!used[i] && !paths[i]->empty()) consider(i, false), consider(i, true);
      }
      if (bi == kStart) break;
      used[bi] = 1;
      order.push_back({bi, brev});
      total += bc;
      cur = bi;
      pos = end_of(bi, brev);
    }
    if (end_cost && !order.empty()) total += end_cost(pos);
    return total;
  };
  std::vector<Visit> best, order;
  double best_cost = greedy(kStart, false, best);
  if (n < (end_cost ? 1 : 2) || n > max_tries) return best;
  for (size_t i = 0; i < n; ++i)
    for (bool rev : {false, true}) {
      if (paths[i]->empty()) continue;
      double c = greedy(i, rev, order);
      if (c < best_cost) best_cost = c, best.swap(order);
    }
  return best;
}

}  // namespace tranche::toolpath
