// `tranche slice` as a library call, for the executable and the end-to-end tests: compiles the
// profile, the --rules files and the --set expressions (compiler/load_rules.h), builds the plate
// of the models (geometry/plate: loading, transforms, arrangement, the bed check), then runs the
// pipeline on the result (geometry/pipeline/slice_job.h). The two halves meet only here, so the
// slicer's libraries never depend on the rule compiler.
#pragma once

#include "base/report.h"
#include "base/result.h"
#include "geometry/pipeline/slice_job.h"
#include "geometry/plate/options.h"

namespace tranche::app {

// One model (options.model), as it is: the plate of that one file.
Result<pipeline::SliceSummary> slice(const pipeline::SliceOptions& options, Report& report);

// The plate of plate.files (an SVG drawing is sliced on its own, without plate options).
Result<pipeline::SliceSummary> slice(const pipeline::SliceOptions& options, const plate::PlateOptions& plate,
                                     Report& report);

}  // namespace tranche::app
