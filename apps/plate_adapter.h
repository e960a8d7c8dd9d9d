// TRANSITIONAL ADAPTER (issue 13), to be removed when the pipeline takes a plate: run_slice
// reads one model file, so a plate is merged into one mesh in bed coordinates, written to a
// temporary binary STL, and sliced as that file. Known limits until then:
//  - the pipeline centres the merged mesh on the bed: objects keep their places relative to
//    each other, not their absolute places (--center X,Y of the whole plate has no effect);
//  - the G-code header names the temporary file (messages are renamed here to the models).
// A plate of one STL file whose object is only moved (no turn, no scale) is sliced from that
// file itself, so that its G-code stays byte for byte what it was.
#pragma once

#include "base/report.h"
#include "base/result.h"
#include "geometry/pipeline/slice_job.h"
#include "geometry/plate/bed.h"
#include "geometry/plate/plate.h"
#include "runtime/vm/vm.h"

namespace tranche::app {

// The bed the printer profile describes (bed_size_x, bed_size_y; rectangular, origin 0, 0; no
// height limit yet), from the compiled rules and the plain --set overrides.
Result<plate::Bed> bed_from_profile(const pipeline::SliceOptions& options, const vm::RuleSet* rules);

// Slices `plate` (built for `options`) through run_slice.
Result<pipeline::SliceSummary> slice_plate(const pipeline::SliceOptions& options, const plate::Plate& plate,
                                           const std::vector<std::string>& files, const vm::RuleSet* rules,
                                           Report& report);

}  // namespace tranche::app
