// The canonical layout (grammar/format.h): what it does to spacing, indentation, blocks and
// comments; that it changes only white space and `;`; that it formats its own output to itself;
// and that the stdlib, the examples and the docs' rules blocks are kept formatted.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>

#include "grammar/format.h"
#include "tests/support/fixtures.h"

namespace fs = std::filesystem;
using tranche::grammar::format_file;

namespace {

std::optional<std::string> fmt(const std::string& text, int width = 100) {
  tranche::ast::SourceMap sources;
  uint32_t id = sources.add("t.rules", text);
  tranche::diag::Sink sink;
  tranche::grammar::FormatOptions o;
  o.width = width;
  return format_file(sources, id, sink, o);
}

std::string fmt_ok(const std::string& text, int width = 100) {
  auto out = fmt(text, width);
  REQUIRE_MESSAGE(out.has_value(), text);
  return *out;
}

// The text without white space and `;`: all that formatting may change.
std::string skeleton(const std::string& s) {
  std::string out;
  for (char c : s)
    if (c != ' ' && c != '\t' && c != '\r' && c != '\n' && c != ';') out += c;
  return out;
}

std::vector<fs::path> rule_files(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".rules") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("fmt: spacing around operators, units, brackets and commas") {
  CHECK(fmt_ok("rule \"x\"when layer.index<2{speed=20mm/s*(1+2);flow=1.05}\n") ==
        "rule \"x\" when layer.index < 2 { speed = 20 mm/s * (1 + 2); flow = 1.05 }\n");
  CHECK(fmt_ok("rule { fan = 100 %; fill_angle = 15 ° + - 3deg; width = min( 0.4 mm , 0.5mm ) }\n") ==
        "rule { fan = 100%; fill_angle = 15° + -3 deg; width = min(0.4 mm, 0.5 mm) }\n");
  CHECK(fmt_ok("rule when below . area < layers [ layer.index-1 ] . area{fan=0}\n") ==
        "rule when below.area < layers[layer.index - 1].area { fan = 0 }\n");
  CHECK(fmt_ok("rule when layer.z in 0.1 mm .. 0.3mm and path.kind in(infill,bridge){fan=0}\n") ==
        "rule when layer.z in 0.1 mm..0.3 mm and path.kind in (infill, bridge) { fan = 0 }\n");
  CHECK(fmt_ok("rule { replace path { offset -0.1 mm\nmove to(1 mm,2 mm)travel with speed=1 mm/s } }\n") ==
        "rule {\n  replace path {\n    offset -0.1 mm\n    move to (1 mm, 2 mm) travel with speed = 1 mm/s\n  }\n}\n");
  // Another slicer's `mm/min` stays written as one unit (the checker reports it, E0106); a
  // division by a name or by `min(...)` is spaced as any division.
  CHECK(fmt_ok("rule{speed=1200 mm/min}\n") == "rule { speed = 1200 mm/min }\n");
  CHECK(fmt_ok("rule{width=0.9 mm/min(2,3)/k}\n") == "rule { width = 0.9 mm / min(2, 3) / k }\n");
}

TEST_CASE("fmt: indentation, statements one per line, blank lines, `{` and `else`") {
  CHECK(fmt_ok("rule \"a\"\n{\nspeed = 1 mm/s; flow = 1\n\n\n\n      fan = 0\n\n}\n\n\n\nrule \"b\" { }\n") ==
        "rule \"a\" {\n  speed = 1 mm/s\n  flow = 1\n\n  fan = 0\n}\n\nrule \"b\" { }\n");
  // Two items on one line are split; `else` keeps its line, or follows `}`.
  CHECK(fmt_ok("rule { fan = 0 } rule { flow = 1 }") == "rule { fan = 0 }\nrule { flow = 1 }\n");
  std::string with_else =
      "on layer.start {\n  if layer.index == 1 { gcode \"A\" }\n  else { gcode \"B\" }\n"
      "  if layer.index == 2 {\n    gcode \"C\"\n  } else {\n    gcode \"D\"\n  }\n}\n";
  CHECK(fmt_ok(with_else) == with_else);
  // A statement continued on the next line keeps its break, four spaces further in.
  CHECK(fmt_ok("rule when layer.index > 2\n and path.kind == infill {\n speed = 20 mm/s *\n 2 }\n") ==
        "rule when layer.index > 2\n    and path.kind == infill {\n  speed = 20 mm/s *\n      2\n}\n");
}

TEST_CASE("fmt: a one-line block stays on one line while it fits, else it is broken from the outside in") {
  std::string line = "rule \"x\" { before layer { gcode \"M106 S255\" } }\n";
  CHECK(fmt_ok(line) == line);
  CHECK(fmt_ok(line, 40) == "rule \"x\" {\n  before layer { gcode \"M106 S255\" }\n}\n");
  CHECK(fmt_ok(line, 20) == "rule \"x\" {\n  before layer {\n    gcode \"M106 S255\"\n  }\n}\n");
  // A multi-line block is never joined.
  std::string multi = "rule \"x\" {\n  speed = 20 mm/s\n}\n";
  CHECK(fmt_ok(multi) == multi);
}

TEST_CASE("fmt: comments stay where they are") {
  std::string text =
      "# header\n\n# about a\nrule \"a\" { # after the brace\n  # own line\n  speed = 1 mm/s   # trailing\n\n"
      "  # before the end\n}   # after the rule\n# at the end\n";
  CHECK(fmt_ok(text) ==
        "# header\n\n# about a\nrule \"a\" { # after the brace\n  # own line\n  speed = 1 mm/s # trailing\n\n"
        "  # before the end\n} # after the rule\n# at the end\n");
  // A comment inside a block keeps it broken; one in a filter keeps the line break.
  CHECK(fmt_ok("rule { fan = 0 # off\n}\n") == "rule {\n  fan = 0 # off\n}\n");
  CHECK(fmt_ok("rule when layer.index > 2 and # why\n path.kind == infill { fan = 0 }\n") ==
        "rule when layer.index > 2 and # why\n    path.kind == infill { fan = 0 }\n");
  CHECK(fmt_ok("# only a comment") == "# only a comment\n");
  CHECK(fmt_ok("") == "");
}

TEST_CASE("fmt: strings, templates and triple-quoted text are kept byte for byte") {
  std::string text = "rule {\n  before print {\n    gcode \"\"\"\nG28   ; home\n   G29\n\"\"\"\n"
                     "    comment \"a  {layer.z:.2}  b; c\"\n  }\n}\n";
  CHECK(fmt_ok(text) == text);
}

TEST_CASE("fmt: the byte order mark and CRLF line endings are kept") {
  CHECK(fmt_ok("\xEF\xBB\xBFrule{fan=0}\r\nrule{flow=1}\r\n") == "\xEF\xBB\xBFrule { fan = 0 }\r\nrule { flow = 1 }\r\n");
}

TEST_CASE("fmt: a file with syntax errors is not formatted") {
  CHECK_FALSE(fmt("rule \"x\" { speed = }\n").has_value());
  CHECK_FALSE(fmt("rule \"x\" { speed = 1 mm/s\n").has_value());
  CHECK_FALSE(fmt("rule \"unterminated { }\n").has_value());
}

TEST_CASE("fmt: markdown rules blocks are formatted; the rest of the file and blocks that do not parse are not") {
  std::string md = "# Title\n\n```rules\nrule{fan=0}\n```\n\ntext  with  spaces\n\n```rules\nrule { speed = }\n```\n";
  CHECK(tranche::grammar::format_markdown(md) ==
        "# Title\n\n```rules\nrule { fan = 0 }\n```\n\ntext  with  spaces\n\n```rules\nrule { speed = }\n```\n");
}

TEST_CASE("fmt: every .rules file of the repository formats to itself twice, changing only white space") {
  fs::path root = tranche::test::source_dir();
  size_t n = 0, formatted = 0;
  for (const char* dir : {"stdlib", "examples", "tests", "bench", "fuzz", "docs"}) {
    if (!fs::exists(root / dir)) continue;
    for (const auto& path : rule_files(root / dir)) {
      std::string text = tranche::test::read_file(path);
      auto once = fmt(text);
      if (!once) continue;  // cases of syntax errors
      ++n;
      INFO(path.string());
      CHECK(skeleton(*once) == skeleton(text));
      auto twice = fmt(*once);
      REQUIRE(twice.has_value());
      CHECK(*twice == *once);
      formatted += *once == text;
    }
  }
  CHECK(n >= 150);
  MESSAGE(n << " files, " << formatted << " already in the canonical layout");
}

TEST_CASE("fmt: the stdlib, the examples and the docs' rules blocks are in the canonical layout") {
  fs::path root = tranche::test::source_dir();
  for (const char* dir : {"stdlib", "examples"}) {
    for (const auto& path : rule_files(root / dir)) {
      std::string text = tranche::test::read_file(path);
      auto out = fmt(text);
      INFO(path.string() << " is not formatted: run `rulec fmt " << path.string() << "`");
      REQUIRE(out.has_value());
      CHECK(*out == text);
    }
  }
  for (const auto& e : fs::directory_iterator(root / "docs")) {
    if (e.path().extension() != ".md") continue;
    std::string md = tranche::test::read_file(e.path());
    INFO(e.path().string() << " has rules blocks that are not formatted: run `rulec fmt " << e.path().string()
                           << "`");
    CHECK(tranche::grammar::format_markdown(md) == md);
  }
}
