#include "geometry/pipeline/slice_job.h"

namespace tranche::pipeline {

Result<SliceSummary> run_slice(const SliceOptions& options, Report& /*report*/) {
  return Error{options.model, "slicing is not implemented yet"};
}

}  // namespace tranche::pipeline
