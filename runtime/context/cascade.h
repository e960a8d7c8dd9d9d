// The cascade of one run: schema defaults < built-in defaults < the user's compiled rules < --set. Owns the deciders and hands the loop a `Rules`; also decides the two
// things needed before the loop starts: the print stage and each layer's height.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "runtime/context/defaults.h"
#include "runtime/context/overrides.h"

namespace tranche::ctx {

class Cascade {
 public:
  // Errors: a --set that names no property or gives a bad value (see parse_override).
  // `rules` (the compiled user rules, which also execute and replace) comes between the
  // built-in defaults and the --set overrides; it must outlive the Cascade.
  static Result<std::unique_ptr<Cascade>> create(const std::vector<std::pair<std::string, std::string>>& sets,
                                                 const Decider* rules = nullptr,
                                                 const Executors* executors = nullptr,
                                                 const Replacers* replacers = nullptr);

  const Rules& rules() const { return rules_; }
  const Overrides& overrides() const { return overrides_; }

  // Decides `stage` for the element `c` describes: the built-in defaults, then the rules.
  Status decide(schema::Stage stage, const Context& c, PropertyValues& props) const;
  // The print stage, from the schema defaults.
  Result<PropertyValues> print_props(const Context& print_ctx) const;
  // layer_height (mm) of layer `index` whose bottom is at `z_bottom` mm: first_layer_height on
  // layer 0 and layer_height elsewhere, unless a rule or --set decides otherwise.
  Result<double> layer_height(const Context& print_ctx, const PropertyValues& print, int index,
                              double z_bottom) const;

 private:
  Cascade() = default;
  BuiltinDefaults defaults_;
  Overrides overrides_;
  DeciderChain chain_;
  Rules rules_;
};

}  // namespace tranche::ctx
