// `tranche slice MODEL --explain "layer=12 island=0 path=outer_perimeter"`: the real contexts of
// a real slice explained. The layer is planned with provenance recorded, as for the preview
// (preview_adapter.h), and for each matching path the explanation lists every recorded slot's
// value with its chain (schema default -> built-in default -> each rule with file:line -> --set
// -> the slicer's min_layer_time slowdown), the executors that wrote G-code around the path and
// the replacer that generated it, or that the default G-code printed it.
#pragma once

#include <optional>
#include <string>

#include "base/result.h"
#include "geometry/preview/preview.h"
#include "geometry/setup/print_setup.h"
#include "runtime/context/cascade.h"
#include "runtime/vm/vm.h"

namespace tranche::pipeline {

// Which paths: `layer=N` (required), then any of `island=N`, `path=KIND` (a path.kind value) or
// `path=N` (the island's Nth path in print order), `cell=N`, `perimeter=N` (0 = outermost);
// separated by spaces or commas.
struct ExplainSpec {
  int layer = -1;
  int island = -1, path = -1, cell = -1, perimeter = -1;  // -1: any
  std::optional<schema::PathKind> kind;
};

// Errors (where "--explain"): an unknown key, a value that is not a whole number or a path
// kind, no layer.
Result<ExplainSpec> parse_explain_spec(const std::string& spec);

// The explanation of the paths of `setup` that `spec` selects. Errors: a layer past the top, an
// island the layer does not have, no path matching (the message lists what the layer has).
Result<std::string> explain_slice(const setup::PrintSetup& setup, const ctx::Cascade& cascade,
                                  const vm::RuleSet* rules, const ExplainSpec& spec);

// One path's provenance as text, each line starting with `indent`: the slots with their chains,
// the executors and the replacer.
std::string provenance_text(const preview::Provenance& p, const std::string& indent);

}  // namespace tranche::pipeline
