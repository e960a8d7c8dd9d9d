// stdlib/printers and stdlib/materials: each profile sliced end to end, checked on what the
// firmware receives (start and end G-code, temperatures, fan, retraction, speeds).
#include <doctest/doctest.h>

#include <fstream>
#include <iterator>
#include <set>

#include "tests/stdlib/stdlib_helpers.h"

using namespace tranche;
using namespace tranche::test;

namespace {

// The retraction lengths (mm of filament pulled back before a travel) of the printed layers.
std::set<double> retractions(const Gcode& g) {
  std::set<double> out;
  for (const auto& m : g.moves)
    if (m.layer >= 0 && m.type != "Custom" && m.has_e && !m.has_xy && m.de < 0) out.insert(std::round(-m.de * 1000) / 1000);
  return out;
}

bool before_first_layer(const Gcode& g, const std::string& line_start) {
  for (const auto& l : g.lines) {
    if (l.rfind(";LAYER:0", 0) == 0) return false;
    if (l.rfind(line_start, 0) == 0) return true;
  }
  return false;
}

// Two separate parts: the travel between them leaves the material, so it retracts (travels
// inside one part are combed and retract only past retract_long_travel).
geo::Mesh two_parts() {
  geo::Mesh m = geo::box({20, 20, 2});
  geo::append(m, geo::translated(geo::box({20, 20, 2}), {30, 0, 0}));
  return m;
}

}  // namespace

TEST_CASE("printers: every printer slices, its start G-code heats to the first layer's temperatures") {
  TempDir dir("printers");
  auto box = two_parts();
  struct Case {
    const char* printer;
    std::vector<const char*> start;  // lines the start G-code must hold, before layer 0
    double bed_x;
    double retract;
  };
  const std::vector<Case> cases = {
      {"generic-marlin", {"M190 S60", "M109 S215", "G28"}, 200, 0.8},
      {"prusa-mk3s", {"M862.3 P \"MK3S\"", "M862.1 P0.4", "M190 S60", "M109 S215", "G80", "M900 K0", "G1 X100 E12.5"}, 250, 0.8},
      {"ender3", {"M190 S60", "M109 S215", "G28", "G1 X0.1 Y200 Z0.3 F1500 E15"}, 220, 5},
      {"klipper", {"PRINT_START BED=60 EXTRUDER=215"}, 235, 0.5},
      {"reprapfirmware", {"T0", "G10 P0 S215 R215", "M116", "M106 P0 S0"}, 250, 0.6},
  };
  for (const auto& c : cases) {
    INFO(c.printer);
    auto g = slice_with(dir, c.printer, box, Profile().printer(c.printer));
    for (const char* l : c.start) CHECK_MESSAGE(before_first_layer(g, l), l);
    // The start G-code heats itself: the slicer adds no heating of its own.
    CHECK_FALSE(g.contains("no temperature in the start G-code"));
    // Centred on the printer's bed.
    double min_x = 1e9, max_x = -1e9;
    for (const auto& m : g.moves)
      if (extrudes(m) && m.layer >= 0) min_x = std::min(min_x, m.x), max_x = std::max(max_x, m.x);
    CHECK((min_x + max_x) / 2 == doctest::Approx(c.bed_x / 2).epsilon(0.01));
    CHECK(retractions(g) == std::set<double>{c.retract});
    // An end G-code turns the heaters off.
    CHECK((g.contains("M104 S0") || g.contains("G10 P0 S0 R0") || g.contains("PRINT_END")));
  }
}

TEST_CASE("printers: Prusa MK3S prints with relative E; RepRapFirmware's fan is a fraction on P0") {
  TempDir dir("printers-dialects");
  auto box = geo::box({20, 20, 2});
  auto prusa = slice_with(dir, "prusa", box, Profile().printer("prusa-mk3s"));
  CHECK(prusa.relative_e);
  CHECK(prusa.contains("G1 Z32.0 F720"));  // 30 mm above the 2 mm print
  auto rrf = slice_with(dir, "rrf", box, Profile().printer("reprapfirmware"));
  CHECK(rrf.contains("M106 P0 S1"));
  for (const auto& l : rrf.lines) CHECK(l.rfind("M106 S", 0) != 0);
  // A temperature change between layers is M104 for the selected tool.
  CHECK(rrf.contains("M104 S210"));
}

TEST_CASE("materials: temperatures of the first layer and the next, fan and retraction") {
  TempDir dir("materials");
  auto box = geo::box({20, 20, 2});
  struct Case {
    const char* material;
    int first_nozzle, nozzle, first_bed, bed;
    double fan_layer1, fan_layer5;
  };
  const std::vector<Case> cases = {
      {"pla", 215, 210, 60, 60, 1.0, 1.0},
      {"petg", 235, 240, 85, 80, 0.0, 0.5},
      {"abs", 255, 250, 105, 100, 0.0, 0.15},
      {"tpu", 235, 230, 50, 50, 0.5, 0.5},
  };
  for (const auto& c : cases) {
    INFO(c.material);
    auto g = slice_with(dir, c.material, box, Profile().material(c.material));
    CHECK(g.contains("M109 S" + std::to_string(c.first_nozzle)));
    CHECK(g.contains("M190 S" + std::to_string(c.first_bed)));
    if (c.nozzle != c.first_nozzle) CHECK(g.contains("M104 S" + std::to_string(c.nozzle)));
    if (c.bed != c.first_bed) CHECK(g.contains("M140 S" + std::to_string(c.bed)));
    std::map<int, double> fan;
    for (const auto& m : g.moves)
      if (extrudes(m)) fan[m.layer] = m.fan;
    CHECK(fan[0] == 0);
    CHECK(fan[1] == doctest::Approx(c.fan_layer1).epsilon(0.02));
    CHECK(fan[5] == doctest::Approx(c.fan_layer5).epsilon(0.02));
  }
}

TEST_CASE("materials: PETG retracts 20% more with a z hop; TPU is slow and retracts little, even on a Bowden printer") {
  TempDir dir("materials-retract");
  auto box = two_parts();
  auto petg = slice_with(dir, "petg", box, Profile().material("petg"));
  CHECK(retractions(petg) == std::set<double>{0.96});
  CHECK(petg.contains("G1 Z0.4"));  // 0.2 mm first layer + 0.2 mm hop
  auto tpu = slice_with(dir, "tpu", box, Profile().printer("ender3").material("tpu"));
  CHECK(retractions(tpu) == std::set<double>{1.0});
  for (const auto& m : tpu.moves)
    if (extrudes(m) && m.layer >= 0) CHECK(m.f <= 1200);
}

TEST_CASE("stdlib: every file starts with a comment saying what it is, and every one is sliced by these tests") {
  std::string self;
  for (const char* f : {"features_test.cpp", "profiles_test.cpp"}) {
    std::ifstream in(source_dir() / "tests" / "stdlib" / f);
    self += std::string(std::istreambuf_iterator<char>(in), {});
  }
  int files = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(stdlib_path())) {
    if (e.path().extension() != ".rules") continue;
    ++files;
    std::ifstream in(e.path());
    std::string first;
    std::getline(in, first);
    INFO(e.path().string());
    CHECK(first.rfind("# ", 0) == 0);
    std::string kind = e.path().parent_path().filename().string(), name = e.path().stem().string();
    if (kind == "features") CHECK(self.find(".feature(\"" + name + "\")") != std::string::npos);
    if (kind == "printers") CHECK(self.find("{\"" + name + "\", {") != std::string::npos);
    if (kind == "materials") CHECK(self.find("{\"" + name + "\", ") != std::string::npos);
  }
  CHECK(files >= 22);
}
