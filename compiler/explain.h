// `rulec explain FILE --at "layer.index=3, path.kind=outer_perimeter"`: for one context, which
// rule decided each slot and why every later candidate did not match (the first part of its
// filter that is false, with the values it read), and the order in which the files compose.
#pragma once

#include <string>
#include <vector>

#include "grammar/ast/ast.h"
#include "base/result.h"
#include "runtime/vm/vm.h"

namespace tranche::compiler {

// `program` checked; `rules` generated from it with debug information. `at` is a comma-separated
// list of `field=value` (a number with the field's unit, an enum value, true/false) and
// `property=value` (a value below the rules, as the lower layers of the cascade would give it).
// Errors: an unknown name or a bad value in `at`, a run-time error of the rules.
// `only`: the slots to show (`speed`, `before path`, `replace island`); empty: every slot the rules set.
Result<std::string> explain(const ast::Program& program, const vm::RuleSet& rules, const std::string& at,
                            const std::vector<std::string>& only = {});

}  // namespace tranche::compiler
