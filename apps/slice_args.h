// The arguments of `tranche slice`, parsed: CLI11 splits them, every option is declared once (a
// table that also writes --help), and the values are checked with messages that say what an
// option needs. Shared by the executable and the tests.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/result.h"
#include "geometry/pipeline/slice_job.h"
#include "geometry/plate/options.h"

namespace tranche::app {

struct SliceArgs {
  pipeline::SliceOptions slice;  // slice.model: the first model
  plate::PlateOptions plate;     // plate.files: every model
  bool help = false;             // -h/--help: print slice_usage() and nothing else
  uint64_t max_memory_mb = 0;    // --max-memory: the process's address-space limit (0: none), set by main
};

// `args` are the words after `tranche slice`. Errors are usage errors (the caller exits with 2):
// a missing or malformed value, an unknown option, no model. `quiet` is the default of --quiet
// (the caller passes true when stderr is not a terminal).
Result<SliceArgs> parse_slice_args(const std::vector<std::string>& args, bool quiet);

// The --help text: usage, then every option (after "options:" and "plate:"), one per line.
std::string slice_usage();

}  // namespace tranche::app
