#include "geometry/toolpath/comb.h"

#include <cmath>

#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/order.h"

namespace tranche::toolpath {

using geo::Point;

Comber::Comber(const geo::Rings& material, double margin_mm)
    : material_(material), shrink_count_(material.size()), margin_mm_(margin_mm) {}

Comber::Comber(const geo::Rings& material, const geo::Rings& ready, const geo::Rings& ready_inner, double margin_mm)
    : material_(material), shrink_count_(material.size()), ready_inner_(ready_inner), margin_mm_(margin_mm) {
  material_.insert(material_.end(), ready.begin(), ready.end());
}

const EdgeGrid& Comber::border() const {
  std::call_once(border_once_, [&] { border_ = EdgeGrid(material_); });
  return border_;
}

void Comber::build_comb() const {
  std::call_once(comb_once_, [&] {
    const geo::Rings shrink(material_.begin(), material_.begin() + static_cast<std::ptrdiff_t>(shrink_count_));
    comb_ = offset_coarse(shrink, -margin_mm_);  // travels need no finer than 25 µm
    comb_.insert(comb_.end(), ready_inner_.begin(), ready_inner_.end());
    comb_grid_ = EdgeGrid(comb_);
  });
}

namespace {
double len_mm(const Point& a, const Point& b) { return std::sqrt(dist2(a, b)) * geo::kMmPerUnit; }
Point at(const Point& a, const Point& b, double t) {
  return Point(a.X + static_cast<geo::coord_t>(std::llround(t * double(b.X - a.X))),
               a.Y + static_cast<geo::coord_t>(std::llround(t * double(b.Y - a.Y))));
}
}  // namespace

double Comber::length_mm(const Point& a, const geo::Ring& via, const Point& b) {
  double len = 0;
  Point prev = a;
  for (const auto& q : via) len += len_mm(prev, q), prev = q;
  return len + len_mm(prev, b);
}

std::optional<Point> Comber::enter(const Point& a, double tol_mm) const {
  build_comb();
  if (comb_.empty()) return std::nullopt;
  if (comb_grid_.inside(a)) return a;
  const double tol = tol_mm * geo::kUnitsPerMm;
  if (auto [d2, q] = nearest_on_rings(comb_, a); d2 <= tol * tol && d2 > 0) {
    double d = std::sqrt(d2), push = 5e3;  // units: 5 µm
    Point in(q.X + static_cast<geo::coord_t>(std::llround(double(q.X - a.X) / d * push)),
             q.Y + static_cast<geo::coord_t>(std::llround(double(q.Y - a.Y) / d * push)));
    if (comb_grid_.inside(in)) return in;
  }
  return std::nullopt;
}

std::optional<geo::Ring> Comber::route(const Point& a, const Point& b, double slack_mm) const {
  build_comb();
  if (comb_.empty() || !comb_grid_.inside(a) || !comb_grid_.inside(b)) return std::nullopt;
  auto hits = comb_grid_.hits(a, b);
  // Through a vertex of a ring (a round hole centred on the line), the crossing is counted for
  // both of its edges: the same segment moved a few nanometres sideways meets each edge once; if
  // it still passes through one, not worth the risk.
  auto through_vertex = [](const std::vector<EdgeGrid::Hit>& hs) {
    if (hs.size() % 2 != 0) return true;
    for (size_t k = 1; k < hs.size(); ++k)
      if (hs[k].t - hs[k - 1].t < 1e-12) return true;
    return false;
  };
  if (through_vertex(hits)) {
    hits = comb_grid_.hits(Point(a.X + 3, a.Y + 7), Point(b.X + 3, b.Y + 7));
    if (through_vertex(hits)) return std::nullopt;
  }
  // Each (exit, entry) pair of crossings is bridged along the ring it crosses, the short way.
  geo::Ring path{a};
  for (size_t k = 0; k < hits.size(); k += 2) {
    const auto &out = hits[k], &in = hits[k + 1];
    if (out.ring != in.ring) return std::nullopt;  // left this island for another one
    const geo::Ring& r = comb_[out.ring];
    const uint32_t n = static_cast<uint32_t>(r.size());
    Point p_out = at(a, b, out.t), p_in = at(a, b, in.t);
    // Forward: vertices out.edge+1 .. in.edge; backward: out.edge .. in.edge+1.
    auto walk = [&](bool forward, geo::Ring& pts) {
      double len = 0;
      Point prev = p_out;
      uint32_t steps = forward ? (in.edge + n - out.edge) % n : (out.edge + n - in.edge) % n;
      for (uint32_t s = 0; s < steps; ++s) {
        uint32_t v = forward ? (out.edge + 1 + s) % n : (out.edge + n - s) % n;
        pts.push_back(r[v]);
        len += len_mm(prev, r[v]);
        prev = r[v];
      }
      return len + len_mm(prev, p_in);
    };
    geo::Ring fwd, bwd;
    double lf = walk(true, fwd), lb = walk(false, bwd);
    path.push_back(p_out);
    const geo::Ring& best = lf <= lb ? fwd : bwd;
    path.insert(path.end(), best.begin(), best.end());
    path.push_back(p_in);
  }
  path.push_back(b);
  if (path.size() > 400) return std::nullopt;
  // Pull tight: from each point jump to the farthest later one in direct sight.
  geo::Ring tight{a};
  size_t i = 0;
  while (i + 1 < path.size()) {
    size_t j = path.size() - 1;
    while (j > i + 1 && !direct(path[i], path[j])) --j;
    if (!direct(path[i], path[j])) return std::nullopt;
    tight.push_back(path[j]);
    i = j;
  }
  double total = 0;
  for (size_t k = 1; k < tight.size(); ++k) total += len_mm(tight[k - 1], tight[k]);
  double straight = len_mm(a, b);
  if (total > std::max(2 * straight, straight + slack_mm)) return std::nullopt;
  return geo::Ring(tight.begin() + 1, tight.end() - 1);
}

}  // namespace tranche::toolpath
