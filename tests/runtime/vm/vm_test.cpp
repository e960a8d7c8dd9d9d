// The rule VM end to end from rule text: the cascade (last match wins, slot by slot), inherited
// values, hooks and `append`, templates, loops, replacers, hoisting, run-time errors.
#include <doctest/doctest.h>

#include <fmt/format.h>

#include <algorithm>
#include <thread>

#include "runtime/vm/verify.h"
#include "tests/compiler/vm_helpers.h"

using namespace tranche;
using schema::FieldId;
using schema::Level;
using schema::PropId;
using schema::Stage;

namespace {

ctx::Context layer_ctx(int index, double z = 0) {
  ctx::Context c;
  c.clear_from(Level::Layer);
  c.set(FieldId::LayerIndex, index);
  c.set(FieldId::LayerZ, z);
  return c;
}

// Records what a replacer does.
struct Api final : ctx::ReplaceApi {
  std::vector<std::string> log;
  void move_to(double x, double y, const ctx::MoveOptions& o) override {
    std::string s = fmt::format("{} {:g},{:g}", o.travel ? "travel" : "move", x, y);
    if (o.speed) s += fmt::format(" speed={:g}", *o.speed);
    if (o.flow) s += fmt::format(" flow={:g}", *o.flow);
    if (o.width) s += fmt::format(" width={:g}", *o.width);
    log.push_back(s);
  }
  void gcode(std::string_view l) override { log.push_back(std::string(l)); }
  void comment(std::string_view t) override { log.push_back("; " + std::string(t)); }
  Status emit_default() override {
    log.push_back("default");
    return ok_status();
  }
  Status offset(double mm) override {
    log.push_back(fmt::format("offset {:g}", mm));
    return ok_status();
  }
  void retract() override { log.push_back("retract"); }
  Status reverse() override {
    log.push_back("reverse");
    return ok_status();
  }
};

}  // namespace

TEST_CASE("vm: last match wins, slot by slot") {
  auto rs = test::rules(R"(
rule "base" { speed = 60 mm/s; flow = 1.0 }
rule "slow start" when layer.index < 2 { speed = 20 mm/s }
)");
  auto c0 = layer_ctx(0);
  auto p0 = test::decide(*rs, Stage::Piece, c0);
  CHECK(p0[PropId::Speed] == 20);
  CHECK(p0[PropId::Flow] == 1.0);
  auto c5 = layer_ctx(5);
  auto p5 = test::decide(*rs, Stage::Piece, c5);
  CHECK(p5[PropId::Speed] == 60);
  CHECK(rs->varies_at(Stage::Piece) == Level::Layer);
  CHECK(rs->reads(FieldId::LayerIndex));
  CHECK_FALSE(rs->reads(FieldId::IslandArea));
}

TEST_CASE("vm: a property read in its own rule is the value the earlier rules give it") {
  auto rs = test::rules(R"(
rule "profile" { speed = 80 mm/s }
rule "half on small islands" when island.area < 4 mm2 { speed = speed * 50% }
rule "cap" when speed > 50 mm/s { speed = 50 mm/s }
rule "again" when island.area < 1 mm2 { speed = speed - 10 mm/s }
)");
  ctx::Context c;
  c.clear_from(Level::Island);
  c.set(FieldId::IslandArea, 10);
  CHECK(test::decide(*rs, Stage::Piece, c)[PropId::Speed] == 50);  // 80, capped
  // A new island (a new generation): results kept for the previous one are not reused.
  c.clear_from(Level::Island);
  c.set(FieldId::IslandArea, 2);
  CHECK(test::decide(*rs, Stage::Piece, c)[PropId::Speed] == 40);  // 80 halved; cap does not match
  c.clear_from(Level::Island);
  c.set(FieldId::IslandArea, 0.5);
  CHECK(test::decide(*rs, Stage::Piece, c)[PropId::Speed] == 30);  // 80 halved, minus 10
  // No rule matching below: the value below the rules (here what the caller had).
  auto only = test::rules("rule when island.area > 5 mm2 { speed = speed + 5 mm/s }");
  auto props = ctx::PropertyValues::schema_defaults();
  props[PropId::Speed] = 33;
  c.clear_from(Level::Island);
  c.set(FieldId::IslandArea, 10);
  CHECK(test::decide(*only, Stage::Piece, c, props)[PropId::Speed] == 38);
}

TEST_CASE("vm: same-stage properties are decided in dependency order") {
  auto rs = test::rules(R"(
rule "flow follows width" { flow = width / 0.45 mm }
rule "wide" when path.kind == infill { width = 0.9 mm }
)");
  ctx::Context c;
  c.clear_from(Level::Path);
  c.set(FieldId::PathKind, static_cast<double>(schema::PathKind::Infill));
  auto p = test::decide(*rs, Stage::PathPlan, c);
  CHECK(p[PropId::Width] == doctest::Approx(0.9));
  p = test::decide(*rs, Stage::Piece, c, p);
  CHECK(p[PropId::Flow] == doctest::Approx(2.0));
}

TEST_CASE("vm: expressions match the constant folder") {
  // Each rule computes with fields what the checker would fold with constants.
  auto rs = test::rules(R"(
rule { fill_angle = atan2(island.size_y, island.size_x) + abs(-15 deg) }
rule { perimeters = round(island.area / 10 mm2) + 1 }
rule { infill_density = clamp(island.area / 100 mm2, 10%, 90%) }
rule when island.holes mod 3 == 2 and not (island.index in (1, 4)) { top_layers = 7 }
rule when island.area in 20 mm2 .. 30 mm2 { bottom_layers = 9 }
rule { outer_first = island.holes > 1 or island.area > 100 mm2 }
rule { seam = if island.holes == 0 then rear else nearest }
rule { infill_overlap = lerp(10%, 30%, min(1, max(0, sin(island.size_x / 1 mm)))) }
)");
  ctx::Context c;
  c.clear_from(Level::Island);
  c.set(FieldId::IslandSizeX, 10);
  c.set(FieldId::IslandSizeY, 10);
  c.set(FieldId::IslandArea, 25);
  c.set(FieldId::IslandHoles, 5);
  c.set(FieldId::IslandIndex, 2);
  auto p = test::decide(*rs, Stage::Island, c);
  CHECK(p[PropId::FillAngle] == doctest::Approx(60));
  CHECK(p[PropId::Perimeters] == 4);  // round(2.5) = 3 (away from zero), + 1
  CHECK(p[PropId::InfillDensity] == doctest::Approx(0.25));
  CHECK(p[PropId::TopLayers] == 7);
  CHECK(p[PropId::BottomLayers] == 9);
  CHECK(p[PropId::OuterFirst] == 1);
  CHECK(p[PropId::Seam] == static_cast<double>(schema::Seam::Nearest));
  CHECK(p[PropId::InfillOverlap] == doctest::Approx(0.1));  // sin(10 rad) < 0 -> 0
  c.set(FieldId::IslandIndex, 4);
  c.set(FieldId::IslandHoles, 0);
  c.set(FieldId::IslandArea, 19.999);
  p = test::decide(*rs, Stage::Island, c);
  CHECK(p[PropId::TopLayers] == 3);     // schema default: not decided by a rule
  CHECK(p[PropId::BottomLayers] == 3);  // 19.999 is outside 20..30
  CHECK(p[PropId::Seam] == static_cast<double>(schema::Seam::Rear));
}

TEST_CASE("vm: angles are brought into [0, 360), other values must be in their physical range") {
  auto rs = test::rules("rule \"helicoid\" when layer.index >= 3 { fill_angle = 15 deg * layer.index }");
  ctx::Context c;
  c.clear_from(Level::Island);
  c.set(FieldId::LayerIndex, 100);
  CHECK(test::decide(*rs, Stage::Island, c)[PropId::FillAngle] == doctest::Approx(1500 - 4 * 360));
  auto bad = test::rules("rule \"too fast\"\nwhen layer.index > 2 {\n  speed = 400 mm/s * layer.index\n}");
  c.set(FieldId::LayerIndex, 3);
  auto props = ctx::PropertyValues::schema_defaults();
  c.set_props(&props);
  auto s = bad->decide(Stage::Piece, c, props);
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().where == "test.rules:3:11");
  CHECK(s.error().message.find("\"too fast\"") != std::string::npos);
  CHECK(s.error().message.find("1200 mm/s") != std::string::npos);
  CHECK(s.error().message.find("outside its physical range") != std::string::npos);
}

TEST_CASE("vm: division by zero at run time names the rule and the operator") {
  auto rs = test::rules("rule \"ratio\" { fan = clamp(layer.area / below.area, 0, 1) }");
  ctx::Context c;
  c.clear_from(Level::Layer);
  c.set(FieldId::LayerArea, 5);
  auto props = ctx::PropertyValues::schema_defaults();
  c.set_props(&props);
  auto s = rs->decide(Stage::Cooling, c, props);
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().where == "test.rules:1:28");
  CHECK(s.error().message.find("division by zero") != std::string::npos);
  CHECK(s.error().message.find("\"ratio\"") != std::string::npos);
  // Guarded by the filter: never divides.
  auto ok = test::rules("rule when below.area > 0 { fan = clamp(layer.area / below.area, 0, 1) }");
  CHECK(test::decide(*ok, Stage::Cooling, c)[PropId::Fan] == 1);  // schema default
}

TEST_CASE("vm: executors — last match wins, `append` adds, templates format values") {
  auto rs = test::rules(R"(
rule "PA outer wall" when path.kind == outer_perimeter { before path { gcode "M900 K0.045" } }
rule "PA other" when path.kind != outer_perimeter { before path { gcode "M900 K0.02" } }
rule "home" { before print { gcode "G28" } }
rule "level bed too" { before print append { gcode "G29 ; z={print.height:.1}" } }
rule "marks" when layer.index > 0 {
  after layer { comment "layer {layer.index} at z = {layer.z:.2}, {layer.z}" }
}
rule "kinds" { after path { comment "kind {path.kind}, solid {cell.solid}, perimeter {path.perimeter}, {2.5 * 2}" } }
on layer.end when layer.index == 3 append { gcode """M400
  M117 layer {layer.index + 1}""" }
)");
  ctx::Context c;
  c.clear_from(Level::Path);
  c.set(FieldId::PathKind, static_cast<double>(schema::PathKind::OuterPerimeter));
  auto props = ctx::PropertyValues::schema_defaults();
  c.set_props(&props);
  test::Lines out;
  REQUIRE(rs->run(Level::Path, ctx::When::Before, c, out).ok());
  CHECK(out.joined() == "M900 K0.045\n");
  c.set(FieldId::PathKind, static_cast<double>(schema::PathKind::Infill));
  out.lines.clear();
  REQUIRE(rs->run(Level::Path, ctx::When::Before, c, out).ok());
  CHECK(out.joined() == "M900 K0.02\n");

  c.set(FieldId::PrintHeight, 12.34);
  out.lines.clear();
  REQUIRE(rs->run(Level::Print, ctx::When::Before, c, out).ok());
  CHECK(out.joined() == "G28\nG29 ; z=12.3\n");

  c.set(FieldId::LayerIndex, 3);
  c.set(FieldId::LayerZ, 0.8);
  out.lines.clear();
  REQUIRE(rs->run(Level::Layer, ctx::When::After, c, out).ok());
  CHECK(out.joined() == "; layer 3 at z = 0.80, 0.8\nM400\nM117 layer 4\n");
  out.lines.clear();
  c.set(FieldId::PathPerimeter, -1);
  REQUIRE(rs->run(Level::Path, ctx::When::After, c, out).ok());
  CHECK(out.joined() == "; kind infill, solid 0, perimeter -1, 5\n");
  CHECK_FALSE(rs->has(Level::Island, ctx::When::Before));
  CHECK(rs->has(Level::Layer, ctx::When::After));
}

TEST_CASE("vm: an `append` executor alone, and one before the last plain executor, are both cascade-ordered") {
  auto rs = test::rules(R"(
rule "a" { before layer append { gcode "A" } }
rule "b" { before layer { gcode "B" } }
rule "c" { before layer append { gcode "C" } }
rule "d" when layer.index == 7 { before layer append { gcode "D" } }
)");
  auto c = layer_ctx(7);
  auto props = ctx::PropertyValues::schema_defaults();
  c.set_props(&props);
  test::Lines out;
  REQUIRE(rs->run(Level::Layer, ctx::When::Before, c, out).ok());
  CHECK(out.joined() == "B\nC\nD\n");  // "a" lost to "b"
  auto only = test::rules("rule { after layer append { gcode \"X\" } }\nrule { after layer append { gcode \"Y\" } }");
  out.lines.clear();
  REQUIRE(only->run(Level::Layer, ctx::When::After, c, out).ok());
  CHECK(out.joined() == "X\nY\n");
}

TEST_CASE("vm: loops over ranges, points, pieces and islands") {
  auto rs = test::rules(R"(
rule {
  after path {
    for i in 1..3 { gcode "R{i}" }
    for p in path.points { if p.index mod 2 == 0 { gcode "P{p.index} {p.x:.1} {p.y:.1}" } }
    let total = 0 mm
    for pc in path.pieces { if pc.length > 1 mm { comment "long piece {pc.index}: {pc.length:.2}" } }
  }
  before layer { for isl in layer.islands { gcode "I{isl.index} {isl.area}" } }
}
)");
  std::vector<ctx::PointMm> pts = {{0, 0}, {1, 0}, {1, 2}, {3, 2}};
  struct Piece {
    double length;
  };
  static const Piece pieces[] = {{0.5}, {2}, {1.25}};
  ctx::Context c;
  c.clear_from(Level::Path);
  c.set_points(pts);
  c.set_pieces(ctx::Collection(pieces, 3, [](const void* d, size_t i, FieldId f) {
    if (f == FieldId::PieceLength) return static_cast<const Piece*>(d)[i].length;
    if (f == FieldId::PieceIndex) return static_cast<double>(i);
    return 0.0;
  }));
  static const double areas[] = {4, 12.5};
  c.set_islands(ctx::Collection(areas, 2, [](const void* d, size_t i, FieldId f) {
    if (f == FieldId::IslandArea) return static_cast<const double*>(d)[i];
    if (f == FieldId::IslandIndex) return static_cast<double>(i);
    return 0.0;
  }));
  auto props = ctx::PropertyValues::schema_defaults();
  c.set_props(&props);
  test::Lines out;
  REQUIRE(rs->run(Level::Path, ctx::When::After, c, out).ok());
  CHECK(out.joined() ==
        "R1\nR2\nR3\nP0 0.0 0.0\nP2 1.0 2.0\n; long piece 1: 2.00\n; long piece 2: 1.25\n");
  out.lines.clear();
  REQUIRE(rs->run(Level::Layer, ctx::When::Before, c, out).ok());
  CHECK(out.joined() == "I0 4\nI1 12.5\n");
}

TEST_CASE("vm: replacers emit moves, text and the default, and alter the element") {
  auto rs = test::rules(R"(
rule "wavy top" when path.kind == top_solid {
  replace path {
    for p in path.points { move to (p.x, p.y + 0.2 mm * sin(p.x / 1 mm)) }
    comment "wavy top on layer {layer.index}"
  }
}
rule "reverse outer walls" when path.kind == outer_perimeter {
  replace path {
    reverse
    default
    retract
    move to (1 mm, 2 mm) travel
    move to (3 mm, 4 mm) with flow = 90%, speed = 20 mm/s, width = 0.5 mm
  }
}
rule "shrink small islands" when island.area < 10 mm2 {
  replace island {
    offset -0.1 mm
    gcode "M117 small"
    default
  }
}
)");
  std::vector<ctx::PointMm> pts = {{0, 0}, {1.5707963267948966, 1}};
  ctx::Context c;
  c.clear_from(Level::Path);
  c.set(FieldId::LayerIndex, 4);
  c.set(FieldId::PathKind, static_cast<double>(schema::PathKind::TopSolid));
  c.set_points(pts);
  auto props = ctx::PropertyValues::schema_defaults();
  c.set_props(&props);
  Api api;
  auto r = rs->replace(Level::Path, c, api);
  REQUIRE(r.ok());
  CHECK(*r);
  REQUIRE(api.log.size() == 3);
  CHECK(api.log[0] == "move 0,0");
  CHECK(api.log[1] == "move 1.5708,1.2");
  CHECK(api.log[2] == "; wavy top on layer 4");
  api.log.clear();
  c.set(FieldId::PathKind, static_cast<double>(schema::PathKind::OuterPerimeter));
  REQUIRE(*rs->replace(Level::Path, c, api));
  CHECK(api.log ==
        std::vector<std::string>{"reverse", "default", "retract", "travel 1,2", "move 3,4 speed=20 flow=0.9 width=0.5"});
  api.log.clear();
  c.set(FieldId::PathKind, static_cast<double>(schema::PathKind::Infill));
  CHECK_FALSE(*rs->replace(Level::Path, c, api));
  CHECK(api.log.empty());
  c.set(FieldId::IslandArea, 5);
  REQUIRE(*rs->replace(Level::Island, c, api));
  CHECK(api.log == std::vector<std::string>{"offset -0.1", "M117 small", "default"});
}

TEST_CASE("vm: a layer-level condition is evaluated once per layer, not once per piece") {
  auto rs = test::rules(R"(
rule "first layers slow" when layer.index < 2 and path.kind == infill { speed = 20 mm/s }
rule "overhangs" when layer.index > 0 and piece.overhang > 30% { speed = 15 mm/s }
)");
  CHECK(rs->varies_at(Stage::Piece) == Level::Piece);
  ctx::Context c;
  c.clear_from(Level::Layer);
  c.set(FieldId::LayerIndex, 1);
  c.clear_from(Level::Path);
  c.set(FieldId::PathKind, static_cast<double>(schema::PathKind::Infill));
  auto& n = vm::thread_counters();
  auto before = n;
  int slow = 0;
  for (int i = 0; i < 100; ++i) {
    c.clear_from(Level::Piece);
    c.set(FieldId::PieceOverhang, i % 2 ? 0.5 : 0.0);
    auto p = test::decide(*rs, Stage::Piece, c);
    slow += p[PropId::Speed] == 15;
    CHECK(p[PropId::Speed] == (i % 2 ? 15 : 20));
  }
  CHECK(slow == 50);
  // layer.index > 0 and layer.index < 2: evaluated once each; path.kind once; the piece test 100 times.
  uint64_t run = n.conjuncts_run - before.conjuncts_run;
  CHECK(run == 100 + 3);
  CHECK(n.live_rebuilds - before.live_rebuilds == 1);  // one path: one list of live candidates
  // A new layer: evaluated again.
  c.clear_from(Level::Layer);
  c.set(FieldId::LayerIndex, 0);
  c.set(FieldId::PathKind, static_cast<double>(schema::PathKind::Infill));
  c.set(FieldId::PieceOverhang, 0.9);
  CHECK(test::decide(*rs, Stage::Piece, c)[PropId::Speed] == 20);
}

TEST_CASE("vm: codegen fuses a field compared with a constant into one compare-and-branch") {
  auto p = test::program(R"(rule when layer.index < 2 and path.kind in (outer_perimeter, inner_perimeter) {
  speed = 20 mm/s
})",
                         false);
  REQUIRE(p.rules.size() == 1);
  REQUIRE(p.rules[0].count == 2);
  CHECK(vm::disassemble_chunk(p, p.conjuncts[0].chunk) ==
        "   0  jnlt.fk    layer.index, K0(2), ->2\n"
        "   1  retk       K1(1)\n"
        "   2  retk       K2(0)\n");
  CHECK(vm::disassemble_chunk(p, p.conjuncts[1].chunk) ==
        "   0  jeq.fk     path.kind, K2(0), ->3\n"
        "   1  jeq.fk     path.kind, K1(1), ->3\n"
        "   2  jmp        ->4\n"
        "   3  retk       K1(1)\n"
        "   4  retk       K2(0)\n");
  CHECK(vm::disassemble_chunk(p, p.props[static_cast<size_t>(PropId::Speed)][0].chunk) == "   0  retk       K3(20)\n");
}

TEST_CASE("vm: a rule reading its own property compiles to `inherit` of the rules before it") {
  auto p = test::program("rule { speed = 80 mm/s }\nrule when island.area < 4 mm2 { speed = speed * 50% }", false);
  const auto& cands = p.props[static_cast<size_t>(PropId::Speed)];
  REQUIRE(cands.size() == 2);
  CHECK(cands[0].rule == 1);
  CHECK(cands[1].rule == 0);
  CHECK(vm::disassemble_chunk(p, cands[0].chunk) ==
        "   0  inherit    r1, speed, rule1\n"
        "   1  loadk      r2, K4(0.5)\n"
        "   2  mul        r0, r1, r2\n"
        "   3  ret        r0\n");
}

TEST_CASE("vm: loops are bounded at run time") {
  auto rs = test::rules(R"(
rule { after path { for p in path.points { for q in path.points { for r in path.points { gcode "" } } } } }
)");
  std::vector<ctx::PointMm> pts(400);
  ctx::Context c;
  c.clear_from(Level::Path);
  c.set_points(pts);
  auto props = ctx::PropertyValues::schema_defaults();
  c.set_props(&props);
  test::Lines out;
  auto s = rs->run(Level::Path, ctx::When::After, c, out);
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().message.find("steps") != std::string::npos);
}

TEST_CASE("vm: one RuleSet decides on many threads at once, as layers run in parallel") {
  auto rs = test::rules(R"(
rule "base" { speed = 60 mm/s }
rule when layer.index < 2 { speed = 20 mm/s }
rule when island.area < 4 mm2 { speed = speed * 50% }
rule when piece.overhang > 30% and layer.index > 0 { speed = 15 mm/s }
rule { after path { comment "p {layer.index} {island.area:.1}" } }
)");
  auto one = [&](int i) {
    ctx::Context c;
    c.clear_from(Level::Layer);
    c.set(FieldId::LayerIndex, i % 7);
    c.clear_from(Level::Island);
    c.set(FieldId::IslandArea, (i % 5) * 1.5);
    c.clear_from(Level::Path);
    double sum = 0;
    for (int k = 0; k < 20; ++k) {
      c.clear_from(Level::Piece);
      c.set(FieldId::PieceOverhang, (k % 3) * 0.2);
      auto props = ctx::PropertyValues::schema_defaults();
      c.set_props(&props);
      if (!rs->decide(Stage::Piece, c, props).ok()) return -1.0;
      sum += props[PropId::Speed];
    }
    test::Lines out;
    if (!rs->run(Level::Path, ctx::When::After, c, out).ok() || out.lines.size() != 1) return -1.0;
    return sum + static_cast<double>(out.lines[0].size());
  };
  const int n = 4000;
  std::vector<double> serial(n), parallel(n);
  for (int i = 0; i < n; ++i) serial[static_cast<size_t>(i)] = one(i);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int i = t; i < n; i += 4) parallel[static_cast<size_t>(i)] = one(i);
    });
  for (auto& th : threads) th.join();
  CHECK(serial == parallel);
  CHECK(std::find(serial.begin(), serial.end(), -1.0) == serial.end());
}

TEST_CASE("vm: a value that is not a number, a negative square root and a runaway template are errors") {
  ctx::Context c;
  c.clear_from(Level::Layer);
  c.set(FieldId::LayerZ, 1e300);
  auto props = ctx::PropertyValues::schema_defaults();
  c.set_props(&props);
  auto inf = test::rules("rule \"huge\" { fan = layer.z * layer.z / 1 mm2 }");
  auto s = inf->decide(Stage::Cooling, c, props);
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().message.find("not a number") != std::string::npos);
  auto nan = test::rules("rule \"nan\" { fan = (layer.z * layer.z - layer.z * layer.z) / 1 mm2 }");
  s = nan->decide(Stage::Cooling, c, props);
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().message.find("not a number") != std::string::npos);
  auto root = test::rules("rule \"root\" { fan = sqrt(-layer.z * 1 mm) / 1 mm }");
  s = root->decide(Stage::Cooling, c, props);
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().where == "test.rules:1:21");
  CHECK(s.error().message.find("square root of a negative number") != std::string::npos);
  auto text = test::rules(R"(rule "long" { after layer { for i in 1..9000 { gcode "{i} {i} {i}" } } })");
  test::Lines out;
  c.set(FieldId::LayerZ, 1);
  CHECK(text->run(Level::Layer, ctx::When::After, c, out).ok());  // many lines: fine
  CHECK(out.lines.size() == 9000);
  // One template that grows without bound: refused.
  std::string big = "rule \"big\" { after layer { gcode \"";
  for (int i = 0; i < 6000; ++i) big += "{layer.z:.12}";  // 14 characters each
  big += "\" } }";
  auto huge = test::rules(big);
  out.lines.clear();
  auto r = huge->run(Level::Layer, ctx::When::After, c, out);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().message.find("more than 65536 characters") != std::string::npos);
  CHECK(r.error().message.find("\"big\"") != std::string::npos);
}

namespace {
struct Recorder final : ctx::Trace {
  std::vector<ctx::TraceStep> steps;
  std::vector<std::pair<uint32_t, std::string>> hooks;
  std::vector<uint32_t> replacers;
  void step(const ctx::TraceStep& s) override { steps.push_back(s); }
  void hook(Level, ctx::When, uint32_t rule, std::string_view text) override { hooks.emplace_back(rule, text); }
  void replaced(Level, uint32_t rule) override { replacers.push_back(rule); }
};
}  // namespace

TEST_CASE("vm: a trace records the deciding rule and the values it read from the rules before it") {
  auto rs = test::rules(R"(
rule "profile" { speed = 80 mm/s }
rule "half on small islands" when island.area < 4 mm2 { speed = speed * 50% }
rule "again" when island.area < 1 mm2 { speed = speed - 10 mm/s }
)");
  ctx::Context c;
  c.clear_from(Level::Island);
  c.set(FieldId::IslandArea, 0.5);
  Recorder r;
  c.set_trace(&r);
  CHECK(test::decide(*rs, Stage::Piece, c)[PropId::Speed] == 30);
  // Inner reads first (deepest first), then the decision: 80 (rule 0) -> 40 (rule 1) -> 30 (rule 2).
  REQUIRE(r.steps.size() == 3);
  CHECK(r.steps[0].rule == 0);
  CHECK(r.steps[0].value == 80);
  CHECK(r.steps[0].depth == 2);
  CHECK(r.steps[1].rule == 1);
  CHECK(r.steps[1].value == 40);
  CHECK(r.steps[1].depth == 1);
  CHECK(r.steps[2].rule == 2);
  CHECK(r.steps[2].value == 30);
  CHECK(r.steps[2].depth == 0);
  for (const auto& s : r.steps) CHECK(s.source == ctx::TraceStep::Source::Rule);
  CHECK(rs->rule_name(r.steps[1].rule) == "rule \"half on small islands\"");
  // Without a trace nothing is recorded (and the result is the same).
  c.set_trace(nullptr);
  CHECK(test::decide(*rs, Stage::Piece, c)[PropId::Speed] == 30);
  CHECK(r.steps.size() == 3);
}

TEST_CASE("vm: a trace records executors with their text, and the replacer that ran") {
  auto rs = test::rules(R"(
rule "pa" when path.kind == outer_perimeter { before path { gcode "M900 K0.04" } }
rule "extra" when path.kind == outer_perimeter { before path append { gcode "; hello" } }
rule "wavy" when path.kind == top_solid { replace path { default } }
)");
  ctx::Context c;
  auto props = ctx::PropertyValues::schema_defaults();
  c.set_props(&props);
  c.set(FieldId::PathKind, static_cast<double>(schema::PathKind::OuterPerimeter));
  Recorder r;
  c.set_trace(&r);
  test::Lines out;
  REQUIRE(rs->run(Level::Path, ctx::When::Before, c, out).ok());
  CHECK(out.joined() == "M900 K0.04\n; hello\n");
  REQUIRE(r.hooks.size() == 2);
  CHECK(r.hooks[0] == std::pair<uint32_t, std::string>{0, "M900 K0.04"});
  CHECK(r.hooks[1] == std::pair<uint32_t, std::string>{1, "; hello"});
  struct Api final : ctx::ReplaceApi {
    void move_to(double, double, const ctx::MoveOptions&) override {}
    void gcode(std::string_view) override {}
    void comment(std::string_view) override {}
    Status emit_default() override { return ok_status(); }
    Status offset(double) override { return ok_status(); }
    Status reverse() override { return ok_status(); }
    void retract() override {}
  } api;
  c.set(FieldId::PathKind, static_cast<double>(schema::PathKind::TopSolid));
  auto replaced = rs->replace(Level::Path, c, api);
  REQUIRE(replaced.ok());
  CHECK(*replaced);
  CHECK(r.replacers == std::vector<uint32_t>{2});
}

TEST_CASE("vm: any and all over a range of layers stop at the step that decides") {
  auto rs = test::rules(R"(
rule "step" when layer.index > 3 and any(i in 1..3: layers[layer.index - i].area < layer.area * 80%) { fan = 50% }
rule "steady" when all(k in 1..2: layers[layer.index - k].islands == layer.islands) { flow = 90% }
rule "nested" when any(i in 0..2: all(j in 0..1: layers[i + j].area > 0)) and layer.index == 9 { speed = 7 mm/s }
rule "empty" when any(i in 3..1: layer.index > 0) { width = 0.3 mm }
)");
  // Areas by layer: 10, 10, 10, 10, 12, 12, 13, 14, 20, 0 (the last layer is empty).
  static const double area[] = {10, 10, 10, 10, 12, 12, 13, 14, 20, 0};
  static const double islands[] = {1, 1, 1, 2, 2, 2, 2, 1, 1, 1};
  ctx::LayerTable table(10);
  for (size_t i = 0; i < 10; ++i) {
    table.set(i, FieldId::LayerIndex, static_cast<double>(i));
    table.set(i, FieldId::LayerArea, area[i]);
    table.set(i, FieldId::LayerIslands, islands[i]);
  }
  auto at = [&](int index) {
    ctx::Context c = layer_ctx(index);
    c.set_layers(&table);
    c.set(FieldId::LayerArea, area[index]);
    c.set(FieldId::LayerIslands, islands[index]);
    auto p = ctx::PropertyValues::schema_defaults();
    for (int st = 0; st < schema::kStageCount; ++st) p = test::decide(*rs, static_cast<Stage>(st), c, p);
    return p;
  };
  // Layer 8 (20 mm2): layers 5..7 are all under 80% of it. Layer 5 (12 mm2): 10, 10 and 12 are not.
  CHECK(at(8)[PropId::Fan] == 0.5);
  CHECK(at(5)[PropId::Fan] == 1.0);
  // Layer 4 (12 mm2) over layer 3 (10 mm2): 10 < 9.6 is false for 1..3. Layer 3 is filtered out.
  CHECK(at(4)[PropId::Fan] == 1.0);
  // all: layer 6 (2 islands) over 5 and 4 (2 each) holds; layer 3 over 2 (1 island) does not.
  CHECK(at(6)[PropId::Flow] == doctest::Approx(0.9));
  CHECK(at(3)[PropId::Flow] == doctest::Approx(1.0));
  // Nested quantifiers read the outer variable; an empty range makes `any` false.
  CHECK(at(9)[PropId::Speed] == doctest::Approx(7));
  CHECK(at(9)[PropId::Width] != doctest::Approx(0.3));
}

TEST_CASE("vm: a quantifier compiles to a bounded loop: load, test, increment, jump back") {
  auto p = test::program("rule when any(i in 1..3: layers[layer.index - i].area > 0) { fan = 0% }\n");
  std::vector<vm::Op> ops;
  for (const auto& in : p.code) ops.push_back(in.code());
  auto has = [&](vm::Op op) { return std::find(ops.begin(), ops.end(), op) != ops.end(); };
  CHECK(has(vm::Op::JGtRK));
  CHECK(has(vm::Op::Incr));
  CHECK(has(vm::Op::Jmp));
  CHECK(vm::verify(p).ok());
}

TEST_CASE("vm: what a path's piece decisions depend on, given the rules its own fields leave in play") {
  // The stdlib's overhang steps: on walls only, reading their own property (min(speed, ...)).
  auto rs = test::rules(R"(
rule "walls over air" when path.kind in (outer_perimeter, inner_perimeter) and piece.overhang >= 25% {
  speed = min(speed, 20 mm/s)
}
rule "capped" when path.kind == infill { speed = min(speed, 60 mm/s) }
rule "long pieces" when path.kind == skirt and piece.length > 5 mm { flow = 95% }
rule "bridges" when path.kind == bridge and layer.index > 2 { flow = 80% }
)");
  REQUIRE(rs->varies_at(Stage::Piece) == Level::Piece);
  ctx::Context c;
  c.clear_from(Level::Layer);
  c.set(FieldId::LayerIndex, 3);
  auto at = [&](schema::PathKind kind) {
    c.clear_from(Level::Path);
    c.set(FieldId::PathKind, static_cast<double>(kind));
    auto d = rs->depends(Stage::Piece, c);
    REQUIRE(d.ok());
    return *d;
  };
  auto overhang = static_cast<size_t>(FieldId::PieceOverhang);
  auto length = static_cast<size_t>(FieldId::PieceLength);
  // Infill: only "capped" is in play, and reading speed in its own rule does not make it vary.
  auto infill = at(schema::PathKind::Infill);
  CHECK(infill.level < Level::Piece);
  CHECK(infill.fields.none());
  // Walls vary along the path and need piece.overhang, not piece.length.
  auto wall = at(schema::PathKind::OuterPerimeter);
  CHECK(wall.level == Level::Piece);
  CHECK(wall.fields[overhang]);
  CHECK_FALSE(wall.fields[length]);
  auto skirt = at(schema::PathKind::Skirt);
  CHECK(skirt.level == Level::Piece);
  CHECK(skirt.fields[length]);
  CHECK_FALSE(skirt.fields[overhang]);
  auto bridge = at(schema::PathKind::Bridge);
  CHECK(bridge.level < Level::Piece);
  CHECK(bridge.fields.none());
  // Nothing but these piece decisions reads piece.overhang.
  CHECK_FALSE(rs->reads_beyond(Stage::Piece, FieldId::PieceOverhang));
  CHECK(rs->reads(FieldId::PieceOverhang));

  // The same decisions as without asking: the live list depends() built is the one decide() uses.
  c.clear_from(Level::Path);
  c.set(FieldId::PathKind, static_cast<double>(schema::PathKind::OuterPerimeter));
  REQUIRE(rs->depends(Stage::Piece, c).ok());
  c.set(FieldId::PieceOverhang, 0.5);
  CHECK(test::decide(*rs, Stage::Piece, c)[PropId::Speed] == 20);
  c.set(FieldId::PieceOverhang, 0.1);
  CHECK(test::decide(*rs, Stage::Piece, c)[PropId::Speed] != 20);
}

TEST_CASE("vm: piece.overhang read by a fan rule or a hook is read beyond the piece decisions") {
  auto fan = test::rules(R"(rule when piece.overhang > 50% { fan = 100% })");
  CHECK(fan->reads_beyond(Stage::Piece, FieldId::PieceOverhang));
  auto hook = test::rules(R"(rule { before path { for pc in path.pieces { if pc.overhang > 50% { comment "air" } } } })");
  CHECK(hook->reads_beyond(Stage::Piece, FieldId::PieceOverhang));
  // A condition shared by a piece decision and a cooling one counts for the cooling one.
  auto shared = test::rules(R"(rule when piece.overhang > 50% {
  speed = 10 mm/s
  fan = 100%
})");
  CHECK(shared->reads_beyond(Stage::Piece, FieldId::PieceOverhang));
  auto piece_only = test::rules(R"(rule when piece.overhang > 50% { speed = 10 mm/s })");
  CHECK_FALSE(piece_only->reads_beyond(Stage::Piece, FieldId::PieceOverhang));
}
