// Words for what a provenance trace recorded (runtime/context/trace.h): a property's value as a
// person writes it, a built-in default as the rule it stands for, and who set each step of a
// value chain (the stage's start, a built-in default, the middle layer, a rule with its
// file:line, --set). Shared by the preview (geometry/pipeline/preview_adapter) and the two
// explain commands (`rulec explain`, `tranche slice --explain`).
#pragma once

#include <cstdint>
#include <string>

#include "runtime/context/trace.h"
#include "runtime/vm/vm.h"

namespace tranche::vm {

// "25 mm/s", "95%", "rear", "true": the value in the property's unit.
std::string value_text(schema::PropId prop, double value);

// Built-in default `i` (ctx::builtin_rules()) as a rule would say it:
// "speed = 25 mm/s when path.kind == outer_perimeter"; empty when there is no such rule.
std::string builtin_rule_text(uint32_t i);

// Who set one step of a chain.
struct StepSource {
  ctx::TraceStep::Source source = ctx::TraceStep::Source::Start;
  std::string rule;  // a rule's name without quotes ("bridges"); empty otherwise
  std::string file;  // the rules file as given (a rule's step); empty otherwise
  uint32_t line = 0; // the line of the rule's assignment (or of the rule itself); 0 when unknown
  std::string text;  // a built-in default's rule text; empty otherwise
  bool read = false; // a value a rule read from the rules before it (`speed = speed * 50%`)
};

// Names the source of `s`; `rules` names the rules (null: rules are named by index).
StepSource step_source(const ctx::TraceStep& s, const RuleSet* rules);

// Where rule `rule` (or its value code `chunk`, when it has one) is written: file and line.
void rule_position(const RuleSet& rules, uint32_t rule, uint32_t chunk, std::string& file, uint32_t& line);

}  // namespace tranche::vm
