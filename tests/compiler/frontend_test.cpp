// Reading files, `use` resolution, the stdlib directory, and `--set`.
#include <doctest/doctest.h>

#include <chrono>
#include <cstdlib>
#include <fstream>

#include "compiler/frontend.h"
#include "tests/compiler/helpers.h"
#include "tests/support/fixtures.h"

using namespace tranche;
namespace fs = std::filesystem;

namespace {
void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}
}  // namespace

TEST_CASE("frontend: `use` expands in place, once, relative to the using file, `.rules` optional") {
  test::TempDir dir("use");
  write(dir / "lib/base.rules", "rule \"base\" { speed = 60 mm/s }\n");
  write(dir / "lib/pla.rules", "use \"./base\"\nrule \"pla\" { nozzle_temp = 210 °C }\n");
  write(dir / "main.rules",
        "rule \"first\" { flow = 1 }\nuse \"./lib/pla\"\nuse \"./lib/base.rules\"\nrule \"last\" { fan = 1 "
        "}\n");
  write(dir / "second.rules", "use \"./lib/base\"\nrule \"second\" { width = 0.5 mm }\n");
  diag::Sink sink;
  ast::Program p =
      compiler::compile({(dir / "main.rules").string(), (dir / "second.rules").string()}, {}, {}, sink);
  CHECK(sink.all().empty());
  std::vector<std::string> names;
  for (const ast::Rule* r : p.cascade) names.push_back(r->name);
  CHECK(names == std::vector<std::string>{"first", "base", "pla", "last", "second"});
  CHECK(p.sources.size() == 4);
}

TEST_CASE(
    "frontend: stdlib names resolve in the first existing directory, and stdlib files are not user files") {
  test::TempDir dir("stdlib");
  write(dir / "std/printers/p.rules", "rule \"p\" { nozzle_diameter = 0.4 mm }\n");
  write(dir / "main.rules", "use \"printers/p\"\n");
  compiler::FrontendOptions options;
  options.stdlib_dir = (dir / "std").string();
  diag::Sink sink;
  ast::Program p = compiler::compile({(dir / "main.rules").string()}, {}, options, sink);
  CHECK(sink.all().empty());
  REQUIRE(p.cascade.size() == 1);
  CHECK_FALSE(p.sources.file(p.cascade[0]->span.file).user);
  CHECK(compiler::stdlib_dir(options) == dir / "std");
}

TEST_CASE("frontend: the stdlib search order is --stdlib, $TRANCHE_STDLIB, the checkout, <exe>/../share") {
  test::TempDir dir("order");
  compiler::FrontendOptions options;
  options.stdlib_dir = (dir / "flag").string();
  options.exe_path = (dir / "bin" / "rulec").string();
  fs::create_directories(dir / "bin");
  fs::create_directories(dir / "env");
  ::setenv("TRANCHE_STDLIB", (dir / "env").c_str(), 1);
  auto c = compiler::stdlib_candidates(options);
  ::unsetenv("TRANCHE_STDLIB");
  REQUIRE(c.size() >= 3);
  CHECK(c[0] == dir / "flag");
  CHECK(c[1] == dir / "env");
  CHECK(c.back().lexically_normal() == (dir / "share" / "tranche" / "stdlib").lexically_normal());
  // --stdlib names a missing directory: the next existing one is used.
  ::setenv("TRANCHE_STDLIB", (dir / "env").c_str(), 1);
  CHECK(compiler::stdlib_dir(options) == dir / "env");
  ::unsetenv("TRANCHE_STDLIB");
}

TEST_CASE("frontend: unreadable inputs and files are diagnostics, not crashes") {
  test::TempDir dir("missing");
  diag::Sink sink;
  compiler::compile({(dir / "nope.rules").string(), dir.path().string()}, {}, {}, sink);
  REQUIRE(sink.all().size() == 2);
  CHECK(sink.all()[0].code == "E0010");
  CHECK(sink.all()[0].message.find("No such file or directory") != std::string::npos);
  CHECK(sink.all()[1].message.find("is a directory") != std::string::npos);
  CHECK_FALSE(sink.all()[0].span().valid());  // the whole file
}

TEST_CASE("frontend: --set takes the property's unit, and is the last rule") {
  test::Compiled c;
  REQUIRE(compiler::add_set(c.program, "speed", "40", c.sink));
  REQUIRE(compiler::add_set(c.program, "nozzle_temp", "205", c.sink));
  REQUIRE(compiler::add_set(c.program, "fan", "50%", c.sink));
  REQUIRE(compiler::add_set(c.program, "seam", "rear", c.sink));
  REQUIRE(compiler::add_set(c.program, "fill_angle", "15 deg * layer.index", c.sink));
  test::compile_text(c, "rule \"user\" { speed = 20 mm/s }\n", false);
  // compile_text loads the file after the sets; the cascade keeps --set rules last when built by compile().
  CHECK(c.program.checked);
  CHECK(c.sink.errors() == 0);
  const ast::Rule& speed = c.rule(0);
  CHECK(speed.from_set);
  CHECK(speed.name == "--set speed");
  CHECK(speed.slots.at(0).action->value->constant == 40.0);
  CHECK(speed.slots[0].action->value->type == ast::Type::number(ast::Unit{1, -1, 0, 0}));
  CHECK(c.rule(1).slots.at(0).action->value->type == ast::Type::number(ast::Unit{0, 0, 0, 1}));
  CHECK(c.rule(2).slots.at(0).action->value->constant == 0.5);
  CHECK(c.rule(3).slots.at(0).action->value->enum_value == static_cast<int>(schema::Seam::Rear));

  diag::Sink sink;
  test::TempDir dir("set");
  write(dir / "a.rules", "rule \"a\" { speed = 20 mm/s }\n");
  ast::Program p = compiler::compile({(dir / "a.rules").string()}, {{"speed", "40"}}, {}, sink);
  REQUIRE(p.cascade.size() == 2);
  CHECK(p.cascade.back()->from_set);
}

TEST_CASE("frontend: --set errors name --set") {
  auto one = [](const std::string& key, const std::string& value) {
    ast::Program p;
    diag::Sink sink;
    if (compiler::add_set(p, key, value, sink)) compiler::check(p, sink);
    sink.finish({});
    REQUIRE(sink.all().size() == 1);
    CHECK(p.sources.file(sink.all()[0].span().file).path == "--set");
    return sink.all()[0];
  };
  auto unknown = one("sped", "40");
  CHECK(unknown.code == "E0103");
  CHECK(unknown.message == "unknown property `sped` in `--set`");
  CHECK(unknown.helps.at(0) == "did you mean `--set speed=40`?");
  auto range = one("fan", "50");
  CHECK(range.code == "E0500");
  CHECK(range.helps.at(0) == "for a percentage, write `--set fan=50%`");
  CHECK(one("speed", "").code == "E0004");
  CHECK(one("speed", "20 mm").code == "E0202");
  CHECK(one("speed", "20 +").code == "E0004");
  CHECK(one("perimeters", "2.5").code == "E0203");
}

TEST_CASE("frontend: rules are counted before parsing: `rule` and `on` items, not words in strings or blocks") {
  CHECK(compiler::count_rule_items("") == 0);
  CHECK(compiler::count_rule_items("rule { speed = 1 mm/s }\non layer.start { gcode \"rule on\" }\n") == 2);
  CHECK(compiler::count_rule_items("# rule rule\nrule \"rule\" { comment \"\"\"on\nrule\"\"\" }\n") == 1);
  CHECK(compiler::count_rule_items("rules ruler on_x x_on rule") == 1);
  CHECK(compiler::count_rule_items("rule \"a\\\"rule\" {}") == 1);
}

TEST_CASE("frontend: more rules than the VM numbers are refused before parsing (E0013), quickly") {
  test::TempDir dir("many-rules");
  std::string text;
  for (int i = 0; i < 100000; ++i) text += "rule \"r\" when layer.index == 3 { speed = 20 mm/s }\n";
  write(dir / "many.rules", text);
  const auto start = std::chrono::steady_clock::now();
  diag::Sink sink;
  compiler::compile({(dir / "many.rules").string()}, {}, {}, sink);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  REQUIRE(sink.all().size() == 1);
  CHECK(sink.all()[0].code == "E0013");
  CHECK(sink.all()[0].message.find("100000") != std::string::npos);
  CHECK(sink.all()[0].message.find("65535") != std::string::npos);
  CHECK(seconds < 2);
}
