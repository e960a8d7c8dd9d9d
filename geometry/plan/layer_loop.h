// The slicing loop below the print level, one function per level: layer ⊃ island ⊃ cell ⊃
// path ⊃ piece. For each element it fills the context, asks the cascade to decide the
// properties of the element's stage (hoisted to the level they vary at), runs replacers, and
// builds the geometry: perimeters along real borders, the fill region split into solid and
// sparse, one zig-zag per cell, print order, travel and retraction, time, cooling.
// A layer's plan depends only on the (read-only) layers around it: layers run in parallel.
#pragma once

#include <span>

#include "geometry/core/layer.h"
#include "geometry/toolpath/motion.h"
#include "geometry/toolpath/plan.h"
#include "base/report.h"
#include "base/result.h"
#include "runtime/context/hooks.h"

namespace tranche::toolpath {

// What every layer task shares, read-only.
struct PrintSetup {
  std::span<const geo::Layer> layers;  // islands already simplified by simplify_mm
  ctx::Rules rules;
  ctx::Context print_ctx;           // print fields set, layer table bound
  ctx::PropertyValues print_props;  // after the print stage
  geo::Point shift;                 // model units + shift = bed units
  MotionLimits motion;
  geo::Rings skirt_around;     // what the skirt surrounds (convex hull of layer 0)
  double simplify_mm = 0.0125;  // mm: island outlines are simplified this much (PrusaSlicer's resolution)
};

// Plans layer `index`. Warnings (cells that are not monotone, ...) go to `report`.
Result<LayerPlan> plan_layer(const PrintSetup& setup, int index, Report& report);

}  // namespace tranche::toolpath
