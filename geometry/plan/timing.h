// The time model: how long a layer plan takes at its decided speeds (the writer's own moves,
// visited by walk_layer, through MotionClock's trapezoids and junction speeds), the layer
// change between two layers, and the min_layer_time slowdown.
#pragma once

#include "geometry/plan/plan.h"
#include "geometry/plan/travel.h"
#include "geometry/toolpath/motion.h"

namespace tranche::plan {

struct LayerTime {
  double total_s = 0;    // the whole layer, from its first travel's end
  double extrude_s = 0;  // the extruding moves alone
  double volume_mm3 = 0;
};

// The time of `plan` (layer height `height_mm`), excluding the travel from the previous layer.
LayerTime layer_time(const LayerPlan& plan, const toolpath::MotionLimits& motion, const TravelPolicy& policy,
                     double height_mm);

// The layer change: retraction (when `retract`), the z move of `height_mm`, and the travel from
// `from` along `via` to `to` (when `from` is given).
double layer_change_time(const geo::Point* from, const geo::Ring& via, const geo::Point& to, bool retract,
                         double height_mm, const toolpath::MotionLimits& motion, const TravelPolicy& policy);

// A speed slowed by `factor` (≤ 1), but not below `min_speed` unless it already was (mm/s).
float slowed(float speed, double factor, double min_speed);

// Sets plan.time_s and plan.extruded_mm3; when the layer is faster than plan.props'
// min_layer_time, slows its extrusions down (not below `min_speed`) and sets plan.slowed.
void time_and_slow_down(LayerPlan& plan, const toolpath::MotionLimits& motion, const TravelPolicy& policy,
                        double min_speed);

}  // namespace tranche::plan
