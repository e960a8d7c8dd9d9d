// The built-in defaults that depend on the context (speed by path kind, the first layer, the fan,
// the 45°/135° fill-angle alternation). They are the lowest layer of the cascade above the schema
// defaults, written as a small table of rules so that stdlib/defaults.rules can replace it.
#pragma once

#include <span>

#include "runtime/context/hooks.h"

namespace tranche::ctx {

// One built-in rule: `rule when FIELD TEST VALUE { PROP = RESULT }`.
struct BuiltinRule {
  enum class Test : uint8_t { Always, Equals, Odd };
  PropId prop;
  FieldId field;  // ignored for Always
  Test test;
  double operand;  // for Equals
  double result;   // in the property's unit
};

// The table, in cascade order (last match wins).
std::span<const BuiltinRule> builtin_rules();

// Decider for the built-in table: with no --rules this, plus the --set overrides, is the cascade.
class BuiltinDefaults final : public Decider {
 public:
  BuiltinDefaults();
  Status decide(schema::Stage stage, const Context& ctx, PropertyValues& props) const override;
  schema::Level varies_at(schema::Stage stage) const override;
  bool reads(schema::FieldId field) const override;

 private:
  schema::Level varies_[schema::kStageCount];
};

}  // namespace tranche::ctx
