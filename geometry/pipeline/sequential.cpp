#include "geometry/pipeline/sequential.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/toolpath/clip.h"

namespace tranche::pipeline {
namespace {

using schema::PropId;

// Distance (mm) from point p to segment ab.
double point_segment(const geo::Point& p, const geo::Point& a, const geo::Point& b) {
  const double ax = double(a.X), ay = double(a.Y), dx = double(b.X) - ax, dy = double(b.Y) - ay;
  const double l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((double(p.X) - ax) * dx + (double(p.Y) - ay) * dy) / l2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(double(p.X) - (ax + t * dx), double(p.Y) - (ay + t * dy)) * geo::kMmPerUnit;
}

// Distance (mm) between two convex rings; 0 when they overlap.
double hull_distance(const geo::Ring& a, const geo::Ring& b) {
  if (a.empty() || b.empty()) return 1e300;
  if (toolpath::area_mm2(toolpath::intersection({a}, {b})) > 0) return 0;
  double d = 1e300;
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t j = 0; j < b.size(); ++j) {
      d = std::min(d, point_segment(a[i], b[j], b[(j + 1) % b.size()]));
      d = std::min(d, point_segment(b[j], a[i], a[(i + 1) % a.size()]));
    }
  return d;
}

}  // namespace

Result<std::vector<ObjectPass>> sequential_passes(const std::vector<geo::Layer>& layers,
                                                  const std::vector<std::string>& names,
                                                  const ctx::PropertyValues& print) {
  const size_t n = std::max<size_t>(names.size(), 1);
  std::vector<ObjectPass> passes(n);
  std::vector<geo::Ring> outline(n);  // every outline point of the object, then its convex hull
  for (size_t k = 0; k < n; ++k) passes[k].object = static_cast<int>(k);
  for (const geo::Layer& l : layers) {
    for (auto& p : passes) {
      geo::Layer own;
      own.index = l.index;
      own.z_bottom = l.z_bottom;
      own.z_top = l.z_top;
      own.max_slope = l.max_slope;
      p.layers.push_back(std::move(own));
    }
    for (const geo::Island& island : l.islands) {
      const auto k = static_cast<size_t>(std::clamp(island.object, 0, static_cast<int>(n) - 1));
      passes[k].layers.back().islands.push_back(island);
      passes[k].top_mm = l.z_top;
      outline[k].insert(outline[k].end(), island.shape.outer.begin(), island.shape.outer.end());
    }
  }
  for (size_t k = 0; k < n; ++k) {  // each pass ends at its object's top
    auto& ls = passes[k].layers;
    while (!ls.empty() && ls.back().islands.empty()) ls.pop_back();
    geo::Rings hull = toolpath::convex_hull(outline[k]);
    outline[k] = hull.empty() ? geo::Ring{} : hull[0];
  }
  const double radius = print[PropId::ExtruderClearanceRadius], height = print[PropId::ExtruderClearanceHeight];
  for (size_t a = 0; a < n; ++a)
    for (size_t b = a + 1; b < n; ++b) {
      const double d = hull_distance(outline[a], outline[b]);
      if (d < radius)
        return Error{"print_order = sequential",
                     fmt::format("{} and {} are {:.1f} mm apart; printing one after the other needs {:g} mm "
                                 "(extruder_clearance_radius) so that the print head cannot hit the one printed "
                                 "first: arrange them farther apart (--arrange --spacing {:g}), or print them "
                                 "layer by layer (print_order = layers)",
                                 names[a], names[b], d, radius, std::ceil(radius))};
    }
  // Lowest first, so that only the last can rise above the gantry.
  std::stable_sort(passes.begin(), passes.end(),
                   [](const ObjectPass& x, const ObjectPass& y) { return x.top_mm < y.top_mm; });
  for (size_t i = 0; i + 1 < passes.size(); ++i)
    if (passes[i].top_mm > height)
      return Error{"print_order = sequential",
                   fmt::format("{} is {:.1f} mm tall and {} is printed after it: every object but the last must "
                               "be lower than the gantry (extruder_clearance_height = {:g} mm); print layer by layer "
                               "(print_order = layers), or print the tall ones on their own",
                               names[static_cast<size_t>(passes[i].object)], passes[i].top_mm,
                               names[static_cast<size_t>(passes[i + 1].object)], height)};
  passes.erase(std::remove_if(passes.begin(), passes.end(), [](const ObjectPass& p) { return p.layers.empty(); }),
               passes.end());
  return passes;
}

}  // namespace tranche::pipeline
