// The cooling stage: the fan, decided once the layer's print time is known (layer.time). Once
// for the whole layer when no rule reads a deeper level for it, else per path (with its island's
// and cell's fields), and recorded in every path's fan and props.
#pragma once

#include "geometry/plan/nest.h"
#include "geometry/plan/plan.h"

namespace tranche::plan {

Status decide_cooling(LayerPlan& plan, Nest& nest);

}  // namespace tranche::plan
