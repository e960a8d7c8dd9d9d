// `rulec explain`: the deciding rule of each slot, why later rules did not match, the cascade.
#include <doctest/doctest.h>

#include "compiler/explain.h"
#include "tests/compiler/vm_helpers.h"

using namespace tranche;

namespace {
std::string explain(const std::string& text, const std::string& at) {
  test::Compiled c;
  test::compile_text(c, text, false);
  REQUIRE(c.program.checked);
  auto p = compiler::generate(c.program);
  REQUIRE(p.ok());
  auto rs = vm::RuleSet::create(std::move(*p));
  REQUIRE(rs.ok());
  auto out = compiler::explain(c.program, **rs, at);
  REQUIRE_MESSAGE(out.ok(), (out.ok() ? "" : out.error().to_string()));
  return *out;
}
}  // namespace

TEST_CASE("explain: the deciding rule, and why each later candidate did not match") {
  const std::string rules = R"(rule "base" { speed = 60 mm/s; flow = 1.0 }
rule "first layers slow" when layer.index < 2 { speed = 20 mm/s }
rule "small islands" when island.area < 4 mm2 and path.kind == infill { speed = 15 mm/s }
rule "PA outer wall" when path.kind == outer_perimeter { before path { gcode "M900 K0.045" } }
rule "more" when path.kind == outer_perimeter { before path append { gcode "M117 x" } }
)";
  std::string out = explain(rules, "layer.index=3, path.kind=outer_perimeter, island.area=2mm2");
  CHECK(out.find("  rules 0-4      test.rules\n") != std::string::npos);
  CHECK(out.find("speed = 60 mm/s\n  decided by rule \"base\" at test.rules:1:1") != std::string::npos);
  CHECK(out.find("rule \"small islands\" at test.rules:3:1: `path.kind == infill` is false (path.kind = "
                 "outer_perimeter)") != std::string::npos);
  CHECK(out.find("rule \"first layers slow\" at test.rules:2:1: `layer.index < 2` is false (layer.index = 3)") !=
        std::string::npos);
  CHECK(out.find("before path\n  decided by rule \"PA outer wall\"") != std::string::npos);
  CHECK(out.find("and, appended: rule \"more\"") != std::string::npos);
  std::string first = explain(rules, "layer.index=0");
  CHECK(first.find("speed = 20 mm/s\n  decided by rule \"first layers slow\"") != std::string::npos);
  CHECK(first.find("earlier rules that lose this slot: rule \"base\"") != std::string::npos);
  CHECK(first.find("not given, read as 0: island.area path.kind") != std::string::npos);
}

TEST_CASE("explain: bad contexts are refused with a suggestion") {
  test::Compiled c;
  test::compile_text(c, "rule { speed = 10 mm/s }", false);
  auto p = compiler::generate(c.program);
  REQUIRE(p.ok());
  auto rs = vm::RuleSet::create(std::move(*p));
  REQUIRE(rs.ok());
  auto bad = compiler::explain(c.program, **rs, "layer.indx=3");
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().message.find("did you mean `layer.index`?") != std::string::npos);
  auto unit = compiler::explain(c.program, **rs, "island.area=3 mm/s");
  REQUIRE_FALSE(unit.ok());
  CHECK(unit.error().message.find("mm2") != std::string::npos);
  auto kind = compiler::explain(c.program, **rs, "path.kind=wall");
  REQUIRE_FALSE(kind.ok());
  CHECK(kind.error().message.find("outer_perimeter") != std::string::npos);
  CHECK(compiler::explain(c.program, **rs, "speed=40, cell.solid=true").ok());
}

TEST_CASE("explain: --slot shows only the slots asked for, and refuses names that are none") {
  const std::string rules = "rule \"a\" { speed = 10 mm/s; flow = 1.0 }\nrule { before layer { gcode \"X\" } }\n";
  std::string all = explain(rules, "layer.index=1");
  CHECK(all.find("\nflow = ") != std::string::npos);
  test::Compiled c;
  test::compile_text(c, rules, false);
  auto p = compiler::generate(c.program);
  REQUIRE(p.ok());
  auto rs = vm::RuleSet::create(std::move(*p));
  REQUIRE(rs.ok());
  auto only = compiler::explain(c.program, **rs, "layer.index=1", {"speed", "before layer"});
  REQUIRE(only.ok());
  CHECK(only->find("\nspeed = 10 mm/s") != std::string::npos);
  CHECK(only->find("\nbefore layer") != std::string::npos);
  CHECK(only->find("\nflow = ") == std::string::npos);
  auto bad = compiler::explain(c.program, **rs, "", {"sped"});
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().message.find("not a slot") != std::string::npos);
}

TEST_CASE("explain: a name given with --at is matched as the slicer matches it") {
  const std::string rules = "rule \"lid\" when object.name == \"lid\" { infill_density = 40% }\n";
  CHECK(explain(rules, "object.name=lid").find("infill_density = 40%\n  decided by rule \"lid\"") != std::string::npos);
  const std::string base = explain(rules, "object.name=\"base\"");
  CHECK(base.find("context: object.name = \"base\"") != std::string::npos);
  CHECK(base.find("`object.name == \"lid\"` is false (object.name = \"base\")") != std::string::npos);
}
