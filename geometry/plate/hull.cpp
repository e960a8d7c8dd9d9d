#include "geometry/plate/hull.h"

#include <algorithm>
#include <cmath>

namespace tranche::plate {
namespace {

double cross(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Index of the lowest vertex (then leftmost): where the edges' angles start at 0.
size_t bottom(const Convex& c) {
  size_t best = 0;
  for (size_t i = 1; i < c.size(); ++i)
    if (c[i].y() < c[best].y() || (c[i].y() == c[best].y() && c[i].x() < c[best].x())) best = i;
  return best;
}

}  // namespace

Convex convex_hull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  Convex h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

double area(const Convex& c) {
  double a = 0;
  for (size_t i = 0, n = c.size(); i < n; ++i) a += cross(c[i], c[(i + 1) % n]);
  return a / 2;
}

Convex circumscribe(const Convex& c, int k) {
  if (static_cast<int>(c.size()) <= k || c.size() < 3) return c;
  std::vector<Vec2> normal(k);
  std::vector<double> support(k, -1e300);
  for (int i = 0; i < k; ++i) {
    const double a = 2 * M_PI * i / k;
    normal[i] = {std::cos(a), std::sin(a)};
    for (const Vec2& p : c) support[i] = std::max(support[i], normal[i].dot(p));
  }
  // Each support line touches `c`, so consecutive lines meet at the polygon's vertices.
  std::vector<Vec2> out;
  for (int i = 0; i < k; ++i) {
    const int j = (i + 1) % k;
    const double det = cross(normal[i], normal[j]);
    out.push_back(Vec2(support[i] * normal[j].y() - support[j] * normal[i].y(),
                       support[j] * normal[i].x() - support[i] * normal[j].x()) /
                  det);
  }
  return convex_hull(std::move(out));
}

Convex minkowski_sum(const Convex& a, const Convex& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  const size_t n = a.size(), m = b.size(), ia = bottom(a), ib = bottom(b);
  Convex out;
  out.reserve(n + m);
  size_t i = 0, j = 0;
  while (i < n || j < m) {
    out.push_back(a[(ia + i) % n] + b[(ib + j) % m]);
    const Vec2 ea = a[(ia + i + 1) % n] - a[(ia + i) % n];
    const Vec2 eb = b[(ib + j + 1) % m] - b[(ib + j) % m];
    const double turn = cross(ea, eb);
    if (j == m || (i < n && turn > 0)) ++i;
    else if (i == n || turn < 0) ++j;
    else ++i, ++j;  // parallel edges: one step on both
  }
  return convex_hull(std::move(out));  // drops the collinear vertices of parallel runs
}

Convex negated(const Convex& c) {
  Convex out;
  out.reserve(c.size());
  for (const Vec2& p : c) out.push_back(-p);
  return out;
}

Convex inflated(const Convex& c, double d) {
  if (d <= 0) return c;
  constexpr int kSides = 16;
  const double r = d / std::cos(M_PI / kSides);
  Convex disc;
  for (int i = 0; i < kSides; ++i) {
    const double a = 2 * M_PI * (i + 0.5) / kSides;
    disc.push_back({r * std::cos(a), r * std::sin(a)});
  }
  return minkowski_sum(c, convex_hull(disc));
}

Convex clip(const Convex& c, const Vec2& n, double offset) {
  Convex out;
  for (size_t i = 0, k = c.size(); i < k; ++i) {
    const Vec2 &p = c[i], &q = c[(i + 1) % k];
    const double dp = n.dot(p) - offset, dq = n.dot(q) - offset;
    if (dp <= 0) out.push_back(p);
    if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) out.push_back(p + (q - p) * (dp / (dp - dq)));
  }
  return out;
}

bool strictly_inside(const Convex& c, const Vec2& p, double eps) {
  if (c.size() < 3) return false;
  for (size_t i = 0, n = c.size(); i < n; ++i) {
    const Vec2 e = c[(i + 1) % n] - c[i];
    const double len = e.norm();
    if (len == 0) continue;
    if (cross(e, p - c[i]) / len <= eps) return false;
  }
  return true;
}

bool inside_or_on(const Convex& c, const Vec2& p, double eps) {
  if (c.size() < 3) return false;
  for (size_t i = 0, n = c.size(); i < n; ++i) {
    const Vec2 e = c[(i + 1) % n] - c[i];
    const double len = e.norm();
    if (len == 0) continue;
    if (cross(e, p - c[i]) / len < -eps) return false;
  }
  return true;
}

Box2 bounds(const Convex& c) {
  Box2 b;
  for (const Vec2& p : c) b.add(p);
  return b;
}

}  // namespace tranche::plate
