// Travel and retraction: the one policy for every travel, inside a layer (between two paths)
// and across a layer change (from the layer below's last point). A travel that would leave the
// part is routed around inside it (combing) when that is not much longer; it retracts only if
// it still leaves the part, or is long.
#pragma once

#include <optional>

#include "geometry/core/geom.h"
#include "geometry/plan/plan.h"
#include "geometry/toolpath/comb.h"
#include "runtime/context/context.h"

namespace tranche::plan {

struct TravelPolicy {
  double retract_mm = 0.8;      // filament pulled back (0: never retract)
  double retract_speed = 35;    // mm/s, of the retraction and of the unretraction
  double before_mm = 2;         // travels shorter than this never retract
  double long_mm = 100;         // travels longer than this always retract
  double travel_speed = 150;    // mm/s

  // From the print stage's retract_length, retract_speed, retract_before_travel,
  // retract_long_travel and travel_speed.
  static TravelPolicy of(const ctx::PropertyValues& print);
  bool can_retract() const { return retract_mm > 0; }
  // Seconds a retraction and its unretraction take together.
  double retract_time_s() const { return 2 * retract_mm / retract_speed; }
  // Whether a travel of `length_mm` retracts, given whether it leaves the material.
  bool retracts(double length_mm, bool leaves) const {
    return can_retract() && (length_mm > long_mm || (length_mm > before_mm && leaves));
  }
};

struct Travel {
  bool retract = false;
  geo::Ring via;          // intermediate points (combing), model units
  double length_mm = 0;   // along via
};

// The travel from `from` to `to` over the material `comber` describes (null: not combed, it
// leaves the part). `enter_mm` > 0: `from` may lie that far outside the material (the layer
// below's last point where the wall slopes inward); the route then steps in first.
Travel route_travel(const toolpath::Comber* comber, const geo::Point& from, const geo::Point& to,
                    const TravelPolicy& policy, double enter_mm = 0);

// Decides the travel into every path of the plan (PathPlan::retract and ::via) and keeps the
// layer's material in plan.comber for the layer change. The first path's travel comes from the
// layer below: it is left to the writer (retract set as a mark). Replacer output moves the nozzle
// where the plan cannot follow: the travel after it, or into a replaced path, retracts.
void plan_travels(LayerPlan& plan, const TravelPolicy& policy);

}  // namespace tranche::plan
