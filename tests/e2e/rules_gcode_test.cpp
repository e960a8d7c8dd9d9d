// End to end with rules: every example of the language's design (LANGUAGE.md), sliced from a
// generated mesh with `--rules`, checked on the G-code a printer would receive.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>

#include "compiler/codegen.h"
#include "compiler/frontend.h"
#include "gcode_reader.h"
#include "geometry/fillangle/fill_angle.h"
#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "apps/slice_command.h"
#include "runtime/vm/bundle.h"
#include "tests/support/fixtures.h"

using namespace tranche;
namespace fs = std::filesystem;

namespace {

std::string write_file(const test::TempDir& dir, const std::string& name, const std::string& text) {
  std::string path = (dir / name).string();
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

struct Run {
  pipeline::SliceOptions options;
  std::vector<Warning> warnings;
  Result<pipeline::SliceSummary> result = Error{"", "not run"};
};

Run run(const test::TempDir& dir, const std::string& name, const geo::Mesh& mesh, const std::vector<std::string>& rules,
        std::vector<std::pair<std::string, std::string>> sets = {}) {
  Run r;
  r.options.quiet = true;
  r.options.model = (dir / (name + ".stl")).string();
  REQUIRE(geo::write_stl_binary(r.options.model, mesh).ok());
  r.options.output_gcode = (dir / (name + ".gcode")).string();
  r.options.rules = rules;
  r.options.sets = {{"skirt_loops", "0"}};
  r.options.sets.insert(r.options.sets.end(), sets.begin(), sets.end());
  Report report;
  r.result = app::slice(r.options, report);
  r.warnings = report.warnings();
  return r;
}

test::Gcode slice(const test::TempDir& dir, const std::string& name, const geo::Mesh& mesh, const std::string& rules,
                  std::vector<std::pair<std::string, std::string>> sets = {}) {
  std::vector<std::string> files;
  if (!rules.empty()) files.push_back(write_file(dir, name + ".rules", rules));
  auto r = run(dir, name, mesh, files, std::move(sets));
  REQUIRE_MESSAGE(r.result.ok(), (r.result.ok() ? "" : r.result.error().to_string()));
  for (const auto& w : r.warnings) CHECK_MESSAGE(w.code != "rules", w.where << ": " << w.message);
  return test::read_gcode(r.options.output_gcode);
}

bool extrudes(const test::Move& m) { return m.has_xy && m.de > 0; }

// Direction of a segment as an undirected line, in [0, 180) degrees.
double line_angle(const test::Move& m) {
  double a = std::atan2(m.y - m.y0, m.x - m.x0) * 180 / std::numbers::pi;
  a = std::fmod(a + 360, 180);
  return a;
}

}  // namespace

SCENARIO("rules: per-feature pressure advance before every outer wall, and nowhere else") {
  test::TempDir dir("rules-pa");
  auto g = slice(dir, "pa", geo::plate_with_holes(20, 20, 2, 2, 2, 2, 24), R"(
rule "PA outer wall" when path.kind == outer_perimeter {
  before path { gcode "M900 K0.045" }
}
)");
  // Each M900 is followed by an outer perimeter before any other extrusion; each outer
  // perimeter path (after a travel) has an M900 since the previous extrusion.
  size_t m900 = 0, outer_paths = 0;
  size_t last_extrusion_line = 0;
  bool in_outer = false;
  for (const auto& m : g.moves) {
    if (!m.has_xy) continue;
    if (!extrudes(m)) {
      if (!(m.has_e && m.de == 0)) in_outer = false;  // a zero-length extrusion is not a travel
      continue;
    }
    bool outer = m.type == "External perimeter";
    if (outer && !in_outer) {
      ++outer_paths;
      bool seen = false;
      for (size_t l = last_extrusion_line + 1; l < m.line; ++l) seen = seen || g.lines[l] == "M900 K0.045";
      CHECK_MESSAGE(seen, "outer perimeter at line " << m.line << " without M900");
    }
    if (!outer) {
      for (size_t l = last_extrusion_line + 1; l < m.line; ++l)
        CHECK_MESSAGE(g.lines[l] != "M900 K0.045", "M900 before a " << m.type << " at line " << m.line);
    }
    in_outer = outer;
    last_extrusion_line = m.line;
  }
  for (const auto& l : g.lines) m900 += l == "M900 K0.045";
  CHECK(outer_paths >= 10 * 5);  // 10 layers, an outline and 4 holes each
  CHECK(m900 == outer_paths);
}

SCENARIO("rules: slower speed on the first two layers only, and last match wins slot by slot") {
  test::TempDir dir("rules-slow");
  auto g = slice(dir, "slow", geo::box({30, 30, 2}), R"(
rule "base" { speed = 50 mm/s; flow = 1.0 }
rule "first layers slow" when layer.index < 2 {
  speed = 12 mm/s
}
)",
                 {{"min_layer_time", "0"}});
  std::map<int, std::set<double>> feeds;
  for (const auto& m : g.moves)
    if (extrudes(m) && m.type != "Skirt/Brim") feeds[m.layer].insert(m.f);
  REQUIRE(feeds.size() == 10);
  for (const auto& [layer, fs] : feeds) {
    if (layer < 2)
      CHECK(fs == std::set<double>{720});
    else
      CHECK(fs == std::set<double>{3000});
  }
}

SCENARIO("rules: fan 100% on islands under 4 mm², and the property a rule reads is the earlier value") {
  test::TempDir dir("rules-fan");
  geo::Mesh m = geo::box({20, 20, 3});
  geo::append(m, geo::translated(geo::box({1.5, 1.5, 3}), {30, 0, 0}));
  auto g = slice(dir, "fan", m, R"(
rule "base" { fan = 20% }
rule "small islands cool down" when island.area < 4 mm2 { speed = 15 mm/s; fan = 100% }
rule "halve the base on big ones" when island.area > 100 mm2 { fan = fan * 50% }
)",
                 {{"min_layer_time", "0"}});
  // Bed coordinates: the scene is centred at x = 100; the pillar is the rightmost part.
  int small = 0, big = 0;
  for (const auto& mv : g.moves) {
    if (!extrudes(mv) || mv.layer < 1 || mv.type == "Skirt/Brim") continue;
    if (mv.x > 110) {
      ++small;
      CHECK(mv.fan == doctest::Approx(1.0));
      CHECK(mv.f == 900);
    } else {
      ++big;
      CHECK(mv.fan == doctest::Approx(0.1).epsilon(0.02));
    }
  }
  CHECK(small > 20);
  CHECK(big > 100);
}

SCENARIO("rules: a helicoid rotates the infill 15° a layer") {
  test::TempDir dir("rules-helicoid");
  auto g = slice(dir, "helicoid", geo::box({30, 30, 4}), R"(
rule "helicoid" when layer.index >= 3 { fill_angle = 15 deg * layer.index }
)",
                 {{"top_layers", "0"}, {"bottom_layers", "0"}});
  // The longest sparse-infill line of each layer runs at the layer's angle.
  std::map<int, std::pair<double, double>> longest;  // layer -> (length, angle)
  for (const auto& m : g.moves) {
    if (!extrudes(m) || m.type != "Internal infill") continue;
    double len = std::hypot(m.x - m.x0, m.y - m.y0);
    auto& l = longest[m.layer];
    if (len > l.first) l = {len, line_angle(m)};
  }
  REQUIRE(longest.size() >= 15);
  for (const auto& [layer, l] : longest) {
    if (layer < 3) continue;
    double want = std::fmod(15.0 * layer, 180.0);
    double diff = std::abs(l.second - want);
    diff = std::min(diff, 180 - diff);
    CHECK_MESSAGE(diff < 0.5, "layer " << layer << ": " << l.second << " deg, want " << want);
  }
}

SCENARIO("rules: a replacer's moves stand in place of the default path") {
  test::TempDir dir("rules-wavy");
  auto box = geo::box({20, 20, 2});
  auto plain = slice(dir, "plain", box, "");
  auto wavy = slice(dir, "wavy", box, R"(
rule "wavy top" when path.kind == top_solid {
  replace path {
    for p in path.points { move to (p.x, p.y + 0.2 mm * sin(p.x / 1 mm)) }
    comment "wavy top on layer {layer.index}"
  }
}
)");
  // Same points, moved by 0.2 sin(x), on the top layers; everything else unchanged.
  std::multiset<std::pair<long, long>> want, got;
  auto key = [](double x, double y) { return std::pair<long, long>(std::lround(x * 100), std::lround(y * 100)); };
  for (const auto& m : plain.moves)
    if (extrudes(m) && m.type == "Top solid infill") want.insert(key(m.x, m.y + 0.2 * std::sin(m.x)));
  for (const auto& m : wavy.moves)
    if (extrudes(m) && m.type == "Top solid infill") got.insert(key(m.x, m.y));
  REQUIRE(want.size() > 50);
  // The replacer also extrudes to the first point (moved), after the travel to the path's start.
  // (coordinates are written with 3 decimals: allow a rounding step either way)
  auto near = [&](std::pair<long, long> k) {
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy)
        if (got.count({k.first + dx, k.second + dy})) return true;
    return false;
  };
  for (const auto& k : want) CHECK_MESSAGE(near(k), k.first << "," << k.second);
  CHECK(got.size() >= want.size());
  CHECK(got.size() <= want.size() + 5);
  for (const auto& m : wavy.moves)  // no long extrusion from the previous path
    if (extrudes(m) && m.type == "Top solid infill") CHECK(std::hypot(m.x - m.x0, m.y - m.y0) < 30);
  CHECK(wavy.contains("; wavy top on layer 9"));
  CHECK_FALSE(wavy.contains("; wavy top on layer 5"));
  size_t plain_perims = 0, wavy_perims = 0;
  for (const auto& m : plain.moves) plain_perims += extrudes(m) && m.type == "External perimeter";
  for (const auto& m : wavy.moves) wavy_perims += extrudes(m) && m.type == "External perimeter";
  CHECK(plain_perims == wavy_perims);
}

SCENARIO("rules: `on layer.start` at layer 10 only") {
  test::TempDir dir("rules-m600");
  auto g = slice(dir, "m600", geo::box({10, 10, 4}), R"(
on layer.start when layer.index == 10 { gcode "M600 ; colour change" }
)");
  std::vector<size_t> at;
  for (size_t i = 0; i < g.lines.size(); ++i)
    if (g.lines[i] == "M600 ; colour change") at.push_back(i);
  REQUIRE(at.size() == 1);
  size_t layer10 = 0, layer11 = 0;
  for (size_t i = 0; i < g.lines.size(); ++i) {
    if (g.lines[i] == ";LAYER:10") layer10 = i;
    if (g.lines[i] == ";LAYER:11") layer11 = i;
  }
  CHECK(at[0] > layer10);
  CHECK(at[0] < layer11);
  for (const auto& m : g.moves)  // before any extrusion of layer 10
    if (m.layer == 10 && extrudes(m)) CHECK(m.line > at[0]);
}

SCENARIO("rules: variable layer height gives the expected z values") {
  test::TempDir dir("rules-vlh");
  auto g = slice(dir, "vlh", geo::box({10, 10, 4}), R"(
rule "fine above 2 mm" when layer.z_bottom >= 2 mm { layer_height = 0.1 mm }
)");
  REQUIRE(g.layer_z.size() == 30);
  for (int i = 0; i < 10; ++i) CHECK(g.layer_z.at(i) == doctest::Approx(0.2 * (i + 1)));
  for (int i = 10; i < 30; ++i) CHECK(g.layer_z.at(i) == doctest::Approx(2.0 + 0.1 * (i - 9)));
}

SCENARIO("rules: a bundle slices exactly like its source, and `--set` expressions are implicit last rules") {
  test::TempDir dir("rules-bundle");
  const std::string text = R"(
rule "first layers slow" when layer.index < 2 { speed = 20 mm/s }
rule "PA" when path.kind == outer_perimeter { before path { gcode "M900 K{0.04 + layer.index * 0.001:.3}" } }
)";
  std::string src = write_file(dir, "r.rules", text);
  diag::Sink sink;
  auto program = compiler::compile({src}, {}, {}, sink);
  REQUIRE(program.checked);
  auto p = compiler::generate(program);
  REQUIRE(p.ok());
  std::string bundle = write_file(dir, "r.bundle", vm::write_bundle(*p));
  auto box = geo::box({10, 10, 2});
  auto a = run(dir, "from-rules", box, {src});
  auto b = run(dir, "from-bundle", box, {bundle});
  REQUIRE(a.result.ok());
  REQUIRE(b.result.ok());
  auto ga = test::read_gcode(a.options.output_gcode), gb = test::read_gcode(b.options.output_gcode);
  auto body = [](const test::Gcode& g) { return g.text.substr(g.text.find(";LAYER:0")); };
  CHECK(body(ga) == body(gb));
  CHECK(ga.contains("M900 K0.049"));
  // --set with an expression: the same as a last rule.
  auto c = run(dir, "set-expr", box, {bundle}, {{"speed", "speed * 50%"}});
  REQUIRE_MESSAGE(c.result.ok(), (c.result.ok() ? "" : c.result.error().to_string()));
  auto gc = test::read_gcode(c.options.output_gcode);
  for (const auto& m : gc.moves)
    if (extrudes(m) && m.layer < 2 && m.type != "Skirt/Brim") CHECK(m.f == 600);
}

SCENARIO("rules: bad rules and run-time errors stop the slice with the rule's location and no output") {
  test::TempDir dir("rules-errors");
  auto box = geo::box({10, 10, 2});
  auto bad = run(dir, "bad", box, {write_file(dir, "bad.rules", "rule when layer.index < 2 { sped = 20 mm/s }\n")});
  REQUIRE_FALSE(bad.result.ok());
  CHECK(bad.result.error().message.find("E0103") != std::string::npos);
  CHECK(bad.result.error().message.find("did you mean `speed`?") != std::string::npos);
  CHECK_FALSE(fs::exists(bad.options.output_gcode));
  auto div = run(dir, "div", box,
                 {write_file(dir, "div.rules", "rule \"ramp\" {\n  speed = 100 mm/s / (layer.index - 5) * (layer.index - 5)\n}\n")});
  REQUIRE_FALSE(div.result.ok());
  CHECK(div.result.error().where.find("div.rules:2:") != std::string::npos);
  CHECK(div.result.error().message.find("division by zero") != std::string::npos);
  CHECK_FALSE(fs::exists(div.options.output_gcode));
  auto damaged = write_file(dir, "x.bundle", std::string("TRNCHRUL") + std::string(100, '\0'));
  auto dmg = run(dir, "dmg", box, {damaged});
  REQUIRE_FALSE(dmg.result.ok());
  CHECK(dmg.result.error().where == damaged);
  auto missing = run(dir, "missing", box, {(dir / "nope.rules").string()});
  REQUIRE_FALSE(missing.result.ok());
  CHECK(missing.result.error().message.find("cannot open the rules file: No such file or directory") !=
        std::string::npos);
}

SCENARIO("rules: fill_angle rules win over the Python script, which wins over the default") {
  if (!geo::FillAngleScript::available()) return;  // built without Python
  test::TempDir dir("rules-script");
  auto box = geo::box({30, 30, 3});
  Run r;
  r.options.quiet = true;
  r.options.model = (dir / "box.stl").string();
  REQUIRE(geo::write_stl_binary(r.options.model, box).ok());
  r.options.output_gcode = (dir / "box.gcode").string();
  r.options.fill_angle_script = write_file(dir, "zero.py", "def fill_angle(ctx):\n    return 0\n");
  r.options.rules = {write_file(dir, "r.rules", "rule when layer.index >= 8 { fill_angle = 90 deg }\n")};
  r.options.sets = {{"skirt_loops", "0"}, {"top_layers", "0"}, {"bottom_layers", "0"}};
  Report report;
  auto res = app::slice(r.options, report);
  REQUIRE_MESSAGE(res.ok(), (res.ok() ? "" : res.error().to_string()));
  auto g = test::read_gcode(r.options.output_gcode);
  std::map<int, std::pair<double, double>> longest;
  for (const auto& m : g.moves) {
    if (!extrudes(m) || m.type != "Internal infill") continue;
    double len = std::hypot(m.x - m.x0, m.y - m.y0);
    auto& l = longest[m.layer];
    if (len > l.first) l = {len, line_angle(m)};
  }
  REQUIRE(longest.size() >= 12);
  for (const auto& [layer, l] : longest) {
    double want = layer >= 8 ? 90 : 0;
    double diff = std::min(std::abs(l.second - want), 180 - std::abs(l.second - want));
    CHECK_MESSAGE(diff < 0.5, "layer " << layer << ": " << l.second);
  }
}

SCENARIO("rules: a replacer alters the island for what follows (offset before the default)") {
  test::TempDir dir("rules-offset");
  auto box = geo::box({20, 20, 1});
  auto plain = slice(dir, "plain", box, "");
  auto shrunk = slice(dir, "shrunk", box, R"(
rule "shrink big islands" when island.area > 100 mm2 {
  replace island {
    offset -1 mm
    comment "shrunk island {island.index}: {island.area:.0} mm2"
    default
  }
}
)");
  auto extent = [](const test::Gcode& g) {
    double lo = 1e9, hi = -1e9;
    for (const auto& m : g.moves)
      if (extrudes(m) && m.type == "External perimeter") lo = std::min(lo, m.x), hi = std::max(hi, m.x);
    return hi - lo;
  };
  CHECK(extent(plain) - extent(shrunk) == doctest::Approx(2.0).epsilon(0.01));
  // After `offset`, the replacer reads the altered island: 18 × 18 mm.
  CHECK(shrunk.contains("; shrunk island 0: 324 mm2"));
  // A path replacer: `reverse`, then the reversed path's own fields; moves with their own width.
  auto moved = slice(dir, "moved", box, R"(
rule "walls backwards" when path.kind == outer_perimeter {
  replace path {
    reverse
    for p in path.points { if p.index == 1 { comment "second point {p.x:.3} {p.y:.3}" } }
    move to (100 mm, 100 mm) with width = 0.6 mm, flow = 50%
  }
}
)");
  CHECK(moved.contains(";WIDTH:0.6"));
  // The plain outer perimeter's second-to-last point is the reversed path's second point.
  std::vector<const test::Move*> outer;
  for (const auto& m : plain.moves)
    if (m.layer == 0 && extrudes(m) && m.type == "External perimeter") outer.push_back(&m);
  REQUIRE(outer.size() >= 3);
  const auto* before_last = outer[outer.size() - 2];
  CHECK(moved.contains(fmt::format("; second point {:.3f} {:.3f}", before_last->x, before_last->y)));
}

SCENARIO("rules: a param is changed with --set, without editing the file") {
  test::TempDir dir("rules-param");
  const std::string rules = R"(
param pause_height = 1 mm
rule "pause" when layer.z_bottom >= pause_height and below.z_bottom < pause_height {
  before layer { gcode "M601 ; pause at {pause_height:.1} mm" }
}
)";
  auto box = geo::box({10, 10, 3});
  auto at_layer = [](const test::Gcode& g) {
    int layer = -1, count = 0;
    for (const auto& l : g.lines) {
      if (l.rfind(";LAYER:", 0) == 0) layer = std::stoi(l.substr(7));
      if (l.rfind("M601", 0) == 0) ++count;
      if (l.rfind("M601", 0) == 0 && count == 1) return std::pair<int, std::string>(layer, l);
    }
    return std::pair<int, std::string>(count == 0 ? -1 : -2, "");
  };
  auto plain = slice(dir, "plain", box, rules);
  CHECK(at_layer(plain) == std::pair<int, std::string>(5, "M601 ; pause at 1.0 mm"));  // z_bottom 1.0
  auto moved = slice(dir, "moved", box, rules, {{"pause_height", "2.1"}});            // 2.1 mm
  CHECK(at_layer(moved) == std::pair<int, std::string>(11, "M601 ; pause at 2.1 mm"));  // z_bottom 2.2
}

SCENARIO("rules: `retract` in a replacer pulls the filament back before its own travel") {
  test::TempDir dir("rules-retract");
  auto g = slice(dir, "wipe", geo::box({20, 20, 1}), R"(
rule "wipe and lift away" when path.kind == outer_perimeter {
  replace path {
    default
    retract
    move to (100 mm, 150 mm) travel
  }
}
)");
  // After each outer perimeter: a retraction (E pulled back, no XY), then the travel to
  // (100, 150), and the next extrusion starts with the unretraction.
  int seen = 0;
  for (size_t i = 0; i + 1 < g.moves.size(); ++i) {
    const auto& m = g.moves[i];
    if (!(m.has_xy && !m.has_e && m.x == 100 && m.y == 150)) continue;
    ++seen;
    REQUIRE(i > 0);
    const auto& before = g.moves[i - 1];
    CHECK(before.has_e);
    CHECK_FALSE(before.has_xy);
    CHECK(before.de < 0);
    // The next E move is the unretraction, before any extrusion.
    for (size_t k = i + 1; k < g.moves.size(); ++k) {
      if (!g.moves[k].has_e) continue;
      CHECK_FALSE(g.moves[k].has_xy);
      CHECK(g.moves[k].de > 0);
      break;
    }
    // The outer perimeter ends the layer (infill first): the layer change must not retract a
    // second time, and the filament pulled back is pushed forward exactly once.
    double net = 0;
    bool extrudes_after = false;
    for (size_t k = i - 1; k < g.moves.size() && !extrudes_after; ++k) {
      extrudes_after = g.moves[k].has_xy && g.moves[k].de > 0;
      if (!g.moves[k].has_xy) net += g.moves[k].de;
    }
    if (extrudes_after) CHECK(net == doctest::Approx(0).epsilon(1e-9));  // not after the last layer
  }
  CHECK(seen == 5);  // five layers
}

SCENARIO("rules: a 0.6 mm wall is one gap-fill bead of its plastic, and piece.width slows the narrow ones") {
  test::TempDir dir("rules-walls");
  // Two walls 2 mm tall, 10 mm apart: 0.6 mm and 0.25 mm thick (too thin for a loop of 0.45 mm
  // beads: each is one bead along its middle, as wide as the wall).
  geo::Mesh m = geo::box({20, 0.6, 2});
  geo::append(m, geo::translated(geo::box({20, 0.25, 2}), {0, 10, 0}));
  auto g = slice(dir, "walls", m, R"(
rule "narrow beads slow" when piece.width < 0.3 mm { speed = 15 mm/s }
)",
                 {{"min_layer_time", "0"}});
  CHECK(g.contains(";TYPE:Gap fill"));
  std::set<double> thick_feeds, thin_feeds;
  for (const auto& mv : g.moves) {
    if (!extrudes(mv)) continue;
    CHECK(mv.type == "Gap fill");  // no loop overlapping itself
    if (mv.layer == 0) continue;   // first layer: 20 mm/s for everything
    (mv.y < 100 ? thick_feeds : thin_feeds).insert(mv.f);
  }
  CHECK(thick_feeds == std::set<double>{1800});  // gap fill's default 30 mm/s
  CHECK(thin_feeds == std::set<double>{900});
  // Plastic: the walls' volume less their round ends (the beads stop half a width short of the
  // wall's ends and go on (1 − π/4)·w/2 beyond, so that their footprint matches the wall).
  const double filament_mm2 = std::numbers::pi * 1.75 * 1.75 / 4;
  const double model = (20 * 0.6 + 20 * 0.25) * 2;
  CHECK(g.filament() * filament_mm2 / model == doctest::Approx(1.0).epsilon(0.05));
}
