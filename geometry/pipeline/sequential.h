// print_order = sequential: the objects of the plate printed one after the other, each whole,
// lowest first, after a check that the print head (extruder_clearance_radius around the nozzle,
// the gantry extruder_clearance_height above it) cannot hit an object already printed.
#pragma once

#include <string>
#include <vector>

#include "base/result.h"
#include "geometry/core/layer.h"
#include "runtime/context/context.h"

namespace tranche::pipeline {

// One object's print: its layers (its islands only, up to its top) and its top (mm).
struct ObjectPass {
  int object = 0;
  std::vector<geo::Layer> layers;
  double top_mm = 0;
};

// The passes, in print order. Errors name the objects: two closer than the clearance radius, or
// an object other than the last one taller than the clearance height.
Result<std::vector<ObjectPass>> sequential_passes(const std::vector<geo::Layer>& layers,
                                                  const std::vector<std::string>& names,
                                                  const ctx::PropertyValues& print);

}  // namespace tranche::pipeline
