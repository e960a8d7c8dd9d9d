// Bundles (write, read, verify), the verifier on hand-made bad programs, and linking.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "runtime/vm/bundle.h"
#include "runtime/vm/link.h"
#include "runtime/vm/verify.h"
#include "tests/compiler/vm_helpers.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using schema::FieldId;
using schema::Level;
using schema::PropId;
using schema::Stage;

namespace {

const char* kRules = R"(
rule "base" { speed = 60 mm/s; flow = 1.0 }
rule "slow start" when layer.index < 2 { speed = 20 mm/s }
rule "PA" when path.kind == outer_perimeter { before path { gcode "M900 K{0.045:.3}" } }
rule "cap" when speed > 50 mm/s { speed = speed * 90% }
rule "shrink" when island.area < 10 mm2 { replace island { offset -0.1 mm; default } }
on layer.start when layer.index == 10 { gcode "M600 ; colour change" }
)";

// A one-chunk program: `chunk` returns r0 after `code`.
vm::Program tiny(std::vector<vm::Instr> code, uint16_t regs = 1, vm::ChunkKind kind = vm::ChunkKind::Value) {
  vm::Program p;
  p.consts = {1.5};
  p.code = std::move(code);
  p.chunks.push_back({0, static_cast<uint32_t>(p.code.size()), regs, kind});
  p.rules.push_back({0, 0});
  if (kind == vm::ChunkKind::Value) p.props[static_cast<size_t>(PropId::Speed)].push_back({0, 0, false});
  for (const auto& info : schema::properties()) p.property_order.push_back(info.id);
  std::stable_sort(p.property_order.begin(), p.property_order.end(),
                   [](auto a, auto b) { return schema::property(a).stage < schema::property(b).stage; });
  return p;
}
vm::Instr I(vm::Op op, uint8_t a = 0, uint16_t b = 0, uint16_t c = 0, uint16_t d = 0) {
  return vm::Instr{static_cast<uint8_t>(op), a, b, c, d};
}

}  // namespace

TEST_CASE("bundle: write then read gives the same program, byte for byte, with and without debug") {
  auto p = test::program(kRules);
  std::string a = vm::write_bundle(p);
  CHECK(vm::looks_like_bundle(a));
  auto back = vm::read_bundle(a, "x.bundle");
  REQUIRE_MESSAGE(back.ok(), (back.ok() ? "" : back.error().to_string()));
  CHECK(vm::write_bundle(*back) == a);
  CHECK(vm::disassemble(*back) == vm::disassemble(p));
  // Compiling the same text again gives the same bytes.
  CHECK(vm::write_bundle(test::program(kRules)) == a);
  std::string b = vm::write_bundle(p, false);
  CHECK(b.size() < a.size());
  auto nodebug = vm::read_bundle(b, "y.bundle");
  REQUIRE(nodebug.ok());
  CHECK(nodebug->debug.empty());
  CHECK(nodebug->code.size() == p.code.size());
}

TEST_CASE("bundle: any damaged byte, truncation or extension is refused with a message") {
  std::string a = vm::write_bundle(test::program(kRules));
  for (size_t i = 0; i < a.size(); ++i) {
    std::string d = a;
    d[i] = static_cast<char>(d[i] ^ 0x5a);
    auto r = vm::read_bundle(d, "x.bundle");
    CHECK_MESSAGE(!r.ok(), "byte " << i);
    if (!r.ok()) CHECK(r.error().where == "x.bundle");
  }
  for (size_t n : {size_t(0), size_t(7), size_t(40), a.size() / 2, a.size() - 1}) {
    auto r = vm::read_bundle(a.substr(0, n), "x.bundle");
    CHECK_FALSE(r.ok());
  }
  CHECK_FALSE(vm::read_bundle(a + "x", "x.bundle").ok());
  auto text = vm::read_bundle("rule { speed = 1 mm/s }", "r.rules");
  REQUIRE_FALSE(text.ok());
  CHECK(text.error().message.find("not a rule bundle") != std::string::npos);
}

TEST_CASE("bundle: a bundle for another schema is refused") {
  std::string a = vm::write_bundle(test::program(kRules));
  a[16] = static_cast<char>(a[16] ^ 1);  // the schema hash; then fix the checksum as a forger would
  uint64_t h = vm::bundle_checksum(a);
  for (int i = 0; i < 8; ++i) a[24 + static_cast<size_t>(i)] = static_cast<char>((h >> (8 * i)) & 0xff);
  auto r = vm::read_bundle(a, "x.bundle");
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().message.find("another version of the context") != std::string::npos);
}

TEST_CASE("bundle: the checksum is FNV-1a 64 as docs/bundles.md documents it; version 1 bundles are refused") {
  std::string a = vm::write_bundle(test::program(kRules));
  // The reference FNV-1a 64, written out here rather than shared with the reader.
  uint64_t h = 14695981039346656037ull;
  for (size_t i = 32; i < a.size(); ++i) h = (h ^ static_cast<unsigned char>(a[i])) * 1099511628211ull;
  uint64_t stored = 0;
  for (int i = 7; i >= 0; --i) stored = stored << 8 | static_cast<unsigned char>(a[24 + static_cast<size_t>(i)]);
  CHECK(stored == h);
  CHECK(vm::kBundleVersion == 2);
  std::string old = a;
  old[8] = 1;  // a version 1 bundle (its checksum fixed, as a valid old bundle would have it)
  auto r = vm::read_bundle(old, "old.bundle");
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().message.find("older tranche") != std::string::npos);
  CHECK(r.error().message.find("rebuild it with `rulec build`") != std::string::npos);
}

TEST_CASE("verify: operands, jumps, terminators and opcode classes are checked before anything runs") {
  using vm::Op;
  CHECK(vm::verify(tiny({I(Op::LoadK, 0, 0), I(Op::Ret, 0)})).ok());
  auto bad = [](vm::Program p, const char* what) {
    auto s = vm::verify(p);
    REQUIRE_FALSE(s.ok());
    CHECK_MESSAGE(s.error().message.find(what) != std::string::npos, s.error().message);
  };
  bad(tiny({I(Op::LoadK, 1, 0), I(Op::Ret, 0)}), "register 1 out of range");
  bad(tiny({I(Op::LoadK, 0, 7), I(Op::Ret, 0)}), "constant 7 out of range");
  bad(tiny({I(Op::Field, 0, 999), I(Op::Ret, 0)}), "field 999 out of range");
  bad(tiny({I(Op::Jmp, 0, 5), I(Op::Ret, 0)}), "jump target 5 outside the chunk");
  bad(tiny({I(Op::LoadK, 0, 0)}), "does not end with a return");
  bad(tiny({I(Op::Gcode), I(Op::Ret, 0)}), "`gcode` is not allowed in a value chunk");
  bad(tiny({I(Op::Default), I(Op::Halt)}, 1, vm::ChunkKind::Hook), "`default` is not allowed in a hook chunk");
  bad(tiny({I(Op::Ret, 0)}, 1, vm::ChunkKind::Hook), "`ret` is not allowed in a hook chunk");
  bad(tiny({I(Op::LoadK, 0, 0, 3), I(Op::Ret, 0)}), "operand C: must be 0");
  bad(tiny({I(static_cast<Op>(250)), I(Op::Ret, 0)}), "unknown opcode 250");
  bad(tiny({I(Op::TNum, 0, 13), I(Op::Halt)}, 1, vm::ChunkKind::Hook), "decimals out of range");
  bad(tiny({I(Op::MoveTo, 0, 0, vm::kMoveSpeed | vm::kMoveFlow, 0), I(Op::Halt)}, 1, vm::ChunkKind::Replace),
      "move options out of the chunk's registers");
  bad(tiny({I(Op::LoadK, 0, 0), I(Op::Ret, 0)}, 0), "0 registers");
  auto p = tiny({I(Op::LoadK, 0, 0), I(Op::Ret, 0)});
  p.consts[0] = std::numeric_limits<double>::quiet_NaN();
  bad(p, "not a finite number");
  p = tiny({I(Op::LoadK, 0, 0), I(Op::Ret, 0)});
  p.props[static_cast<size_t>(PropId::Flow)].push_back({3, 0, false});
  bad(p, "candidate names no rule");
  p = tiny({I(Op::LoadK, 0, 0), I(Op::Ret, 0)});
  p.rules.push_back({0, 0});
  p.props[static_cast<size_t>(PropId::Speed)].push_back({1, 0, false});  // ascending: wrong
  bad(p, "descending rule order");
  p = tiny({I(Op::LoadK, 0, 0), I(Op::Ret, 0)});
  std::swap(p.property_order.front(), p.property_order.back());
  bad(p, "stage by stage");
}

TEST_CASE("verify: a backward jump loops, but the VM stops it") {
  using vm::Op;
  auto p = tiny({I(Op::Jmp, 0, 0), I(Op::Ret, 0)});
  auto rs = vm::RuleSet::create(std::move(p));
  REQUIRE(rs.ok());
  ctx::Context c;
  auto props = ctx::PropertyValues::schema_defaults();
  c.set_props(&props);
  auto s = (*rs)->decide(Stage::Piece, c, props);
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().message.find("steps") != std::string::npos);
}

TEST_CASE("link: later programs win slot by slot, inherited values reach into earlier ones") {
  auto a = test::program("rule \"profile\" { speed = 80 mm/s; flow = 0.95 }\nrule \"home\" { before print { gcode \"G28\" } }");
  auto b = test::program("rule \"half\" when layer.index < 2 { speed = speed * 50% }\nrule { before print append { gcode \"G29\" } }");
  auto linked = vm::link({std::move(a), vm::Program(b)}, {"a.rules", "b.rules"});
  REQUIRE_MESSAGE(linked.ok(), (linked.ok() ? "" : linked.error().to_string()));
  auto rs = vm::RuleSet::create(std::move(*linked));
  REQUIRE(rs.ok());
  ctx::Context c;
  c.clear_from(Level::Layer);
  auto p = test::decide(**rs, Stage::Piece, c);
  CHECK(p[PropId::Speed] == 40);
  CHECK(p[PropId::Flow] == doctest::Approx(0.95));
  test::Lines out;
  REQUIRE((*rs)->run(Level::Print, ctx::When::Before, c, out).ok());
  CHECK(out.joined() == "G28\nG29\n");
  // A bundle without debug information still names itself in errors.
  auto nodebug = vm::read_bundle(vm::write_bundle(test::program("rule { fan = 1 mm2 / layer.area }"), false), "n.bundle");
  REQUIRE(nodebug.ok());
  auto l2 = vm::link({std::move(b), std::move(*nodebug)}, {"b.rules", "n.bundle"});
  REQUIRE(l2.ok());
  auto rs2 = vm::RuleSet::create(std::move(*l2));
  REQUIRE(rs2.ok());
  auto props = ctx::PropertyValues::schema_defaults();
  c.set_props(&props);
  auto s = (*rs2)->decide(Stage::Cooling, c, props);
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().where == "n.bundle");
  CHECK(s.error().message.find("rule 0 of n.bundle") != std::string::npos);
}

TEST_CASE("link: properties that read each other across files are refused") {
  auto a = test::program("rule { flow = width / 0.45 mm }");
  auto b = test::program("rule { speed = 100 mm/s * flow }");
  // One direction in each file, the same direction overall: fine.
  CHECK(vm::link({vm::Program(a), vm::Program(b)}, {"a", "b"}).ok());
  auto c = test::program("rule { speed = flow * 100 mm/s }");
  auto d = test::program("rule { flow = speed / 100 mm/s }");
  auto r = vm::link({std::move(c), std::move(d)}, {"c", "d"});
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().message.find("read each other") != std::string::npos);
}

TEST_CASE("docs/bundles.md lists every opcode with the operand kinds of opcodes.def") {
  const std::string doc = test::read_file(test::source_dir() / "docs" / "bundles.md");
  REQUIRE_FALSE(doc.empty());
  auto letter = [](vm::Operand k) {
    switch (k) {
      case vm::Operand::None: return '_';
      case vm::Operand::Reg: return 'R';
      case vm::Operand::Const: return 'K';
      case vm::Operand::Field: return 'F';
      case vm::Operand::Prop: return 'P';
      case vm::Operand::Jump: return 'J';
      case vm::Operand::String: return 'S';
      case vm::Operand::Rule: return 'N';
      case vm::Operand::Enum: return 'E';
      case vm::Operand::Coll: return 'C';
      case vm::Operand::Member: return 'M';
      case vm::Operand::Decimals: return 'D';
      case vm::Operand::LayerOffset: return 'O';
      case vm::Operand::MoveFlags: return 'X';
    }
    return '?';
  };
  for (int op = 0; op < vm::kOpCount; ++op) {
    const auto& info = vm::op_info(static_cast<vm::Op>(op));
    std::string m = info.mnemonic;
    if (m.find('.') != std::string::npos) {  // fused: listed as a family
      CHECK_MESSAGE(doc.find("`" + m + "`") != std::string::npos, m);
      continue;
    }
    std::string row = fmt::format("| `{}` | {} | {} | {} | {} |", m, letter(info.a), letter(info.b), letter(info.c),
                                  letter(info.d));
    CHECK_MESSAGE(doc.find(row) != std::string::npos, row);
  }
}

TEST_CASE("names: quoted text is interned once, a name's field holds its index, linking keeps each text once") {
  // Two rule sets naming the same object: linked, "lid" is one string, so one index matches both.
  auto a = test::program("rule \"lid\" when object.name == \"lid\" { speed = 20 mm/s }\n"
                         "rule { before print { gcode \"lid\" } }");
  auto b = test::program("rule \"lids and caps\" when object.name in (\"cap\", \"lid\") { flow = 0.9 }");
  CHECK(a.strings == std::vector<std::string>{"lid"});  // the template and the name share it
  auto linked = vm::link({std::move(a), std::move(b)}, {"a.rules", "b.rules"});
  REQUIRE(linked.ok());
  CHECK(linked->strings == std::vector<std::string>{"lid", "cap"});
  auto rs = vm::RuleSet::create(std::move(*linked));
  REQUIRE(rs.ok());
  CHECK((*rs)->text_index("lid") == 0);
  CHECK((*rs)->text_index("cap") == 1);
  CHECK((*rs)->text_index("base") == -1);
  const auto texts = (*rs)->compared_texts();
  REQUIRE(texts.size() == 2);
  CHECK(texts[0].first == "lid");
  CHECK(texts[1].first == "cap");
  CHECK(texts[1].second == "test.rules:1:43");  // where "cap" is written
  auto decided = [&](int text) {
    ctx::Context c;
    c.clear_from(Level::Layer);
    c.set(FieldId::ObjectName, text);
    return test::decide(**rs, Stage::Piece, c);
  };
  CHECK(decided(0)[PropId::Speed] == 20);
  CHECK(decided(0)[PropId::Flow] == doctest::Approx(0.9));
  CHECK(decided(1)[PropId::Speed] != 20);
  CHECK(decided(1)[PropId::Flow] == doctest::Approx(0.9));
  CHECK(decided(-1)[PropId::Flow] != doctest::Approx(0.9));
  // The disassembly shows the text.
  CHECK(vm::disassemble((*rs)->program()).find("loads") != std::string::npos);
}

TEST_CASE("verify: a program whose string table repeats a text is refused") {
  auto p = test::program("rule \"lid\" when object.name == \"lid\" { speed = 20 mm/s }");
  p.strings.push_back("lid");
  auto rs = vm::RuleSet::create(std::move(p));
  REQUIRE_FALSE(rs.ok());
  CHECK(rs.error().to_string().find("repeats string 0") != std::string::npos);
}
