// `tranche slice` as a library call, for the executable and the end-to-end tests: compiles the
// profile, the --rules files and the --set expressions (compiler/load_rules.h), then runs the
// pipeline on the result (geometry/pipeline/slice_job.h). The two halves meet only here, so the
// slicer's libraries never depend on the rule compiler.
#pragma once

#include "base/report.h"
#include "base/result.h"
#include "geometry/pipeline/slice_job.h"

namespace tranche::app {

Result<pipeline::SliceSummary> slice(const pipeline::SliceOptions& options, Report& report);

}  // namespace tranche::app
