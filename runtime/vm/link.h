// Linking: several programs in cascade order (the first is the lowest layer) into one, which is
// what `tranche slice --rules a.rules --rules b.bundle --set k=v` runs. Rules keep their order,
// so later programs win slot by slot exactly as if their rules had been written after the
// earlier ones. A program without debug information gets placeholder entries naming it, so
// that run-time errors still say which bundle a rule came from. Texts the programs share are
// kept once, so that a name (object.name) has one index in the linked program.
#pragma once

#include <string>
#include <vector>

#include "base/result.h"
#include "runtime/vm/program.h"

namespace tranche::vm {

// `names[i]` names programs[i] in messages (its file). Errors: limits (rules, constants,
// strings), and properties that read each other across programs (a cycle no single file has).
Result<Program> link(std::vector<Program> programs, const std::vector<std::string>& names);

// The order in which the properties of each stage are decided: same-stage properties read by a
// property's candidates (in values and filters) come first. Errors on a cycle.
Result<std::vector<schema::PropId>> property_order(const Program& program);

}  // namespace tranche::vm
