// The parser on hostile input: it must answer with a diagnostic, never crash or recurse without bound.
#include <doctest/doctest.h>

#include "grammar/parse.h"
#include "tests/compiler/helpers.h"

using namespace tranche;

namespace {
std::vector<std::string> codes(const std::string& text) {
  test::Compiled c;
  test::compile_text(c, text);
  std::vector<std::string> out;
  for (const auto& d : c.sink.all()) out.push_back(d.code);
  return out;
}
}  // namespace

TEST_CASE("parser: empty input and only comments give no rules and no diagnostics") {
  for (const char* text : {"", "\n", "# only a comment", "\xEF\xBB\xBF", "\r\n\r\n;;"}) {
    test::Compiled c;
    test::compile_text(c, text);
    CHECK(c.sink.all().empty());
    CHECK(c.program.cascade.empty());
  }
}

TEST_CASE("parser: deep nesting is refused before it can exhaust the stack") {
  CHECK(codes("rule when " + std::string(100000, '(') + "true" + std::string(100000, ')') +
              " { flow = 1 }") == std::vector<std::string>{"E0005"});
  std::string nots;
  for (int i = 0; i < 50000; ++i) nots += "not ";
  CHECK(codes("rule when " + nots + "true { flow = 1 }") == std::vector<std::string>{"E0005"});
  std::string chain = "rule { before layer { if layer.index == 0 { gcode \"a\" }";
  for (int i = 0; i < 20000; ++i)
    chain += " else if layer.index == " + std::to_string(i + 1) + " { gcode \"a\" }";
  CHECK(codes(chain + " } }") == std::vector<std::string>{"E0005"});
  std::string ifs = "rule { speed = ";
  for (int i = 0; i < 20000; ++i) ifs += "if true then 1 mm/s else ";
  CHECK(codes(ifs + "2 mm/s }") == std::vector<std::string>{"E0005"});
}

TEST_CASE("parser: long flat chains are built without recursion and bounded in depth") {
  std::string sum = "rule { flow = 0";
  for (int i = 0; i < 60000; ++i) sum += " + 0";
  CHECK(codes(sum + " }") == std::vector<std::string>{"E0005"});
  std::string ok = "rule { flow = 0";
  for (int i = 0; i < 150; ++i) ok += " + 0";
  CHECK(codes(ok + " + 1 }").empty());
}

TEST_CASE("parser: syntax errors stop after the budget, with a note") {
  std::string text;
  for (int i = 0; i < 60; ++i) text += "rule \"r\" { speed = = }\n";
  test::Compiled c;
  test::compile_text(c, text);
  CHECK(c.sink.errors() == 20);
  CHECK(c.sink.all().back().notes.size() == 1);
}

TEST_CASE("parser: units after numbers, division elsewhere") {
  test::Compiled c;
  test::compile_text(c, "rule { flow = 0.2 mm / layer.height; speed = 20 mm/s; width = 0.2mm*2 }\n", false);
  REQUIRE(c.sink.all().empty());
  const ast::Expr& flow = *c.rule(0).slots[0].action->value;
  CHECK(flow.op == ast::Op::Div);
  CHECK(flow.args[0]->unit_text == "mm");
  CHECK(c.rule(0).slots[1].action->value->unit_text == "mm/s");
  CHECK(c.rule(0).slots[2].action->value->op == ast::Op::Mul);
}

TEST_CASE("parser: templates split into text and expressions, with braces and escapes resolved") {
  test::Compiled c;
  test::compile_text(c, "rule { before layer { gcode \"a{layer.z:.2}b{{c}}\\\"d\\\\\" } }\n", false);
  REQUIRE(c.sink.all().empty());
  const ast::Template& t = c.rule(0).slots[0].action->body[0]->text;
  REQUIRE(t.parts.size() == 3);
  CHECK(t.parts[0].text == "a");
  CHECK(t.parts[1].expr->field == schema::FieldId::LayerZ);
  CHECK(t.parts[1].decimals == 2);
  CHECK(t.parts[1].span.col == 31);
  CHECK(t.parts[1].expr->span.col == 32);
  CHECK(t.parts[2].text == "b{c}\"d\\");
}

TEST_CASE("parser: every newline convention counts lines the same way") {
  for (const char* nl : {"\n", "\r\n", "\r"}) {
    std::string text = std::string("# a") + nl + nl + "rule when layer.indx < 2 { flow = 1 }" + nl;
    test::Compiled c;
    test::compile_text(c, text);
    REQUIRE(c.sink.all().size() == 1);
    CHECK(c.sink.all()[0].span().line == 3);
    CHECK(c.sink.all()[0].span().col == 11);
  }
}

TEST_CASE("parser: valid input never needs the full-LL pass") {
  size_t before = grammar::ll_fallbacks();
  test::Compiled c;
  test::compile_text(
      c,
      "rule \"a\" when path.kind in (infill, bridge) and layer.index in 1..3 or not cell.solid {\n"
      "  speed = if layer.index < 2 then 20 mm/s else min(speed, 50 mm/s)\n"
      "  before path append { gcode \"M117 {layers[layer.index - 1].area:.1}\" }\n"
      "  replace path { for p in path.points { move to (p.x, p.y) with speed = 10 mm/s } }\n"
      "}\n"
      "on layer.end when (layer.index) in (1, 2) { comment \"x\" }\n");
  CHECK(c.sink.errors() == 0);
  CHECK(grammar::ll_fallbacks() == before);
  test::Compiled bad;
  test::compile_text(bad, "rule \"x\" { speed = = }\n");
  CHECK(grammar::ll_fallbacks() == before + 1);
}

TEST_CASE("parser: a large realistic file parses into every rule") {
  std::string text;
  for (int i = 0; i < 500; ++i)
    text += "rule \"r" + std::to_string(i) + "\" when layer.index == " + std::to_string(i) +
            " and path.kind == infill { speed = " + std::to_string(20 + i % 50) + " mm/s }\n";
  test::Compiled c;
  test::compile_text(c, text);
  CHECK(c.sink.all().empty());
  CHECK(c.program.cascade.size() == 500);
}
