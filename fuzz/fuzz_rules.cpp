// libFuzzer target for the rule-language front end: arbitrary bytes are parsed and checked as a
// .rules file, with no file system (`use` finds nothing), then every diagnostic is rendered.
// When the input starts with `--set `, its first line is also tried as a `--set key=value`.
// A file that parses is also formatted (grammar/format.h): the layout must format to itself and
// change nothing but white space and `;`.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "grammar/ast/ast.h"
#include "compiler/check.h"
#include "compiler/diagnostics.h"
#include "compiler/frontend.h"
#include "grammar/format.h"
#include "grammar/parse.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tranche;
  static int runs = 0;
  if (++runs % 2000 == 0) grammar::clear_parser_caches();  // ANTLR's caches only grow

  std::string text(reinterpret_cast<const char*>(data), size);
  compiler::FrontendOptions options;
  options.stdlib_dir = "/nonexistent-tranche-stdlib";
  options.read_file = [](const std::filesystem::path&) -> std::optional<std::string> { return std::nullopt; };
  diag::Sink sink;
  ast::Program program;
  if (text.rfind("--set ", 0) == 0) {
    size_t eol = text.find('\n');
    std::string line = text.substr(6, eol == std::string::npos ? std::string::npos : eol - 6);
    size_t eq = line.find('=');
    if (eq != std::string::npos) compiler::add_set(program, line.substr(0, eq), line.substr(eq + 1), sink);
    text = eol == std::string::npos ? std::string() : text.substr(eol + 1);
  }
  compiler::load_source(program, "fuzz.rules", text, options, sink);
  if (compiler::check(program, sink) && !sink.has_errors()) compiler::lint(program, sink);
  sink.finish({});
  size_t total = 0;
  for (const auto& d : sink.all()) {
    total += compiler::render_text(program.sources, d, true).size();
    total += compiler::render_json(program.sources, d).size();
  }
  if (program.checked) total += ast::dump(program).size();

  ast::SourceMap once_sources;
  diag::Sink format_sink;
  auto once = grammar::format_file(once_sources, once_sources.add("fuzz.rules", text), format_sink);
  if (once) {
    ast::SourceMap twice_sources;
    auto twice = grammar::format_file(twice_sources, twice_sources.add("fuzz.rules", *once), format_sink);
    // What the layout may change: white space (the lexer's: also \f, \v, U+00A0, U+FEFF) and `;`.
    auto skeleton = [](const std::string& t) {
      std::string out;
      for (size_t i = 0; i < t.size(); ++i) {
        if (t.compare(i, 2, "\xC2\xA0") == 0 || t.compare(i, 3, "\xEF\xBB\xBF") == 0) {
          i += t[i] == '\xC2' ? 1 : 2;
          continue;
        }
        if (std::string_view(" \t\r\n\f\v;").find(t[i]) == std::string_view::npos) out += t[i];
      }
      return out;
    };
    if (!twice || *twice != *once || skeleton(*once) != skeleton(text)) __builtin_trap();
  }
  return total == static_cast<size_t>(-1);
}
