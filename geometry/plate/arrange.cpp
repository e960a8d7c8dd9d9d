#include "geometry/plate/arrange.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

namespace tranche::plate {
namespace {

constexpr int kMaxVertices = 48;  // hulls with more are circumscribed (a little larger)
constexpr double kEps = 1e-7;     // mm: touching is not overlapping

struct Polygon {
  Convex c;
  Box2 box;
};

Polygon make(Convex c) {
  Polygon p{std::move(c), {}};
  p.box = bounds(p.c);
  return p;
}

bool boxes_meet(const Box2& a, const Box2& b) {
  return a.min.x() <= b.max.x() + kEps && b.min.x() <= a.max.x() + kEps && a.min.y() <= b.max.y() + kEps &&
         b.min.y() <= a.max.y() + kEps;
}

// Translations that keep `item` on the bed.
Convex inner_fit(const Bed& bed, const Box2& item, const Convex& hull) {
  const Vec2 lo = bed.min() - item.min, hi = bed.max() - item.max;
  if (lo.x() > hi.x() + kEps || lo.y() > hi.y() + kEps) return {};
  const Vec2 l = lo.cwiseMin(hi), h = hi.cwiseMax(lo);
  Convex fit = {l, {h.x(), l.y()}, h, {l.x(), h.y()}};
  if (bed.shape == Bed::Shape::Rectangle) return fit;
  const Convex o = bed.outline();
  for (size_t i = 0; i < o.size() && !fit.empty(); ++i) {
    const Vec2 e = o[(i + 1) % o.size()] - o[i];
    const Vec2 n = Vec2(e.y(), -e.x()).normalized();  // outward for a counter-clockwise outline
    double reach = -1e300;
    for (const Vec2& p : hull) reach = std::max(reach, n.dot(p));
    fit = clip(fit, n, n.dot(o[i]) - reach);
  }
  return fit.size() >= 3 ? fit : Convex{};
}

struct Edge {
  Vec2 p, d;  // from p to p + d
  Box2 box;
};

// The edges of `c` whose bounding boxes meet `box`: the only ones that can cross the other polygon.
std::vector<Edge> edges_near(const Convex& c, const Box2& box) {
  std::vector<Edge> out;
  for (size_t i = 0; i < c.size(); ++i) {
    Edge e{c[i], c[(i + 1) % c.size()] - c[i], {}};
    e.box.add(c[i]);
    e.box.add(c[i] + e.d);
    if (boxes_meet(e.box, box)) out.push_back(e);
  }
  return out;
}

void edges_crossing(const Polygon& a, const Polygon& b, std::vector<Vec2>& out) {
  const std::vector<Edge> ea = edges_near(a.c, b.box), eb = edges_near(b.c, a.box);
  for (const Edge& r : ea)
    for (const Edge& s : eb) {
      if (!boxes_meet(r.box, s.box)) continue;
      const double d = r.d.x() * s.d.y() - r.d.y() * s.d.x();
      if (std::fabs(d) < 1e-12) continue;
      const Vec2 qp = s.p - r.p;
      const double t = (qp.x() * s.d.y() - qp.y() * s.d.x()) / d, u = (qp.x() * r.d.y() - qp.y() * r.d.x()) / d;
      if (t >= -1e-9 && t <= 1 + 1e-9 && u >= -1e-9 && u <= 1 + 1e-9) out.push_back(r.p + t * r.d);
    }
}

class Arranger {
 public:
  Arranger(const Bed& bed, double spacing) : bed_(bed), half_(std::max(0.0, spacing) / 2) {}

  void fix(const Convex& hull) {
    placed_.push_back(make(inflated(hull, half_)));
    pile_.add(bounds(hull));
  }

  // The move that puts `hull` at the best free place, if there is one.
  std::optional<Vec2> place(const Convex& hull) {
    const Box2 box = bounds(hull);
    const Polygon fit = make(inner_fit(bed_, box, hull));
    if (fit.c.empty()) return std::nullopt;
    const Convex moving = negated(inflated(hull, half_));
    std::vector<Polygon> nfp;
    nfp.reserve(placed_.size());
    for (const Polygon& p : placed_) nfp.push_back(make(minkowski_sum(p.c, moving)));

    std::vector<Vec2> cand(fit.c.begin(), fit.c.end());
    cand.push_back(bed_.center() - box.center());  // the first object goes to the centre
    for (size_t i = 0; i < nfp.size(); ++i) {
      if (!boxes_meet(nfp[i].box, fit.box)) continue;
      cand.insert(cand.end(), nfp[i].c.begin(), nfp[i].c.end());
      edges_crossing(nfp[i], fit, cand);
      for (size_t j = i + 1; j < nfp.size(); ++j)
        if (boxes_meet(nfp[i].box, nfp[j].box)) edges_crossing(nfp[i], nfp[j], cand);
    }
    std::optional<Vec2> best;
    double best_score = 1e300;
    for (const Vec2& t : cand) {
      const double s = score(box, t);
      if (s >= best_score || !free(t, fit, nfp)) continue;
      best = t;
      best_score = s;
    }
    if (best) {
      Convex at = hull;
      for (Vec2& p : at) p += *best;
      fix(at);
    }
    return best;
  }

  const Box2& pile() const { return pile_; }

 private:
  bool free(const Vec2& t, const Polygon& fit, const std::vector<Polygon>& nfp) const {
    if (!inside_or_on(fit.c, t, 1e-6)) return false;
    for (const Polygon& n : nfp) {
      if (t.x() <= n.box.min.x() || t.x() >= n.box.max.x() || t.y() <= n.box.min.y() || t.y() >= n.box.max.y())
        continue;
      if (strictly_inside(n.c, t, kEps)) return false;
    }
    return true;
  }

  // Smaller is better: the pile's area, and its larger side, both relative to the bed's.
  double score(const Box2& item, const Vec2& t) const {
    Box2 b = pile_;
    b.add(Box2{item.min + t, item.max + t});
    const double w = b.size().x() / bed_.size_x_mm, h = b.size().y() / bed_.size_y_mm;
    const double off = ((item.center() + t) - bed_.center()).norm() / (bed_.size_x_mm + bed_.size_y_mm);
    return w * h + std::max(w, h) * std::max(w, h) + 1e-3 * off;
  }

  const Bed& bed_;
  double half_;
  std::vector<Polygon> placed_;  // hulls grown by half the spacing
  Box2 pile_;                    // of the hulls as they are
};

}  // namespace

Arrangement arrange(const std::vector<ArrangeItem>& items, const Bed& bed, double spacing_mm) {
  Arrangement out;
  out.moves.assign(items.size(), Vec2::Zero());
  std::vector<Convex> hulls(items.size());
  for (size_t i = 0; i < items.size(); ++i) hulls[i] = circumscribe(items[i].hull, kMaxVertices);
  // Arranged objects keep the margin from the edges (the skirt round them stays on the bed).
  Bed inner = bed;
  if (bed.margin_mm > 0 && bed.size_x_mm > 2 * bed.margin_mm && bed.size_y_mm > 2 * bed.margin_mm) {
    inner.origin_x_mm += bed.margin_mm, inner.origin_y_mm += bed.margin_mm;
    inner.size_x_mm -= 2 * bed.margin_mm, inner.size_y_mm -= 2 * bed.margin_mm;
  }
  Arranger a(inner, spacing_mm);
  bool any_fixed = false;
  for (size_t i = 0; i < items.size(); ++i) {
    if (!items[i].fixed) continue;
    a.fix(hulls[i]);
    any_fixed = true;
  }
  std::vector<size_t> order;
  for (size_t i = 0; i < items.size(); ++i)
    if (!items[i].fixed) order.push_back(i);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t x, size_t y) { return area(hulls[x]) > area(hulls[y]); });
  std::vector<size_t> moved;
  for (size_t i : order) {
    if (auto t = a.place(hulls[i])) {
      out.moves[i] = *t;
      moved.push_back(i);
    } else {
      out.unfit.push_back(i);
    }
  }
  std::sort(out.unfit.begin(), out.unfit.end());
  if (!any_fixed && !moved.empty()) {  // the pile, centred on the bed, if it still fits there (a round bed)
    const Vec2 shift = bed.center() - a.pile().center();
    const Convex outline = bed.outline();
    bool fits = true;
    for (size_t i : moved)
      for (const Vec2& p : hulls[i]) fits = fits && inside_or_on(outline, p + out.moves[i] + shift, 1e-6);
    if (fits)
      for (size_t i : moved) out.moves[i] += shift;
  }
  return out;
}

}  // namespace tranche::plate
