// The cascade: the one place a property is decided, for every stage of every element of the
// loop (print, layer planning, layer, island, path, piece, cooling) and for `rulec explain`. Its
// layers, lowest first:
//   schema defaults (properties.def) < built-in defaults (defaults.h: speed by path kind, the
//   first layer, the 45°/135° fill-angle alternation) < an optional decider between them and
//   the rules (the --fill-angle-script's angles) < the user's compiled rules (profile, --rules,
//   --set expressions) < the plain --set overrides.
// decide() runs them in that order on one PropertyValues, so each layer sees, and may override,
// what the lower ones gave. The cascade also hands out the rules' executors and replacers.
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
  // `rules` (the compiled user rules, which also execute and replace) must outlive the Cascade.
  static Result<std::unique_ptr<Cascade>> create(const std::vector<std::pair<std::string, std::string>>& sets,
                                                 const Decider* rules = nullptr,
                                                 const Executors* executors = nullptr,
                                                 const Replacers* replacers = nullptr);

  // Puts `d` between the built-in defaults and the rules (the fill-angle script); null removes
  // it. It must outlive the Cascade. Not thread-safe: call before the loop starts.
  void set_middle(const Decider* d) { middle_ = d; }

  // Decides `stage` for the element `c` describes: every layer of the cascade in order. `props`
  // holds the values of earlier stages on entry; `c` reads them (its props are set to `props`).
  Status decide(schema::Stage stage, Context& c, PropertyValues& props) const;
  // The built-in defaults alone: what the layers above them (a script) see as the default.
  Status decide_defaults(schema::Stage stage, Context& c, PropertyValues& props) const;

  // The deepest level whose fields any decision of `stage` reads (see Decider::varies_at).
  schema::Level varies_at(schema::Stage stage) const;
  // Whether any decider, executor or replacer reads `field` (costly fields are computed only then).
  bool reads(schema::FieldId field) const;
  // What the decisions of `stage` depend on for the element `c` describes (Decider::depends,
  // over every decider), and whether anything else reads `field` (Decider::reads_beyond, and
  // every executor and replacer): a field only the decisions of `stage` read is computed only
  // for the elements whose dependence names it.
  Result<Decider::Dependence> depends(schema::Stage stage, const Context& c) const;
  bool reads_beyond(schema::Stage stage, schema::FieldId field) const;

  const Executors* executors() const { return executors_; }
  const Replacers* replacers() const { return replacers_; }
  const Overrides& overrides() const { return overrides_; }

  // The print stage, from the schema defaults: decided once per run, before layer heights.
  Result<PropertyValues> print_props(const Context& print_ctx) const;
  // layer_height (mm) of layer `index` whose bottom is at `z_bottom` mm: first_layer_height on
  // layer 0 and layer_height elsewhere, unless a rule or --set decides otherwise. `print` is
  // the print stage's result. `max_slope` is layer.max_slope (deg); `planned` (mm, > 0), the
  // adaptive planner's height, replaces layer_height as the value rules start from on layers
  // after the first.
  Result<double> layer_height(const Context& print_ctx, const PropertyValues& print, int index, double z_bottom,
                              double max_slope = 0, double planned = 0) const;

 private:
  Cascade() = default;
  BuiltinDefaults defaults_;
  const Decider* middle_ = nullptr;
  const Decider* rules_ = nullptr;
  Overrides overrides_;
  const Executors* executors_ = nullptr;
  const Replacers* replacers_ = nullptr;
};

}  // namespace tranche::ctx
