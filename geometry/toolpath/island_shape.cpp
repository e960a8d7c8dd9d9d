#include "geometry/toolpath/island_shape.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/toolpath/clip.h"

namespace tranche::toolpath {
namespace {

double dir_deg(const geo::Point& a, const geo::Point& b) {
  return std::atan2(static_cast<double>(b.Y - a.Y), static_cast<double>(b.X - a.X)) * 180 / std::numbers::pi;
}

// Difference of two directions, in [0, 180].
double turn_deg(double a, double b) {
  double d = std::fmod(std::abs(a - b), 360.0);
  return d > 180 ? 360 - d : d;
}

}  // namespace

double longest_edge_angle_deg(const geo::Rings& rings) {
  if (rings.empty() || rings[0].size() < 2) return 0;
  const geo::Ring& r = rings[0];
  const size_t n = r.size();
  auto edge_dir = [&](size_t i) { return dir_deg(r[i], r[(i + 1) % n]); };
  // Start a stretch at an edge that turns from its predecessor, so no stretch wraps around.
  size_t start = 0;
  for (size_t i = 0; i < n; ++i)
    if (turn_deg(edge_dir((i + n - 1) % n), edge_dir(i)) >= 1) {
      start = i;
      break;
    }
  double best = -1, best_dir = 0;
  size_t k = 0;
  while (k < n) {
    const size_t first = (start + k) % n;
    double len = 0;
    size_t last = first;
    do {
      last = (start + k) % n;
      len += std::hypot(static_cast<double>(r[(last + 1) % n].X - r[last].X),
                        static_cast<double>(r[(last + 1) % n].Y - r[last].Y));
      ++k;
    } while (k < n && turn_deg(edge_dir(last), edge_dir((start + k) % n)) < 1);
    if (len > best) {
      best = len;
      best_dir = dir_deg(r[first], r[(last + 1) % n]);
    }
  }
  double a = std::fmod(best_dir, 180.0);
  if (a < 0) a += 180;
  return a >= 180 - 1e-9 ? 0 : a;
}

namespace {

// Round offset by `mm` with an arc tolerance of 1 % of the distance (at least 5 µm): the
// measure compares areas of the order of w², which such arcs do not change.
geo::Rings round_offset(const geo::Rings& rings, double mm) {
  geo::Rings out;
  if (rings.empty()) return out;
  ClipperLib::ClipperOffset co(2.0, std::max(5000.0, 0.01 * std::abs(mm) * geo::kUnitsPerMm));
  co.AddPaths(rings, ClipperLib::jtRound, ClipperLib::etClosedPolygon);
  co.Execute(out, mm * geo::kUnitsPerMm);
  return out;
}

// Whether a disc of diameter `w` rolled inside the island leaves out a part of it at least about
// as long as it is wide (a piece of area w² or more), or all of it: the opening by the disc.
bool thinner_part(const geo::Rings& rings, double w) {
  const geo::Rings eroded = round_offset(rings, -0.5 * w);
  if (area_mm2(eroded) <= 0) return true;
  const geo::Rings opened = round_offset(eroded, 0.5 * w);
  for (const auto& r : difference(rings, opened))
    if (ClipperLib::Orientation(r) && area_mm2(geo::Rings{r}) >= w * w) return true;
  return false;
}

}  // namespace

double min_width_mm(const geo::Rings& island) {
  // Outlines sliced from meshes have many tiny edges: 10 µm of simplification changes no width
  // that is measured to 10 µm, and makes each opening several times cheaper.
  const geo::Rings rings = simplify(island, geo::to_units(0.01));
  if (area_mm2(rings) <= 0) return 0;
  // The smallest such width: double until a disc leaves a part out, then bisect.
  double lo = 0, hi = 0.05;
  while (!thinner_part(rings, hi)) {
    lo = hi;
    hi *= 2;
  }
  while (hi - lo > 0.01) {
    const double mid = 0.5 * (lo + hi);
    (thinner_part(rings, mid) ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

bool is_convex(const geo::Rings& rings) {
  if (rings.size() != 1 || rings[0].size() < 3) return false;
  const geo::Ring& r = rings[0];
  geo::Rings hull = convex_hull(r);
  if (hull.empty()) return false;
  std::vector<geo::Point> corners = hull[0];
  auto less = [](const geo::Point& a, const geo::Point& b) { return a.X < b.X || (a.X == b.X && a.Y < b.Y); };
  std::sort(corners.begin(), corners.end(), less);
  auto on_hull = [&](const geo::Point& p) { return std::binary_search(corners.begin(), corners.end(), p, less); };
  const size_t n = r.size();
  size_t start = 0;
  while (start < n && !on_hull(r[start])) ++start;
  if (start == n) return false;
  // Walking the outline from hull corner to hull corner, every vertex between two corners must
  // lie within the tolerance of the hull edge joining them.
  const double tol = 0.01 * geo::kUnitsPerMm;
  size_t anchor = start;
  for (size_t k = 1; k <= n; ++k) {
    const size_t i = (start + k) % n;
    if (!on_hull(r[i])) continue;
    const geo::Point& a = r[anchor];
    const geo::Point& b = r[i];
    const double ex = static_cast<double>(b.X - a.X), ey = static_cast<double>(b.Y - a.Y);
    const double len = std::hypot(ex, ey);
    for (size_t j = (anchor + 1) % n; j != i; j = (j + 1) % n) {
      const double px = static_cast<double>(r[j].X - a.X), py = static_cast<double>(r[j].Y - a.Y);
      const double inside = len > 0 ? (ex * py - ey * px) / len : std::hypot(px, py);
      if (inside > tol) return false;  // the outline is CCW: inside the hull is to the left
    }
    anchor = i;
  }
  return true;
}

int island_under(const geo::Rings& rings, const geo::Layer& below) {
  const geo::BBox2 box = bbox(rings);
  int best = -1;
  double best_area = 0;
  for (size_t i = 0; i < below.islands.size(); ++i) {
    const geo::Polygon& p = below.islands[i].shape;
    const geo::BBox2 b = geo::bbox(p);
    if (b.empty() || box.empty() || b.max_x < box.min_x || b.min_x > box.max_x || b.max_y < box.min_y ||
        b.min_y > box.max_y)
      continue;
    geo::Rings other{p.outer};
    other.insert(other.end(), p.holes.begin(), p.holes.end());
    const double a = area_mm2(intersection(rings, other));
    if (a > best_area) {
      best_area = a;
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace tranche::toolpath
