// `--rules FILE` (repeatable) and `--set key=EXPRESSION`: the user's rule layers of the cascade,
// compiled (a `.rules` file, parsed here once, on this thread, before any slicing) or loaded (a
// bundle from `rulec build`, verified), then linked in command-line order into one RuleSet that
// the slicer runs (geometry/pipeline receives it; it never parses rules itself).
// Consecutive `.rules` files are compiled together, so that a file `use`d by several of them is
// read once, at its first use, exactly as `rulec check a.rules b.rules` reads them.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "base/report.h"
#include "base/result.h"
#include "runtime/vm/vm.h"

namespace tranche::compiler {

struct RulesInput {
  // The profile below the user's rules: stdlib/defaults.rules, then the printer and the material
  // (stdlib names like `generic-marlin`, or paths to .rules files; "none" for neither).
  bool profile = true;
  std::string printer = "generic-marlin";
  std::string material = "pla";
  std::vector<std::string> files;                                // --rules, in order
  std::vector<std::pair<std::string, std::string>> expressions;  // --set whose value is not a plain value
  std::string stdlib_dir;                                        // empty: the default places
};

// Null when there is nothing to run (no profile, no files, no expressions). Errors: the first compile error, rendered as `rulec check`
// does (file:line:col, the line, the caret, help), with the number of errors; a damaged or
// foreign bundle; a run-time limit of linking. Lint warnings go to `report`.
Result<std::shared_ptr<const vm::RuleSet>> load_rules(const RulesInput& input, Report& report);

}  // namespace tranche::compiler
