// Compiling rule text in memory for unit tests.
#pragma once

#include <string>

#include "grammar/ast/ast.h"
#include "compiler/check.h"
#include "compiler/frontend.h"

namespace tranche::test {

struct Compiled {
  ast::Program program;
  diag::Sink sink;
  const ast::Rule& rule(size_t i) const { return *program.cascade.at(i); }
  bool has(const std::string& code) const {
    for (const auto& d : sink.all())
      if (d.code == code) return true;
    return false;
  }
};

// Parses and checks `text` as the user file `test.rules` (no file system); lints when clean.
inline void compile_text(Compiled& c, const std::string& text, bool lints = true) {
  compiler::FrontendOptions options;
  options.read_file = [](const std::filesystem::path&) -> std::optional<std::string> { return std::nullopt; };
  compiler::load_source(c.program, "test.rules", text, options, c.sink);
  if (compiler::check(c.program, c.sink) && !c.sink.has_errors() && lints) compiler::lint(c.program, c.sink);
}

}  // namespace tranche::test
