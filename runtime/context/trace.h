// Provenance: who set each property, and which rules added or generated G-code, recorded while
// the cascade decides, only when a Trace is attached to the context (Context::set_trace). With
// none attached, deciding does exactly what it did before, plus one pointer test per decision.
#pragma once

#include <cstdint>
#include <string_view>

#include "runtime/schema/schema.h"

namespace tranche::ctx {

enum class When : uint8_t;

// One step of a property's value chain, in the order the cascade took them.
struct TraceStep {
  enum class Source : uint8_t {
    Start,           // the value the stage started from (schema default, or an earlier stage's)
    BuiltinDefault,  // runtime/context/defaults.cpp: `rule` is the built-in rule's index
    Middle,          // the layer between the defaults and the rules (the fill-angle script)
    Rule,            // the compiled rules: `rule` is the RuleSet's rule index, `chunk` its value's code
    Set,             // a plain --set override
  };
  schema::PropId prop = schema::PropId::Speed;
  Source source = Source::Start;
  uint32_t rule = UINT32_MAX;
  uint32_t chunk = UINT32_MAX;
  double value = 0;
  // 0: this step set the property; > 0: a value a rule read as "the property as the rules before
  // it decide it" (`speed = speed * 50%`), one level per such read.
  uint16_t depth = 0;
};

class Trace {
 public:
  virtual ~Trace() = default;
  virtual void step(const TraceStep& s) = 0;
  // Executor `rule` added `text` (lines joined by '\n') at the hook (level, when).
  virtual void hook(schema::Level, When, uint32_t /*rule*/, std::string_view /*text*/) {}
  // Replacer `rule` generated the element's output at `level`.
  virtual void replaced(schema::Level, uint32_t /*rule*/) {}
};

}  // namespace tranche::ctx
