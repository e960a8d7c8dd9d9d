#include "geometry/toolpath/order.h"

#include <algorithm>
#include <cmath>
#include <numbers>

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
  size_t best = 0, n = loop.size();
  if (n == 0) return 0;
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

std::vector<Visit> chain_open_best(const std::vector<const geo::Ring*>& paths, const Point& from,
                                   const StepCost& cost, size_t max_tries) {
  const size_t n = paths.size();
  auto start_of = [&](size_t i, bool rev) -> const Point& {
    return rev ? paths[i]->back() : paths[i]->front();
  };
  auto end_of = [&](size_t i, bool rev) -> const Point& {
    return rev ? paths[i]->front() : paths[i]->back();
  };
  std::vector<char> used(n);
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
    return total;
  };
  std::vector<Visit> best, order;
  double best_cost = greedy(kStart, false, best);
  if (n < 2 || n > max_tries) return best;
  for (size_t i = 0; i < n; ++i)
    for (bool rev : {false, true}) {
      if (paths[i]->empty()) continue;
      double c = greedy(i, rev, order);
      if (c < best_cost) best_cost = c, best.swap(order);
    }
  return best;
}

}  // namespace tranche::toolpath
