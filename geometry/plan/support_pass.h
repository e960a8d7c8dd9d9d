// Support material and the brim, planned once before the layer loop (they need every layer).
// Each island's support settings are decided at its island stage, through the same cascade and
// context the layer loop uses, so a rule turns support on or off per island or height (a blocker
// is a rule that sets support = none, an enforcer one that sets normal). Then the island's
// overhang is measured (geometry/support/overhang), overhangs that want support become contacts
// on the layer where the support's top is printed (support_z_gap below them), and
// geometry/support grows the columns. Overhangs left without support are summed per layer for one
// warning naming the worst layers (an error with --strict).
#pragma once

#include "base/report.h"
#include "base/result.h"
#include "geometry/setup/print_setup.h"
#include "runtime/context/cascade.h"

namespace tranche::plan {

struct SupportPassOptions {
  bool strict = false;  // overhangs printed in the air are an error
  bool warn = true;     // report the warnings (once per run: not again for each object printed sequentially)
};

// Fills S.support, S.overhang_area and S.brim. Errors: a rule's run-time error; with strict,
// overhangs printed in the air.
Status plan_support(setup::PrintSetup& S, const ctx::Cascade& C, Report& report, const SupportPassOptions& options);

}  // namespace tranche::plan
