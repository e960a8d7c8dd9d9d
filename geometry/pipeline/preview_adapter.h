// What the preview shows of a planned layer (--export-preview): its paths in bed millimetres as
// the G-code prints them (speeds after the min_layer_time slowdown, flows with their geometric
// corrections), the travels between them, and, from the traces the layer loop recorded, each
// path's provenance: the chain of values of each slot, the executors that wrote around it, the
// replacer that generated it.
#pragma once

#include "geometry/gcode/layer_text.h"
#include "geometry/plan/plan.h"
#include "geometry/preview/preview.h"
#include "geometry/setup/print_setup.h"
#include "runtime/vm/vm.h"

namespace tranche::pipeline {

// `rules` names the rules of the traces (null: no rules); `text` gives the executors' notes
// (null: none).
preview::PreviewLayer preview_layer(const setup::PrintSetup& setup, const plan::LayerPlan& plan,
                                    const gcode::LayerText* text, const vm::RuleSet* rules);

}  // namespace tranche::pipeline
