// The print level of the slicing loop: decides the print's properties once, then runs every
// layer through plan (parallel) → G-code text (parallel) → file (in order) with TBB's
// pipeline, so only a few layers' toolpaths exist at a time, and writes the header, the start
// G-code (the `before print` executors: the printer profile's), the end G-code (`after print`)
// and the footer. The file appears only when complete (OutputFile).
#pragma once

#include <span>
#include <string>
#include <utility>
#include <vector>

#include "geometry/core/layer.h"
#include "base/report.h"
#include "base/result.h"
#include "runtime/context/hooks.h"

namespace tranche::gcode {

struct GcodeJob {
  std::string output;                  // destination file
  std::span<const geo::Layer> layers;  // every layer, islands resolved
  ctx::Rules rules;                    // cascade (defaults, rules, --set), executors, replacers
  std::string model_name;
  double model_volume_mm3 = 0;  // for print.volume
  geo::BBox2 model_box;         // XY extent centred on the bed; empty: the layers' extent
  std::vector<std::pair<std::string, std::string>> sets;  // --set as given, for the header
  std::vector<std::string> notes;                         // more header lines (profile, rules files)
  int threads = 0;                                        // 0: TBB's default
};

struct GcodeSummary {
  int layers = 0;
  double filament_mm = 0, filament_cm3 = 0, filament_g = 0;
  double time_s = 0;
  int travels = 0, retractions = 0;
};

// Filament density used for the weight estimate, g/cm³ (PLA).
inline constexpr double kFilamentDensity = 1.24;

Result<GcodeSummary> write_gcode(const GcodeJob& job, Report& report);

// "1d 2h 3m 4s" / "27m 8s" / "8s", as PrusaSlicer writes it.
std::string format_duration(double seconds);

}  // namespace tranche::gcode
