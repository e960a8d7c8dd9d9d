// Incremental parsing (lsp/incremental.h): where items start, that a program parsed from the
// cache checks exactly as one parsed whole, and that an edit parses only the part it touches.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>

#include "compiler/check.h"
#include "compiler/diagnostics.h"
#include "compiler/frontend.h"
#include "lsp/incremental.h"
#include "tests/support/fixtures.h"

namespace fs = std::filesystem;
using namespace tranche;

namespace {

// Every diagnostic (rendered) and the checked tree of `text` checked as `path`.
std::string outcome(const std::string& path, const std::string& text, lsp::ItemCache* cache) {
  compiler::FrontendOptions options;
  options.stdlib_dir = (test::source_dir() / "stdlib").string();
  if (cache)
    options.parser = [cache](const ast::SourceMap& s, uint32_t id, diag::Sink& sink) { return cache->parse(s, id, sink); };
  ast::Program program;
  diag::Sink sink;
  compiler::load_source(program, path, text, options, sink);
  if (compiler::check(program, sink) && !sink.has_errors()) compiler::lint(program, sink);
  sink.finish({});
  std::string out;
  for (const auto& d : sink.all()) out += compiler::render_json(program.sources, d) + "\n";
  if (program.checked) out += ast::dump(program);
  return out;
}

}  // namespace

TEST_CASE("incremental: items start on lines that begin with rule, on, use or param outside brackets") {
  std::string text =
      "# head\nuse \"a\"\nparam x = 1\nrule \"r\" {\n  before layer { gcode \"\"\"\nrule inside\n\"\"\" }\n"
      "  comment \"on { \"\n}\n  on layer.start { }\nrules_are_not_rules = 1\n";
  auto starts = lsp::item_starts(text);
  std::vector<std::string> heads;
  for (uint32_t s : starts) heads.push_back(text.substr(s, text.find('\n', s) - s));
  CHECK(heads == std::vector<std::string>{"# head", "use \"a\"", "param x = 1", "rule \"r\" {", "  on layer.start { }"});
}

TEST_CASE("incremental: every .rules file of the repository checks the same parsed in parts as whole") {
  fs::path root = test::source_dir();
  lsp::ItemCache cache;
  size_t n = 0;
  for (const char* dir : {"stdlib", "examples", "tests/language", "bench/rules"}) {
    for (const auto& e : fs::recursive_directory_iterator(root / dir)) {
      if (!e.is_regular_file() || e.path().extension() != ".rules") continue;
      std::string text = test::read_file(e.path());
      INFO(e.path().string());
      CHECK(outcome(e.path().string(), text, &cache) == outcome(e.path().string(), text, nullptr));
      cache.sweep();
      ++n;
    }
  }
  CHECK(n >= 150);
}

TEST_CASE("incremental: an edit parses the part it changes, and the rest is copied in place") {
  std::string text;
  for (int i = 0; i < 50; ++i) text += "rule \"r" + std::to_string(i) + "\" when layer.index == " + std::to_string(i) + " {\n  speed = 20 mm/s\n}\n";
  lsp::ItemCache cache;
  std::string whole = outcome("/tmp/x.rules", text, nullptr);
  CHECK(outcome("/tmp/x.rules", text, &cache) == whole);
  cache.sweep();
  // One more line in rule 10: the parts after it move down one line and a few bytes on.
  std::string edited = text;
  size_t at = edited.find("speed", edited.find("\"r10\""));
  edited.insert(at, "flow = 1\n  ");
  CHECK(outcome("/tmp/x.rules", edited, &cache) == outcome("/tmp/x.rules", edited, nullptr));
  CHECK(cache.reused() == 49);
  // A syntax error: the whole file is parsed, with the errors `rulec check` gives.
  std::string broken = text;
  broken.insert(broken.find("speed", broken.find("\"r30\"")), "speed = \n");
  CHECK(outcome("/tmp/x.rules", broken, &cache) == outcome("/tmp/x.rules", broken, nullptr));
}
