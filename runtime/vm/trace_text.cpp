#include "runtime/vm/trace_text.h"

#include <fmt/format.h>

#include "runtime/context/defaults.h"

namespace tranche::vm {

std::string value_text(schema::PropId prop, double v) {
  const auto& info = schema::property(prop);
  if (info.type == schema::Type::Enum) return std::string(schema::enum_value_name(info.enum_type, static_cast<int>(v)));
  if (info.type == schema::Type::Bool) return v != 0 ? "true" : "false";
  if (info.unit == schema::Unit::Ratio) return fmt::format("{:g}%", v * 100);
  const auto unit = schema::unit_name(info.unit);
  return unit.empty() ? fmt::format("{:g}", v) : fmt::format("{:g} {}", v, unit);
}

std::string builtin_rule_text(uint32_t i) {
  const auto rules = ctx::builtin_rules();
  if (i >= rules.size()) return {};
  const ctx::BuiltinRule& r = rules[i];
  std::string s = fmt::format("{} = {}", schema::property(r.prop).name, value_text(r.prop, r.result));
  const auto& f = schema::field(r.field);
  if (r.test == ctx::BuiltinRule::Test::Equals) {
    const std::string v = f.type == schema::Type::Enum
                              ? std::string(schema::enum_value_name(f.enum_type, static_cast<int>(r.operand)))
                              : fmt::format("{:g}", r.operand);
    s += fmt::format(" when {} == {}", f.name, v);
  } else if (r.test == ctx::BuiltinRule::Test::Odd) {
    s += fmt::format(" when {} is odd", f.name);
  }
  return s;
}

void rule_position(const RuleSet& rules, uint32_t rule, uint32_t chunk, std::string& file, uint32_t& line) {
  auto [f, l] = rules.chunk_source(chunk);
  file = f;
  line = l;
  if (line != 0) return;
  // No value code (a hook, a replacer): the rule's own position, "file:line:col".
  const std::string where = rules.rule_where(rule);
  const size_t a = where.find(':');
  file = where.substr(0, a);
  if (a != std::string::npos) line = static_cast<uint32_t>(std::strtoul(where.c_str() + a + 1, nullptr, 10));
}

StepSource step_source(const ctx::TraceStep& s, const RuleSet* rules) {
  StepSource out;
  out.source = s.source;
  switch (s.source) {
    case ctx::TraceStep::Source::Start:
    case ctx::TraceStep::Source::Middle:
    case ctx::TraceStep::Source::Set:
      break;
    case ctx::TraceStep::Source::BuiltinDefault:
      out.text = builtin_rule_text(s.rule);
      break;
    case ctx::TraceStep::Source::Rule:
      out.read = s.depth > 0;
      if (!rules) {
        out.rule = fmt::format("rule {}", s.rule);
        break;
      }
      out.rule = rules->rule_label(s.rule);
      rule_position(*rules, s.rule, s.chunk, out.file, out.line);
      break;
  }
  return out;
}

}  // namespace tranche::vm
