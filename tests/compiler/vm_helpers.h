// Compiling rule text to a running RuleSet for unit tests, and small sinks and contexts.
#pragma once

#include <doctest/doctest.h>

#include <memory>
#include <string>
#include <vector>

#include "compiler/codegen.h"
#include "runtime/vm/vm.h"
#include "tests/compiler/helpers.h"

namespace tranche::test {

// Compiles `text` (which must check without errors) to a program.
inline vm::Program program(const std::string& text, bool debug = true) {
  Compiled c;
  compile_text(c, text, false);
  for (const auto& d : c.sink.all())
    if (d.severity == diag::Severity::Error) FAIL_CHECK(d.code << ": " << d.message);
  REQUIRE(c.program.checked);
  compiler::CodegenOptions o;
  o.debug = debug;
  auto p = compiler::generate(c.program, o);
  REQUIRE_MESSAGE(p.ok(), (p.ok() ? "" : p.error().to_string()));
  return std::move(*p);
}

// The same, ready to run.
inline std::shared_ptr<const vm::RuleSet> rules(const std::string& text, bool debug = true) {
  auto rs = vm::RuleSet::create(program(text, debug));
  REQUIRE_MESSAGE(rs.ok(), (rs.ok() ? "" : rs.error().to_string()));
  return *rs;
}

struct Lines final : ctx::LineSink {
  std::vector<std::string> lines;
  void line(std::string_view t) override { lines.emplace_back(t); }
  std::string joined() const {
    std::string s;
    for (const auto& l : lines) s += l + "\n";
    return s;
  }
};

// Decides `stage` for a context: props start at the schema defaults (the base of the rules).
inline ctx::PropertyValues decide(const vm::RuleSet& rs, schema::Stage stage, ctx::Context& c,
                                  ctx::PropertyValues props = ctx::PropertyValues::schema_defaults()) {
  c.set_props(&props);
  auto s = rs.decide(stage, c, props);
  REQUIRE_MESSAGE(s.ok(), (s.ok() ? "" : s.error().to_string()));
  return props;
}

}  // namespace tranche::test
