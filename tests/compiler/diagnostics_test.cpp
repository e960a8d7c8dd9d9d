#include <doctest/doctest.h>

#include "compiler/diagnostics.h"
#include "tests/compiler/helpers.h"

using namespace tranche;

namespace {
struct One {
  test::Compiled c;
  const diag::Diagnostic& d;
  explicit One(const std::string& text) : d(init(text)) {}
  const diag::Diagnostic& init(const std::string& text) {
    test::compile_text(c, text);
    c.sink.finish({});
    REQUIRE(c.sink.all().size() == 1);
    return c.sink.all()[0];
  }
};
}  // namespace

TEST_CASE("diagnostics: the text form, rustc style") {
  One one("rule \"slow\" when layer.indx < 2 {\n  speed = 20 mm/s\n}\n");
  std::string text = compiler::render_text(one.c.program.sources, one.d, false);
  CHECK(text ==
        "error[E0102]: unknown field `layer.indx`\n"
        " --> test.rules:1:18\n"
        "  |\n"
        "1 | rule \"slow\" when layer.indx < 2 {\n"
        "  |                  ^^^^^^^^^^ not a field of `layer`\n"
        "  |\n"
        "  = help: did you mean `layer.index`?\n"
        "  = docs: docs/diagnostics.md#e0102\n");
}

TEST_CASE("diagnostics: secondary labels, notes, tabs and wide line numbers") {
  std::string src;
  for (int i = 0; i < 9; ++i) src += "# line\n";
  src += "rule \"x\" when\tspeed > island.area { flow = 1 }\n";
  One one(src);
  std::string text = compiler::render_text(one.c.program.sources, one.d, false);
  CHECK(text ==
        "error[E0200]: cannot compare `mm/s` and `mm2`\n"
        "  --> test.rules:10:21\n"
        "   |\n"
        "10 | rule \"x\" when    speed > island.area { flow = 1 }\n"
        "   |                        ^ the units differ\n"
        "   |                  ----- this is in `mm/s`\n"
        "   |                          ----------- this is in `mm2`\n"
        "   |\n"
        "   = docs: docs/diagnostics.md#e0200\n");
}

TEST_CASE("diagnostics: colour only when asked") {
  One one("rule when layer.indx < 2 { flow = 1 }\n");
  CHECK(compiler::render_text(one.c.program.sources, one.d, true).find("\x1b[") != std::string::npos);
  CHECK(compiler::render_text(one.c.program.sources, one.d, false).find("\x1b[") == std::string::npos);
}

TEST_CASE("diagnostics: JSON, one object per diagnostic, with every span") {
  One one("rule \"x\" when speed > island.area { flow = 1 }\n");
  std::string json = compiler::render_json(one.c.program.sources, one.d);
  CHECK(json ==
        "{\"code\":\"E0200\",\"level\":\"error\",\"message\":\"cannot compare `mm/s` and `mm2`\",\"spans\":["
        "{\"file\":\"test.rules\",\"line\":1,\"col\":21,\"end_line\":1,\"end_col\":22,\"byte_start\":20,"
        "\"byte_end\":21,\"label\":\"the units differ\",\"primary\":true},"
        "{\"file\":\"test.rules\",\"line\":1,\"col\":15,\"end_line\":1,\"end_col\":20,\"byte_start\":14,"
        "\"byte_end\":19,\"label\":\"this is in `mm/s`\",\"primary\":false},"
        "{\"file\":\"test.rules\",\"line\":1,\"col\":23,\"end_line\":1,\"end_col\":34,\"byte_start\":22,"
        "\"byte_end\":33,\"label\":\"this is in `mm2`\",\"primary\":false}],\"notes\":[],\"helps\":[],\"fixes\":[]}");
}

TEST_CASE("diagnostics: a did-you-mean carries the edit that applies it") {
  One one("rule when layer.indx < 2 { flow = 1 }\n");
  REQUIRE(one.d.fixes.size() == 1);
  CHECK(one.c.program.sources.text(one.d.fixes[0].span) == "layer.indx");
  CHECK(one.d.fixes[0].replacement == "layer.index");
  CHECK(compiler::render_json(one.c.program.sources, one.d).find(
            "\"fixes\":[{\"file\":\"test.rules\",\"byte_start\":10,\"byte_end\":20,\"replacement\":\"layer.index\"}]") !=
        std::string::npos);
}

TEST_CASE("diagnostics: columns count characters, bytes count bytes") {
  One one("rule \"größe\" when layer.indx < 2 { flow = 1 }\n");
  ast::Span s = one.d.span();
  CHECK(s.col == 19);
  CHECK(s.offset == 20);  // ö and ß are two bytes each
  CHECK(s.length == 10);
}

TEST_CASE("diagnostics: JSON strings escape quotes, backslashes and control characters") {
  CHECK(compiler::json_string("a\"b\\c\nd\te\x01") == "\"a\\\"b\\\\c\\nd\\te\\u0001\"");
  CHECK(compiler::json_string("größe") == "\"größe\"");
}

TEST_CASE("diagnostics: policy drops allowed warnings and promotes the rest") {
  test::Compiled c;
  test::compile_text(c, "rule \"x\" { }\nrule \"x\" { flow = 1 }\n");
  REQUIRE(c.sink.warnings() == 2);  // W212 empty rule, W211 duplicate name
  diag::Policy allow;
  allow.allowed.insert("W212");
  c.sink.finish(allow);
  REQUIRE(c.sink.all().size() == 1);
  CHECK(c.sink.all()[0].code == "W211");
  diag::Policy deny;
  deny.deny_warnings = true;
  c.sink.finish(deny);
  CHECK(c.sink.errors() == 1);
  CHECK(compiler::summary(1, 0) == "1 error, 0 warnings");
}

TEST_CASE("diagnostics: SARIF 2.1.0, one result per diagnostic with its primary location") {
  test::Compiled c;
  test::compile_text(c, "rule \"x\" when layer.indx < 2 { sped = 20 mm/s }\n");
  REQUIRE(c.sink.all().size() == 2);
  std::string s = compiler::render_sarif(c.program.sources, c.sink.all());
  CHECK(s.find("\"version\":\"2.1.0\"") != std::string::npos);
  CHECK(s.find("{\"id\":\"E0102\",\"helpUri\":\"docs/diagnostics.md#e0102\"}") != std::string::npos);
  CHECK(s.find("\"ruleId\":\"E0103\",\"level\":\"error\"") != std::string::npos);
  CHECK(s.find("\"region\":{\"startLine\":1,\"startColumn\":15,\"endLine\":1,\"endColumn\":25}") != std::string::npos);
  CHECK(s.find("help: did you mean `speed`?") != std::string::npos);
  // The did-you-mean's edit, as a fix.
  CHECK(s.find("\"fixes\":[{\"description\":{\"text\":\"did you mean `layer.index`?\"},\"artifactChanges\":[{"
               "\"artifactLocation\":{\"uri\":\"test.rules\"},\"replacements\":[{\"deletedRegion\":{\"startLine\":1,"
               "\"startColumn\":15,\"endLine\":1,\"endColumn\":25},\"insertedContent\":{\"text\":\"layer.index\"}}]}]}]") !=
        std::string::npos);
  CHECK(s.back() == '\n');
  // An empty run is still a valid log.
  CHECK(compiler::render_sarif(c.program.sources, {}).find("\"results\":[]") != std::string::npos);
}

TEST_CASE("diagnostics: a block left open is shown where it opened as well as where the parse failed") {
  test::Compiled c;
  test::compile_text(c, "rule \"a\" when layer.index < 2 {\n  speed = 20 mm/s\nrule \"b\" { flow = 1 }\n");
  c.sink.finish({});
  const diag::Diagnostic* d = nullptr;
  for (const auto& x : c.sink.all())
    if (x.code == "E0004" && c.program.sources.line_col(x.span().file, x.span().offset).first == 3)
      d = &x;
  REQUIRE(d != nullptr);
  const diag::Label* open = nullptr;
  for (const auto& l : d->labels)
    if (!l.primary) open = &l;
  REQUIRE(open != nullptr);
  CHECK(c.program.sources.line_col(open->span.file, open->span.offset) == std::pair<uint32_t, uint32_t>{1, 31});
  CHECK(c.program.sources.text(open->span) == "{");
  CHECK(open->text == "this `{` is not closed before the next item");
  CHECK(d->helps.size() == 1);
  CHECK(d->helps[0] == "close the block with `}` before `rule`");
  std::string text = compiler::render_text(c.program.sources, *d, false);
  CHECK(text ==
        "error[E0004]: expected `}` or a newline, found `rule`\n"
        " --> test.rules:3:1\n"
        "  |\n"
        "1 | rule \"a\" when layer.index < 2 {\n"
        "  |                               - this `{` is not closed before the next item\n"
        "3 | rule \"b\" { flow = 1 }\n"
        "  | ^^^^ expected `}` or a newline\n"
        "  |\n"
        "  = help: close the block with `}` before `rule`\n"
        "  = docs: docs/diagnostics.md#e0004\n");
}
