// stdlib/features: each feature file, applied with --rules over the default profile, sliced from
// a small generated mesh and checked on the G-code a printer would receive.
#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <set>

#include "tests/stdlib/stdlib_helpers.h"

using namespace tranche;
using namespace tranche::test;

TEST_CASE("features/first-layer: layer 0 slow, wider and hotter; the rest as the profile says") {
  TempDir dir("feat-first");
  auto box = geo::box({20, 20, 2});
  auto plain = slice_with(dir, "plain", box, {});
  auto g = slice_with(dir, "first", box, Profile().feature("first-layer"));
  // PLA: 215 °C and 60 °C on the first layer, +5 each.
  CHECK(g.contains("M109 S220"));
  CHECK(g.contains("M190 S65"));
  CHECK(plain.contains("M109 S215"));
  std::set<double> feeds0, feeds2;
  for (const auto& m : g.moves)
    if (extrudes(m)) (m.layer == 0 ? feeds0 : feeds2).insert(m.f);
  CHECK(feeds0 == std::set<double>{900});  // 15 mm/s
  CHECK(feeds2.size() > 1);
  // 0.54 mm beads instead of 0.45 mm: 20% more plastic per mm on layer 0, as before above it.
  double wide = e_per_mm(g, "External perimeter", 0) / e_per_mm(plain, "External perimeter", 0);
  CHECK(wide == doctest::Approx(0.54 / 0.45).epsilon(0.03));
  CHECK(e_per_mm(g, "External perimeter", 3) == doctest::Approx(e_per_mm(plain, "External perimeter", 3)));
}

TEST_CASE("features/bridges: bridge paths thin and slow, full fan over a gap even for ABS") {
  TempDir dir("feat-bridges");
  // Two 4 mm pillars 12 mm apart carrying a 1 mm slab: the slab's first layer is 40% supported.
  geo::Mesh m = geo::box({4, 20, 3});
  geo::append(m, geo::box({4, 20, 3}, {16, 0, 0}));
  geo::append(m, geo::box({20, 20, 1}, {0, 0, 3}));
  auto abs = Profile().material("abs");
  auto plain = slice_with(dir, "plain", m, abs);
  auto g = slice_with(dir, "bridges", m, abs.feature("bridges"));
  int bridge_moves = 0;
  for (const auto& mv : g.moves) {
    if (!extrudes(mv) || mv.type != "Bridge infill") continue;
    ++bridge_moves;
    CHECK(mv.f == 1200);  // 20 mm/s
    CHECK(mv.fan == doctest::Approx(1.0));
  }
  CHECK(bridge_moves > 5);
  CHECK(e_per_mm(g, "Bridge infill") == doctest::Approx(0.8 * e_per_mm(plain, "Bridge infill")).epsilon(0.02));
  // Elsewhere ABS keeps its 15% fan.
  for (const auto& mv : g.moves)
    if (extrudes(mv) && mv.layer >= 3 && mv.layer < 14) CHECK(mv.fan == doctest::Approx(0.15).epsilon(0.02));
}

TEST_CASE("features/bridges: on a mostly supported island only the bridge paths change") {
  TempDir dir("feat-bridges-path");
  // 7 mm pillars, 6 mm apart: the slab's first layer is 70% supported; its middle is a bridge.
  geo::Mesh m = geo::box({7, 20, 3});
  geo::append(m, geo::box({7, 20, 3}, {13, 0, 0}));
  geo::append(m, geo::box({20, 20, 1}, {0, 0, 3}));
  auto g = slice_with(dir, "bridges", m, Profile().material("abs").feature("bridges").set("min_layer_time", "0"));
  int bridge = 0, walls = 0;
  for (const auto& mv : g.moves) {
    if (!extrudes(mv) || mv.layer != 15) continue;
    if (mv.type == "Bridge infill") {
      ++bridge;
      CHECK(mv.f == 1200);
      CHECK(mv.fan == doctest::Approx(1.0));
    } else if (mv.type == "External perimeter") {
      ++walls;
      CHECK(mv.f == 25 * 60);
      CHECK(mv.fan == doctest::Approx(0.15).epsilon(0.02));
    }
  }
  CHECK(bridge > 3);
  CHECK(walls > 3);
}

TEST_CASE("features/small-island-cooling: a 2 x 2 mm pin is slower and fully cooled, the big part is not") {
  TempDir dir("feat-small");
  geo::Mesh m = geo::box({20, 20, 3});
  geo::append(m, geo::box({2, 2, 3}, {30, 0, 0}));
  auto g = slice_with(dir, "small", m, Profile().material("abs").feature("small-island-cooling").set("min_layer_time", "0"));
  // The scene (0..32 mm) is centred on the 200 mm bed: the pin is right of x = 110.
  int pin = 0, big = 0;
  for (const auto& mv : g.moves) {
    if (!extrudes(mv) || mv.layer < 3) continue;
    if (mv.x > 110) {
      ++pin;
      CHECK(mv.f <= 0.2 * 80 * 60 + 1);  // 4 mm² of 20 mm²: a fifth of the speed, at least 10 mm/s
      CHECK(mv.f >= 600);
      CHECK(mv.fan == doctest::Approx(1.0));
    } else {
      ++big;
      CHECK(mv.f >= 25 * 60);
      CHECK(mv.fan == doctest::Approx(0.15).epsilon(0.02));
    }
  }
  CHECK(pin > 20);
  CHECK(big > 100);
}

namespace {

// For each extruding path, the pressure-advance factor in force must be the one for its type.
void check_pressure_advance(const Gcode& g, const std::string& command) {
  const std::map<std::string, double> want = {{"External perimeter", 0.045}, {"Perimeter", 0.040},
                                              {"Solid infill", 0.035},       {"Top solid infill", 0.035},
                                              {"Bridge infill", 0},          {"Internal infill", 0.030}};
  double k = -1;
  size_t line = 0;
  std::set<std::string> types;
  for (const auto& m : g.moves) {
    for (; line < m.line; ++line)  // the last PA command before this move
      if (g.lines[line].rfind(command, 0) == 0) k = std::stod(g.lines[line].substr(command.size()));
    if (!extrudes(m) || m.layer < 0) continue;
    auto it = want.find(m.type);
    if (it == want.end()) continue;
    INFO("line " << m.line << " " << m.type);
    CHECK(k == doctest::Approx(it->second));
    types.insert(m.type);
  }
  CHECK(types.size() >= 4);
}

}  // namespace

TEST_CASE("features/pressure-advance: the factor of each path kind, in the firmware's dialect") {
  TempDir dir("feat-pa");
  auto plate = geo::plate_with_holes(20, 20, 2, 2, 2, 2, 24);
  auto marlin = slice_with(dir, "marlin", plate, Profile().feature("pressure-advance"));
  check_pressure_advance(marlin, "M900 K");
  CHECK_FALSE(marlin.contains("SET_PRESSURE_ADVANCE"));
  auto klipper = slice_with(dir, "klipper", plate, Profile().printer("klipper").feature("pressure-advance"));
  check_pressure_advance(klipper, "SET_PRESSURE_ADVANCE ADVANCE=");
  CHECK_FALSE(klipper.contains("M900"));
  auto rrf = slice_with(dir, "rrf", plate, Profile().printer("reprapfirmware").feature("pressure-advance"));
  check_pressure_advance(rrf, "M572 D0 S");
  CHECK_FALSE(rrf.contains("M900"));
  // Prusa's start turns linear advance off; the feature then sets it before every path.
  auto prusa = slice_with(dir, "prusa", plate, Profile().printer("prusa-mk3s").feature("pressure-advance"));
  check_pressure_advance(prusa, "M900 K");
}

TEST_CASE("features/infill-angle-list: 45, 135, 0, 90 degrees, repeating every four layers") {
  TempDir dir("feat-list");
  auto g = slice_with(dir, "list", geo::box({30, 30, 4}),
                      Profile().feature("infill-angle-list").set("top_layers", "0").set("bottom_layers", "0"));
  auto angles = infill_angles(g);
  REQUIRE(angles.size() >= 15);
  const double list[] = {45, 135, 0, 90};
  for (const auto& [layer, a] : angles) {
    INFO("layer " << layer << ": " << a);
    CHECK(angle_diff(a, list[layer % 4]) < 0.5);
  }
}

TEST_CASE("features/infill-angle-increment: 15 degrees more every layer") {
  TempDir dir("feat-inc");
  auto g = slice_with(dir, "inc", geo::box({30, 30, 4}),
                      Profile().feature("infill-angle-increment").set("top_layers", "0").set("bottom_layers", "0"));
  auto angles = infill_angles(g);
  REQUIRE(angles.size() >= 15);
  for (const auto& [layer, a] : angles) {
    INFO("layer " << layer << ": " << a);
    CHECK(angle_diff(a, 45 + 15.0 * layer) < 0.5);
  }
}

TEST_CASE("features/infill-rotation-by-height: 10 degrees per mm of z, whatever the layer height") {
  TempDir dir("feat-height");
  for (const char* h : {"0.2", "0.1"}) {
    auto g = slice_with(dir, std::string("rot") + h, geo::box({30, 30, 3}),
                        Profile().feature("infill-rotation-by-height").set("top_layers", "0").set("bottom_layers", "0").set("layer_height", h));
    auto angles = infill_angles(g);
    REQUIRE(angles.size() >= 14);
    for (const auto& [layer, a] : angles) {
      double z_bottom = layer == 0 ? 0 : g.layer_z.at(layer - 1);
      INFO("layer height " << h << ", layer " << layer << " (z_bottom " << z_bottom << "): " << a);
      CHECK(angle_diff(a, 45 + 10 * z_bottom) < 0.5);
    }
  }
}

TEST_CASE("features/colour-change: M600 once, at the start of layer 10; PAUSE on Klipper") {
  TempDir dir("feat-colour");
  auto box = geo::box({10, 10, 4});
  auto g = slice_with(dir, "marlin", box, Profile().feature("colour-change"));
  auto at = lines_starting(g, "M600");
  REQUIRE(at.size() == 1);
  CHECK(layer_of_line(g, at[0]) == 10);
  // Before any extrusion of layer 10.
  for (const auto& m : g.moves)
    if (m.layer == 10 && extrudes(m)) CHECK(m.line > at[0]);
  auto k = slice_with(dir, "klipper", box, Profile().printer("klipper").feature("colour-change"));
  CHECK(count_lines(k, "M600") == 0);
  auto pause = lines_starting(k, "PAUSE");
  REQUIRE(pause.size() == 1);
  CHECK(layer_of_line(k, pause[0]) == 10);
  // The layer is a param: --set moves the change without editing the file.
  auto moved = slice_with(dir, "moved", box, Profile().feature("colour-change").set("colour_change_layer", "14"));
  auto at14 = lines_starting(moved, "M600");
  REQUIRE(at14.size() == 1);
  CHECK(layer_of_line(moved, at14[0]) == 14);
}

TEST_CASE("features/pause-at-height: one pause, before the first layer above 5 mm, in each dialect") {
  TempDir dir("feat-pause");
  auto box = geo::box({10, 10, 8});
  struct Case {
    const char* printer;
    const char* command;
  };
  for (Case c : {Case{"generic-marlin", "M0 "}, Case{"klipper", "PAUSE"}, Case{"reprapfirmware", "M226"}}) {
    INFO(c.printer);
    for (const char* h : {"0.2", "0.15"}) {
      auto g = slice_with(dir, std::string(c.printer) + h, box,
                          Profile().printer(c.printer).feature("pause-at-height").set("layer_height", h));
      auto at = lines_starting(g, c.command);
      REQUIRE(at.size() == 1);
      int layer = layer_of_line(g, at[0]);
      CHECK(g.layer_z.at(layer) > 5);
      CHECK(g.layer_z.at(layer - 1) <= 5 + 1e-6);
    }
  }
  // The height is a param: `--set pause_height=3` (a plain number in the param's unit, mm).
  auto g = slice_with(dir, "at3", box, Profile().feature("pause-at-height").set("pause_height", "3"));
  auto at = lines_starting(g, "M0 ");
  REQUIRE(at.size() == 1);
  int layer = layer_of_line(g, at[0]);
  CHECK(g.layer_z.at(layer) > 3);
  CHECK(g.layer_z.at(layer - 1) <= 3 + 1e-6);
}

TEST_CASE("features/height-range: 0.1 mm layers and four perimeters between 2 and 4 mm only") {
  TempDir dir("feat-range");
  auto g = slice_with(dir, "range", geo::box({20, 20, 6}), Profile().feature("height-range"));
  REQUIRE(g.layer_z.size() > 30);
  std::map<int, double> inner;  // layer -> length of inner perimeters
  for (const auto& m : g.moves)
    if (extrudes(m) && m.type == "Perimeter") inner[m.layer] += length(m);
  int fine = 0;
  for (const auto& [layer, z] : g.layer_z) {
    if (layer == 0) continue;
    double z_bottom = g.layer_z.at(layer - 1), h = z - z_bottom;
    bool in_range = z_bottom >= 2 - 1e-6 && z_bottom < 4 - 1e-6;
    INFO("layer " << layer << " from z " << z_bottom);
    CHECK(h == doctest::Approx(in_range ? 0.1 : 0.2).epsilon(0.01));
    fine += in_range;
    // Two walls give one inner loop, four give three.
    if (in_range) CHECK(inner[layer] > 2.5 * inner[1]);
    else CHECK(inner[layer] < 1.5 * inner[1]);
  }
  CHECK(fine == 20);
}

TEST_CASE("features/ironing: top surfaces gone over again after the walls, typed Ironing, at 15% of a layer") {
  TempDir dir("feat-iron");
  auto box = geo::box({20, 20, 2});
  auto plain = slice_with(dir, "plain", box, {});
  auto g = slice_with(dir, "iron", box, Profile().feature("ironing"));
  // Nothing of the plain print is lost: the same top paths, and ironing only on the last layer
  // (the box's only top surface), after its walls and its top fill.
  CHECK(e_per_mm(g, "Top solid infill") == doctest::Approx(e_per_mm(plain, "Top solid infill")));
  const int last = g.layer_z.rbegin()->first;
  double e_iron = 0, len_iron = 0;
  size_t first_iron = g.lines.size(), last_other = 0;
  for (const auto& m : g.moves) {
    if (!extrudes(m)) continue;
    if (m.type != "Ironing") {
      if (m.layer == last) last_other = std::max(last_other, m.line);
      continue;
    }
    CHECK(m.layer == last);
    CHECK(m.f == 900);  // 15 mm/s
    first_iron = std::min(first_iron, m.line);
    e_iron += m.de;
    len_iron += length(m);
  }
  CHECK(first_iron > last_other);  // after the walls and the top
  // The top's area (the fill inside the walls) gone over at a 0.1 mm spacing: about 18 × 18 mm.
  CHECK(len_iron > 0.7 * 18 * 18 / 0.1);
  CHECK(len_iron < 1.1 * 19.5 * 19.5 / 0.1);
  // 15% of a 0.2 mm layer over a 0.1 mm line spacing, per mm of line.
  const double filament_area = 3.14159265 * 1.75 * 1.75 / 4;
  CHECK(e_iron / len_iron == doctest::Approx(0.15 * 0.2 * 0.1 / filament_area).epsilon(0.01));
  // Crossing the top's lines.
  double top_angle = -1, iron_angle = -1;
  for (const auto& m : g.moves)
    if (extrudes(m) && m.layer == last && length(m) > 5) {
      if (m.type == "Top solid infill" && top_angle < 0) top_angle = line_angle(m);
      if (m.type == "Ironing" && iron_angle < 0) iron_angle = line_angle(m);
    }
  CHECK(angle_diff(top_angle, iron_angle) == doctest::Approx(90).epsilon(0.01));
}

TEST_CASE("features/ironing: the topmost surface only, or the islands a rule picks") {
  TempDir dir("feat-iron-top");
  // A step: a 2 mm slab with a 4 mm tower on it, so tops on layers 9 and 29.
  geo::Mesh m = geo::box({30, 20, 2});
  geo::append(m, geo::box({10, 10, 4}, {0, 0, 2}));
  auto types_by_layer = [](const Gcode& g) {
    std::set<int> layers;
    for (const auto& mv : g.moves)
      if (extrudes(mv) && mv.type == "Ironing") layers.insert(mv.layer);
    return layers;
  };
  auto all = types_by_layer(slice_with(dir, "all", m, Profile().feature("ironing")));
  CHECK(all.count(9));
  CHECK(all.count(29));
  auto top = types_by_layer(slice_with(dir, "top", m, Profile().feature("ironing").set("iron_topmost_only", "true")));
  CHECK(top == std::set<int>{29});
  // A rule on the island stage alone: the slab's top, by its area.
  auto own = types_by_layer(slice_with(dir, "own", m, Profile().set("ironing", "island.area > 200 mm2")));
  CHECK(own == std::set<int>{9});
}

TEST_CASE("features/adaptive-domes: thick layers on the walls, thin ones at the top, shells of 0.6 mm") {
  TempDir dir("feat-domes");
  geo::Mesh ball = geo::sphere(10, 64, 48);
  auto plain = slice_with(dir, "plain", ball, {});
  auto g = slice_with(dir, "dome", ball, Profile().feature("adaptive-domes"));
  REQUIRE(plain.layer_z.size() == 100);
  CHECK(g.layer_z.size() < 90);
  CHECK(g.layer_z.rbegin()->second == doctest::Approx(20));
  std::map<int, double> h;
  double z = 0, thinnest_top = 1, thickest = 0;
  for (const auto& [layer, top] : g.layer_z) {
    h[layer] = top - z;
    if (layer > 0 && top < 19.99) {
      CHECK(h[layer] >= 0.07 - 1e-6);
      CHECK(h[layer] <= 0.3 + 1e-6);
      thickest = std::max(thickest, h[layer]);
      if (top > 19) thinnest_top = std::min(thinnest_top, h[layer]);
    }
    z = top;
  }
  CHECK(thickest == doctest::Approx(0.3));
  CHECK(thinnest_top < 0.2);
  // The top 0.6 mm is solid: no sparse infill in the layers whose top is within it.
  std::set<int> sparse;
  for (const auto& m : g.moves)
    if (extrudes(m) && m.type == "Internal infill") sparse.insert(m.layer);
  int solid_top = 0;
  for (const auto& [layer, top] : g.layer_z)
    if (top > 20 - 0.6 + 1e-6) {
      CHECK_FALSE(sparse.count(layer));
      ++solid_top;
    }
  CHECK(solid_top >= 3);  // the 0.6 mm of thin layers
  // A later layer_height rule still decides its layers.
  auto over = slice_with(dir, "over", ball, Profile().feature("adaptive-domes").set("layer_height", "0.25"));
  for (const auto& [layer, top] : over.layer_z)
    if (layer > 0 && top < 19.9) CHECK(top - over.layer_z.at(layer - 1) == doctest::Approx(0.25));
}

TEST_CASE("features/fan-by-layer-time: full fan on short layers, less on long ones, never under 30%") {
  TempDir dir("feat-fan");
  // A wide base (long layers) under a thin tower (short layers).
  geo::Mesh m = geo::box({60, 60, 2});
  geo::append(m, geo::box({6, 6, 3}, {27, 27, 2}));
  auto g = slice_with(dir, "fan", m, Profile().feature("fan-by-layer-time").set("skirt_loops", "0").set("min_layer_time", "0"));
  std::map<int, std::set<double>> fans;
  for (const auto& mv : g.moves)
    if (extrudes(mv)) fans[mv.layer].insert(std::round(mv.fan * 100) / 100);
  REQUIRE(fans.size() > 20);
  CHECK(fans[0] == std::set<double>{0});
  for (const auto& [layer, f] : fans) {
    if (layer == 0) continue;
    INFO("layer " << layer);
    REQUIRE(f.size() == 1);
    double fan = *f.begin();
    CHECK(fan >= 0.3 - 1e-9);
    if (layer >= 12) CHECK(fan == doctest::Approx(1.0));  // the tower: a few seconds a layer
    if (layer >= 1 && layer < 9) CHECK(fan < 0.9);        // the base: 60 x 60 mm a layer
  }
}

namespace {
// A 4 mm stem under a 20 mm cap whose bottom is at `cap_z`.
geo::Mesh mushroom_at(double cap_z) {
  geo::Mesh m = geo::box({4, 4, cap_z}, {8, 8, 0});
  geo::append(m, geo::box({20, 20, 2}, {0, 0, cap_z}));
  return m;
}
int support_moves(const Gcode& g, const std::string& type = "Support material") {
  int n = 0;
  for (const auto& m : g.moves) n += extrudes(m) && m.type == type;
  return n;
}
}  // namespace

TEST_CASE("features/support-blockers-by-height: support above support_from, none below") {
  TempDir dir("feat-support-block");
  auto high = slice_with(dir, "high", mushroom_at(8), Profile().feature("support-blockers-by-height"));
  CHECK(support_moves(high) > 50);
  auto low = slice_with(dir, "low", mushroom_at(4), Profile().feature("support-blockers-by-height"));
  CHECK(support_moves(low) == 0);
  CHECK(support_moves(low, "Support material interface") == 0);
  auto moved = slice_with(dir, "moved", mushroom_at(8),
                          Profile().feature("support-blockers-by-height").set("support_from", "10"));
  CHECK(support_moves(moved) == 0);
}

TEST_CASE("features/support-touching-near-bed: a cap one layer above the bed stands on a pad; higher caps keep their gap") {
  TempDir dir("feat-support-near-bed");
  // The cap's underside is 0.2 mm above the bed: no support with a 0.2 mm gap fits under it.
  auto plain = slice_with(dir, "plain", mushroom_at(0.2), Profile().set("support", "normal"));
  CHECK(support_moves(plain) + support_moves(plain, "Support material interface") == 0);
  auto touch = slice_with(dir, "touch", mushroom_at(0.2), Profile().feature("support-touching-near-bed"));
  // The pad: layer 0 under the cap (its stem is at 8..12 mm; the cap spans 0..20 mm), nothing above.
  int pad = 0;
  for (const auto& m : touch.moves) {
    if (!extrudes(m) || m.type.find("Support material") != 0) continue;
    CHECK(m.layer == 0);
    ++pad;
  }
  CHECK(pad > 20);
  // A cap 0.4 mm up: with the profile's 0.2 mm gap, support fits under it (one layer, its gap
  // kept), and the feature changes nothing.
  auto support_layers = [](const Gcode& g) {
    std::set<int> out;
    for (const auto& m : g.moves)
      if (extrudes(m) && m.type.find("Support material") == 0) out.insert(m.layer);
    return out;
  };
  auto high = slice_with(dir, "high", mushroom_at(0.4), Profile().feature("support-touching-near-bed"));
  auto high_plain = slice_with(dir, "high-plain", mushroom_at(0.4), Profile().set("support", "normal"));
  CHECK(support_layers(high) == std::set<int>{0});
  CHECK(support_layers(high_plain) == std::set<int>{0});
  // The user's own gap of 0.4 mm (a rule before the feature): no support with that gap fits under
  // the same cap, so the feature's pad touches it, two layers high.
  const auto gap_rule = dir / "gap.rules";
  {
    std::ofstream f(gap_rule);
    f << "rule \"wider gap\" { support_z_gap = 0.4 mm }\n";
  }
  auto wide = Profile().rules(gap_rule.string());
  CHECK(support_layers(slice_with(dir, "wide-plain", mushroom_at(0.4), wide.set("support", "normal"))).empty());
  CHECK(support_layers(slice_with(dir, "wide", mushroom_at(0.4), wide.feature("support-touching-near-bed"))) ==
        std::set<int>{0, 1});
}

TEST_CASE("features/support-for-overhangs-only: sparse support at its own speed, one interface layer") {
  TempDir dir("feat-support-light");
  auto g = slice_with(dir, "light", mushroom_at(8),
                      Profile().feature("support-for-overhangs-only").set("min_layer_time", "0"));
  std::set<int> iface_layers;
  for (const auto& m : g.moves) {
    if (!extrudes(m)) continue;
    if (m.type == "Support material" && m.layer > 0) CHECK(m.f == 45 * 60);
    if (m.type == "Support material interface") iface_layers.insert(m.layer);
  }
  CHECK(support_moves(g) > 30);
  CHECK(iface_layers.size() == 1);
}

TEST_CASE("features/gyroid-for-strength: gyroid at 25% on big islands, the zig-zag on small ones") {
  TempDir dir("feat-gyroid");
  // A 20 mm square block (400 mm²) beside a 6 mm square pin (36 mm²), both 10 mm tall.
  geo::Mesh m = geo::box({20, 20, 10});
  geo::append(m, geo::box({6, 6, 10}, {30, 0, 0}));
  auto plain = slice_with(dir, "plain", m, Profile());
  auto gyroid = slice_with(dir, "gyroid", m, Profile().feature("gyroid-for-strength"));
  auto plain_25 = slice_with(dir, "plain25", m, Profile().set("infill_density", "25%"));
  // Infill of one middle layer, split by island: the pin is the part with x beyond the block.
  auto infill = [](const Gcode& g, bool pin) {
    std::vector<std::pair<double, double>> pts;
    double fil = 0;
    for (const auto& mv : g.moves)
      if (extrudes(mv) && mv.type == "Internal infill" && mv.layer == 25) {
        // The scene (0..36 mm) is centred on the 200 mm bed: the block at x 82..102, the pin 112..118.
        if (pin != (mv.x > 107)) continue;
        pts.push_back({mv.x, mv.y});
        fil += mv.de;
      }
    return std::make_pair(pts, fil);
  };
  const auto big_plain = infill(plain, false), big_gyroid = infill(gyroid, false);
  REQUIRE(!big_plain.first.empty());
  REQUIRE(!big_gyroid.first.empty());
  CHECK(big_plain.first != big_gyroid.first);
  // Gyroid lines are curves: many more points than the zig-zag's straight lines.
  CHECK(big_gyroid.first.size() > 3 * big_plain.first.size());
  // 25% instead of 20%: more plastic, about as much as a 25% zig-zag.
  const double big_25 = infill(plain_25, false).second;
  CHECK(big_gyroid.second > big_plain.second * 1.1);
  CHECK(big_gyroid.second == doctest::Approx(big_25).epsilon(0.2));
  // The pin keeps its 20% zig-zag.
  CHECK(infill(gyroid, true).first == infill(plain, true).first);
  // A smaller threshold takes the pin too.
  auto both = slice_with(dir, "both", m, Profile().feature("gyroid-for-strength").set("gyroid_min_area", "20"));
  CHECK(infill(both, true).first != infill(plain, true).first);
}
