// `--set key=value`: the last layer of the cascade, an implicit rule `{ key = value }` per
// option. Values are a number with an optional unit matching the property (`0.15`, `0.15mm`,
// `20%`, `215C`, `45deg`), an enum value name (`seam=rear`), or true/false.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "runtime/context/hooks.h"

namespace tranche::ctx {

struct Override {
  PropId prop;
  double value;  // in the property's unit
};

// Parses one `key=value` into a property value. Errors name the option and say what to write:
// unknown keys list the close property names; out-of-range values give the range.
Result<Override> parse_override(std::string_view key, std::string_view value);

// Whether `--set key=value` is a plain override (a property and a value parse_override
// accepts), rather than an expression or a `param` of the rules, which the compiler takes.
bool is_plain_override(std::string_view key, std::string_view value);

// A value for the context field `name` as written on a command line (`rulec explain --at`):
// a number with an optional unit of the field, an enum value name, or true/false.
Result<double> parse_field_value(std::string_view name, std::string_view value);

// Property names close to `name` (edit distance, prefix, substring), best first, at most `max`.
std::vector<std::string_view> close_property_names(std::string_view name, size_t max = 3);

// Decider applying the overrides at each property's stage; they never vary with the context.
class Overrides final : public Decider {
 public:
  static Result<Overrides> parse(const std::vector<std::pair<std::string, std::string>>& sets);
  void add(Override o) { items_.push_back(o); }
  const std::vector<Override>& items() const { return items_; }
  Status decide(schema::Stage stage, const Context& ctx, PropertyValues& props) const override;
  schema::Level varies_at(schema::Stage) const override { return schema::Level::Print; }
  bool reads(schema::FieldId) const override { return false; }
  // What a trace calls these values: --set (the top of the cascade), or the middle layer (the
  // values `rulec explain --at` gives below the rules).
  TraceStep::Source recorded_as = TraceStep::Source::Set;

 private:
  std::vector<Override> items_;
};

}  // namespace tranche::ctx
