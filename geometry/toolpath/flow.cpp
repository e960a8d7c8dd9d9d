#include "geometry/toolpath/flow.h"

#include <numbers>

namespace tranche::toolpath {

double bead_area_mm2(double w, double h) {
  if (w <= h) return std::numbers::pi * 0.25 * w * w;
  return (w - h) * h + std::numbers::pi * 0.25 * h * h;
}

double bead_spacing_mm(double w, double h) { return h > 0 ? bead_area_mm2(w, h) / h : w; }

double bead_spacing_mm(double w1, double w2, double h) {
  return 0.5 * (bead_spacing_mm(w1, h) + bead_spacing_mm(w2, h));
}

double filament_area_mm2(double d) { return std::numbers::pi * 0.25 * d * d; }

double e_per_mm(double w, double h, double flow, double d) {
  return bead_area_mm2(w, h) * flow / filament_area_mm2(d);
}

}  // namespace tranche::toolpath
