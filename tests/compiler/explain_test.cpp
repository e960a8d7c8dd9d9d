// `rulec explain`: the deciding rule of each slot, why later rules did not match, the cascade.
#include <doctest/doctest.h>

#include "compiler/explain.h"
#include "tests/compiler/vm_helpers.h"

using namespace tranche;

namespace {
Result<std::string> try_explain(const std::string& text, const std::string& at) {
  test::Compiled c;
  test::compile_text(c, text, false);
  REQUIRE(c.program.checked);
  auto p = compiler::generate(c.program);
  REQUIRE(p.ok());
  auto rs = vm::RuleSet::create(std::move(*p));
  REQUIRE(rs.ok());
  return compiler::explain(c.program, **rs, at);
}

std::string explain(const std::string& text, const std::string& at) {
  auto out = try_explain(text, at);
  REQUIRE_MESSAGE(out.ok(), (out.ok() ? "" : out.error().to_string()));
  return *out;
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
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
  CHECK(first.find("earlier rules that match but lose this slot: rule \"base\"") != std::string::npos);
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

TEST_CASE("explain: the value chain of a slot, from the schema default through each rule with file:line") {
  const std::string rules = R"(rule "bridges" when path.kind == outer_perimeter { speed = 15 mm/s }
rule "small islands" when island.area < 4 mm2 { speed = speed * 50% }
)";
  const std::string out = explain(rules, "layer.index=3, path.kind=outer_perimeter, island.area=2mm2");
  INFO(out);
  CHECK(has(out, "speed = 7.5 mm/s\n  decided by rule \"small islands\""));
  CHECK(has(out, "  chain: 60 mm/s schema default -> 25 mm/s built-in default (speed = 25 mm/s when path.kind == "
                 "outer_perimeter) -> 15 mm/s rule \"bridges\" (test.rules:1, read by the rule after it) -> 7.5 mm/s "
                 "rule \"small islands\" (test.rules:2)\n"));
  CHECK(has(out, "lose this slot: rule \"bridges\" (its value read by a later rule)\n"));
  // Where "bridges" does not match, "small islands" halves the built-in default.
  const std::string inner = explain(rules, "layer.index=3, path.kind=inner_perimeter, island.area=2mm2");
  INFO(inner);
  CHECK(has(inner, "speed = 22.5 mm/s"));
  CHECK(has(inner, "-> 45 mm/s built-in default (speed = 45 mm/s when path.kind == inner_perimeter) -> 22.5 mm/s rule "
                   "\"small islands\" (test.rules:2)\n"));
  // A property given with --at sits below the rules, and the chain says so.
  const std::string given = explain("rule \"slow\" { speed = speed - 10 mm/s }", "layer.index=2, speed=40");
  CHECK(has(given, "-> 40 mm/s given with --at -> 30 mm/s rule \"slow\" (test.rules:1)"));
}

TEST_CASE("explain: --at gives other layers' fields (below, above, layers[N]) through a layer table") {
  const std::string rules = R"(rule "jump" when below.area > 0 and layer.area / below.area > 2 { speed = 10 mm/s }
rule "under the lid" when above.z > 10 mm { fan = 50% }
rule "first z" when layers[0].z > 0.25 mm { flow = 90% }
)";
  const std::string jump = explain(rules, "layer.index=3, layer.area=100mm2, below.area=30mm2, above.z=12, layers[0].z=0.3");
  INFO(jump);
  CHECK(has(jump, "context: layer.index = 3; layer.area = 100 mm2; layers[0].z = 0.3 mm; below.area = 30 mm2; above.z = 12 mm"));
  CHECK(has(jump, "speed = 10 mm/s\n  decided by rule \"jump\""));
  CHECK(has(jump, "fan = 50%\n  decided by rule \"under the lid\""));
  CHECK(has(jump, "flow = 90%\n  decided by rule \"first z\""));
  const std::string flat = explain(rules, "layer.index=3, layer.area=100mm2, below.area=80mm2");
  INFO(flat);
  CHECK(has(flat, "`layer.area / below.area > 2` is false (layer.area = 100 mm2, below.area = 80 mm2)"));
  CHECK(has(flat, "not given, read as 0: above.z layers[...].z"));
  // Mistakes name the item and say what to write.
  auto none_below = try_explain(rules, "layer.index=0, below.area=3mm2");
  REQUIRE_FALSE(none_below.ok());
  CHECK(has(none_below.error().message, "no layer below"));
  auto self = try_explain(rules, "layer.index=3, layers[3].z=0.8");
  REQUIRE_FALSE(self.ok());
  CHECK(has(self.error().message, "give it as layer.z"));
  auto field = try_explain(rules, "below.kind=infill");
  REQUIRE_FALSE(field.ok());
  CHECK(has(field.error().message, "another layer has only these fields: index, z_bottom, z"));
  auto bad = try_explain(rules, "layers[x].z=1");
  REQUIRE_FALSE(bad.ok());
  CHECK(has(bad.error().message, "whole number"));
  auto unit = try_explain(rules, "layer.index=2, below.area=3 mm/s");
  REQUIRE_FALSE(unit.ok());
  CHECK(has(unit.error().message, "below.area"));
}

TEST_CASE("explain: only rules whose filter matched lose the slot; a replace slot nobody takes prints the default") {
  const std::string rules = R"(rule "base" { speed = 60 mm/s }
rule "never" when layer.index > 100 { speed = 5 mm/s }
rule "first layers" when layer.index < 2 { speed = 20 mm/s }
rule "wavy top" when path.kind == top_solid { replace path { default } }
rule "marker" when path.kind == top_solid { before path { gcode "M117 top" } }
)";
  const std::string out = explain(rules, "layer.index=0, path.kind=infill");
  INFO(out);
  CHECK(has(out, "speed = 20 mm/s\n  decided by rule \"first layers\""));
  CHECK(has(out, "  earlier rules that match but lose this slot: rule \"base\"\n"));
  CHECK_FALSE(has(out, "lose this slot: rule \"never\""));
  CHECK_FALSE(has(out, "rule \"never\"\n"));
  CHECK(has(out, "replace path\n  no replacer matched: the default G-code is printed\n"));
  CHECK(has(out, "before path\n  no rule matched: nothing is emitted\n"));
  CHECK(has(out, "rule \"wavy top\" at test.rules:4:1: `path.kind == top_solid` is false (path.kind = infill)"));
  const std::string top = explain(rules, "layer.index=5, path.kind=top_solid");
  CHECK(has(top, "replace path\n  decided by rule \"wavy top\""));
  CHECK_FALSE(has(top, "lose this slot"));  // "base" decides; nothing below it
}

TEST_CASE("explain: a name given with --at is matched as the slicer matches it") {
  const std::string rules = "rule \"lid\" when object.name == \"lid\" { infill_density = 40% }\n";
  CHECK(explain(rules, "object.name=lid").find("infill_density = 40%\n  decided by rule \"lid\"") != std::string::npos);
  const std::string base = explain(rules, "object.name=\"base\"");
  CHECK(base.find("context: object.name = \"base\"") != std::string::npos);
  CHECK(base.find("`object.name == \"lid\"` is false (object.name = \"base\")") != std::string::npos);
}
