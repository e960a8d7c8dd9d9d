// The slicing loop below the print level: it walks the nest layer ⊃ island ⊃ cell ⊃ path ⊃ piece
// and, at each element, fills the context, decides the element's stage through the cascade, runs
// the replacers, and calls a stage for the work: island content (island_content.h), print order
// (print_order.h), travel (travel.h), timing (timing.h), cooling (cooling.h).
// A layer's plan depends only on the (read-only) layers around it: layers run in parallel.
#pragma once

#include "base/result.h"
#include "geometry/plan/plan.h"
#include "geometry/setup/print_setup.h"
#include "runtime/context/cascade.h"

namespace tranche::plan {

// Plans layer `index` of `setup`. Errors: a rule's run-time error (file:line:col).
Result<LayerPlan> plan_layer(const setup::PrintSetup& setup, const ctx::Cascade& cascade, int index);

}  // namespace tranche::plan
