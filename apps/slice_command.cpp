#include "apps/slice_command.h"

#include "compiler/load_rules.h"
#include "runtime/context/overrides.h"

namespace tranche::app {

Result<pipeline::SliceSummary> slice(const pipeline::SliceOptions& options, Report& report) {
  if (Status s = pipeline::check_options(options); !s) return s.error();
  compiler::RulesInput in;
  in.profile = options.profile;
  in.printer = options.printer;
  in.material = options.material;
  in.stdlib_dir = options.stdlib_dir;
  in.files = options.rules;
  // A --set key that is not a plain property value may be an expression or a `param` of the
  // rules: the compiler knows (and says "did you mean" when it is neither).
  for (const auto& [k, v] : options.sets)
    if (!ctx::is_plain_override(k, v)) in.expressions.emplace_back(k, v);
  auto rules = compiler::load_rules(in, report);
  if (!rules) return rules.error();
  return pipeline::run_slice(options, rules->get(), report);
}

}  // namespace tranche::app
