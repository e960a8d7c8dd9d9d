// examples/: every example run end to end as `make example` runs it (scripts/run-example.sh:
// generate the model, `rulec check -W error`, `rulec explain`, `tranche slice`), then one
// assertion per example on the G-code that shows the example's point.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <regex>
#include <set>
#include <sstream>

#include "tests/e2e/gcode_reader.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::test;
namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& p) { return read_file(p); }

std::vector<std::string> example_names() {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(source_dir() / "examples"))
    if (e.is_directory() && fs::exists(e.path() / "example.env")) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

struct Example {
  fs::path out;
  std::string log;
  bool skipped = false;
  Gcode gcode(const std::string& run) const { return read_gcode((out / (run + ".gcode")).string()); }
};

// Runs scripts/run-example.sh into a fresh folder; fails the test with the script's output when
// it fails. A build without the Python hook skips the fill-angle example.
Example run_example(const TempDir& dir, const std::string& name) {
  Example ex;
  ex.out = dir / name;
  fs::path log = dir / (name + ".log");
  std::string cmd = "bash '" + (source_dir() / "scripts" / "run-example.sh").string() + "' '" + binary_dir().string() +
                    "' '" + name + "' '" + ex.out.string() + "' >'" + log.string() + "' 2>&1";
  int rc = std::system(cmd.c_str());
  ex.log = read(log);
  if (rc != 0 && ex.log.find("unavailable") != std::string::npos && ex.log.find("fill-angle") != std::string::npos) {
    MESSAGE("skipped: this build has no Python fill-angle hook\n" << ex.log);
    ex.skipped = true;
    return ex;
  }
  REQUIRE_MESSAGE(rc == 0, "scripts/run-example.sh " << name << " failed:\n" << ex.log);
  CHECK_MESSAGE(ex.log.find("0 errors, 0 warnings") != std::string::npos, ex.log);
  CHECK_MESSAGE(ex.log.find("warning:") == std::string::npos, "the slice warned:\n" << ex.log);
  return ex;
}

bool extrudes(const Move& m) { return m.has_xy && m.de > 0; }
double length(const Move& m) { return std::hypot(m.x - m.x0, m.y - m.y0); }
double line_angle(const Move& m) {
  double a = std::atan2(m.y - m.y0, m.x - m.x0) * 180 / std::numbers::pi;
  return std::fmod(a + 360, 180);
}
double angle_diff(double a, double b) {
  double d = std::abs(std::fmod(a - b + 720, 180.0));
  return std::min(d, 180 - d);
}
std::vector<size_t> lines_starting(const Gcode& g, const std::string& prefix) {
  std::vector<size_t> out;
  for (size_t i = 0; i < g.lines.size(); ++i)
    if (g.lines[i].rfind(prefix, 0) == 0) out.push_back(i);
  return out;
}
int layer_of_line(const Gcode& g, size_t line) {
  int layer = -1;
  for (size_t i = 0; i <= line && i < g.lines.size(); ++i)
    if (g.lines[i].rfind(";LAYER:", 0) == 0) layer = std::stoi(g.lines[i].substr(7));
  return layer;
}
// The lines of layer `layer` (from its ;LAYER: line to the next).
std::vector<std::string> layer_lines(const Gcode& g, int layer) {
  std::vector<std::string> out;
  bool in = false;
  for (const auto& l : g.lines) {
    if (l.rfind(";LAYER:", 0) == 0) in = std::stoi(l.substr(7)) == layer;
    if (in) out.push_back(l);
  }
  return out;
}

}  // namespace

TEST_CASE("examples: at least eight, each with a README, one .rules file, a model and example.env") {
  auto names = example_names();
  CHECK(names.size() >= 8);
  for (const auto& n : names) {
    INFO(n);
    fs::path d = source_dir() / "examples" / n;
    CHECK(fs::exists(d / "README.md"));
    int rules = 0;
    for (const auto& e : fs::directory_iterator(d)) rules += e.path().extension() == ".rules";
    CHECK(rules == 1);
    std::string env = read(d / "example.env");
    std::smatch m;
    REQUIRE(std::regex_search(env, m, std::regex("MODEL=(\\S+)")));
    CHECK((fs::exists(d / "make_model.py") || fs::exists(d / std::string(m[1]))));
    // No third-party model files: models are generated, or hand-written SVG.
    for (const auto& e : fs::directory_iterator(d)) CHECK(e.path().extension() != ".stl");
    // Each example is run, and its point asserted, by a test case of this file.
    std::string self = read(source_dir() / "tests" / "examples" / "examples_test.cpp");
    CHECK_MESSAGE(self.find("run_example(dir, \"" + n + "\")") != std::string::npos,
                  "examples/" << n << " has no test case in tests/examples/examples_test.cpp");
  }
}

TEST_CASE("examples: the pictures a README shows are in its folder, PNG, under 150 KB") {
  int shown = 0;
  for (const auto& n : example_names()) {
    const fs::path d = source_dir() / "examples" / n;
    const std::string md = read(d / "README.md");
    const std::regex image(R"(!\[[^\]]*\]\(([^)]+)\))");
    for (auto it = std::sregex_iterator(md.begin(), md.end(), image); it != std::sregex_iterator(); ++it) {
      const fs::path pic = d / (*it)[1].str();
      INFO(pic.string());
      REQUIRE(fs::exists(pic));
      CHECK(pic.extension() == ".png");
      CHECK(fs::file_size(pic) < 150 * 1024);
      CHECK(read(pic).substr(0, 8) == "\x89PNG\r\n\x1a\n");
      ++shown;
    }
  }
  CHECK(shown >= 3);  // dome-lid's section and layers, infill-patterns' patterns
}

TEST_CASE("examples: together they cover every action kind, context level, other layers, hooks and tools") {
  std::string rules, envs;
  for (const auto& n : example_names()) {
    fs::path d = source_dir() / "examples" / n;
    for (const auto& e : fs::directory_iterator(d))
      if (e.path().extension() == ".rules") rules += read(e.path()) + "\n";
    envs += read(d / "example.env") + "\n";
  }
  auto has = [&](const std::string& re) { return std::regex_search(rules, std::regex(re)); };
  // Action kinds.
  CHECK(has(R"(\{\s*\w+\s*=)"));                        // modifier
  CHECK(has(R"(\b(before|after) (print|layer|island|cell|path)\b|\bon \w+\.(start|end)\b)"));  // executor
  CHECK(has(R"(\breplace path\b)"));
  CHECK(has(R"(\breplace island\b)"));
  // Context levels, as fields and as executor levels.
  for (const char* level : {"print", "layer", "island", "cell", "path"}) {
    INFO(level);
    CHECK(has(std::string(R"(\b)") + level + R"(\.\w+)"));
    CHECK(has(std::string(R"(\b(before|after) )") + level + R"(\b|\bon )" + level + R"(\.)"));
  }
  CHECK(has(R"(\bpiece\.\w+)"));
  CHECK(has(R"(\bpath\.pieces\b)"));
  // Other layers.
  CHECK(has(R"(\bbelow\.\w+)"));
  CHECK(has(R"(\babove\.\w+)"));
  CHECK(has(R"(\blayers\[)"));
  // Hooks and tools.
  CHECK(envs.find("--fill-angle-script") != std::string::npos);
  for (const char* mode : {"additive", "boolean", "subtractive"}) CHECK(envs.find(std::string("--overlap ") + mode) != std::string::npos);
  CHECK(envs.find("EXPLAIN=") != std::string::npos);
  CHECK(envs.find(".svg") != std::string::npos);
}

TEST_CASE("example temperature-tower: 5 °C cooler every 5 mm, waited for once per block") {
  TempDir dir("ex-tower");
  auto ex = run_example(dir, "temperature-tower");
  auto g = ex.gcode("temperature-tower");
  CHECK(g.contains("M109 S215 ; wait for the nozzle"));  // PLA's first layer, untouched
  auto blocks = lines_starting(g, "; block ");
  REQUIRE(blocks.size() == 4);
  for (size_t b = 0; b < blocks.size(); ++b) {
    int temp = 215 - 5 * static_cast<int>(b);
    CHECK(g.lines[blocks[b] + 1] == "M109 S" + std::to_string(temp) + " ; wait for the new temperature");
    int layer = layer_of_line(g, blocks[b]);
    CHECK(g.layer_z.at(layer - 1) == doctest::Approx(5.0 * (b + 1)));
  }
  // The temperature in force for every extrusion above the first layer.
  int temp = 0;
  size_t line = 0;
  for (const auto& m : g.moves) {
    for (; line < m.line; ++line) {
      const auto& l = g.lines[line];
      if (l.rfind("M104 S", 0) == 0 || l.rfind("M109 S", 0) == 0) temp = std::stoi(l.substr(6));
    }
    if (!extrudes(m) || m.layer < 1) continue;
    double z_bottom = g.layer_z.at(m.layer - 1);
    CHECK(temp == 220 - 5 * static_cast<int>(std::floor(z_bottom / 5 + 1e-9)));
  }
}

TEST_CASE("example small-pins: each pin printed by its own area") {
  TempDir dir("ex-pins");
  auto g = run_example(dir, "small-pins").gcode("small-pins");
  CHECK(g.contains("; island 0 of 1: 700.0 mm2"));
  CHECK(g.contains("of 5: 1.8 mm2"));
  // Bed coordinates: the 50 mm plate is centred at x = 100; the 1.5 mm pin is left of x = 81,
  // the 8 mm pin right of x = 108.
  int thin = 0, thick = 0;
  for (const auto& m : g.moves) {
    if (!extrudes(m) || m.layer < 6) continue;
    if (m.x < 81) {
      ++thin;
      CHECK(m.f == 600);  // 10 mm/s: the floor of small-island-cooling
      CHECK(m.fan == doctest::Approx(1.0));
      CHECK(m.type != "Perimeter");  // one wall only
    } else if (m.x > 108) {
      ++thick;
      CHECK(m.f >= 1500);
    }
  }
  CHECK(thin > 50);
  CHECK(thick > 200);
}

TEST_CASE("example overhangs: only the overhanging pieces of the outer wall slow down") {
  TempDir dir("ex-overhangs");
  auto g = run_example(dir, "overhangs").gcode("overhangs");
  // Walls at y 62-82 (20°), 90-110 (40°) and 118-138 (55°) in bed coordinates.
  std::map<int, std::set<double>> feeds;
  for (const auto& m : g.moves)
    if (extrudes(m) && m.layer >= 1 && m.type == "External perimeter") feeds[static_cast<int>((m.y - 62) / 28)].insert(m.f);
  CHECK(feeds[0] == std::set<double>{1500});
  CHECK(feeds[1] == std::set<double>{720, 1500});
  CHECK(feeds[2] == std::set<double>{480, 1500});
  CHECK(lines_starting(g, "; piece ").size() >= 5);
  CHECK(g.contains("63% over air"));
}

TEST_CASE("example comb-cells: the teeth are cells of their own, filled slower than the spine") {
  TempDir dir("ex-comb");
  auto g = run_example(dir, "comb-cells").gcode("comb-cells");
  // Five cells on every layer, solid on the bottom and top layers, sparse between.
  std::regex cell(R"(; cell [0-4] of 5: [0-9.]+ mm2, fill at 0 deg, solid ([01]))");
  std::map<std::string, int> cells;
  for (std::sregex_iterator it(g.text.begin(), g.text.end(), cell), end; it != end; ++it) ++cells[(*it)[1]];
  CHECK(cells["1"] == 5 * 6);   // 3 bottom and 3 top layers
  CHECK(cells["0"] == 5 * 14);  // the 14 layers between
  // The comb (y 0-22) is centred at y = 100: the spine is y 89-95. One tooth belongs to the
  // spine's cell (a line along x crosses the two once), the four others are cells of their own.
  std::set<double> spine;
  int slow = 0;
  for (const auto& m : g.moves) {
    if (!extrudes(m) || m.layer < 1 || (m.type != "Internal infill" && m.type != "Solid infill")) continue;
    if (length(m) > 2) CHECK(angle_diff(line_angle(m), 0) < 0.5);
    if (m.type != "Internal infill") continue;
    if (m.y < 93) spine.insert(m.f);
    if (m.f == 2400) {
      ++slow;
      CHECK(m.y > 93.5);
    }
  }
  CHECK(spine == std::set<double>{4800});
  CHECK(slow > 400);
}

TEST_CASE("example replacers: shrunk first layer, reversed odd walls, a wipe after even ones") {
  TempDir dir("ex-replacers");
  auto g = run_example(dir, "replacers").gcode("replacers");
  auto shrunk = lines_starting(g, "; first layer shrunk");
  REQUIRE(shrunk.size() == 1);
  CHECK(layer_of_line(g, shrunk[0]) == 0);
  // The outer wall's radius: 15 mm less 0.15 on layer 0, 15 mm above (a bead's half inside).
  auto radius = [&](int layer) {
    double r = 0;
    for (const auto& m : g.moves)
      if (extrudes(m) && m.layer == layer && m.type == "External perimeter") r = std::max(r, std::hypot(m.x - 100, m.y - 100));
    return r;
  };
  CHECK(radius(1) - radius(0) == doctest::Approx(0.15).epsilon(0.1));
  // Direction of each layer's outer wall: the sign of its swept area.
  std::map<int, double> swept;
  for (const auto& m : g.moves)
    if (extrudes(m) && m.type == "External perimeter")
      swept[m.layer] += (m.x0 - 100) * (m.y - 100) - (m.x - 100) * (m.y0 - 100);
  REQUIRE(swept.size() == 20);
  for (const auto& [layer, s] : swept) {
    INFO("layer " << layer);
    if (layer > 0) CHECK((s > 0) != (swept[layer - 1] > 0));
  }
  // A wipe after every even layer's wall: a retraction, then three moves without extrusion
  // along the loop.
  auto wipes = lines_starting(g, "; wipe");
  CHECK(wipes.size() == 10);
  for (size_t w : wipes) {
    const auto& r = g.lines[w + 1];
    CHECK(r.rfind("G1 E", 0) == 0);
    for (size_t k = 2; k <= 4; ++k) {
      const auto& l = g.lines[w + k];
      CHECK(l.rfind("G1 X", 0) == 0);
      CHECK(l.find(" E") == std::string::npos);
    }
  }
}

TEST_CASE("example python-fill-angle: infill along each bar, skins crossing on odd layers") {
  TempDir dir("ex-python");
  auto ex = run_example(dir, "python-fill-angle");
  if (ex.skipped) return;
  auto g = ex.gcode("python-fill-angle");
  // Bars at 0°, 60° and 120°: every long fill line runs along one of them, or across one on
  // odd solid layers; each layer holds the three directions.
  std::map<int, std::set<int>> directions;
  for (const auto& m : g.moves) {
    if (!extrudes(m) || length(m) < 4 || (m.type != "Internal infill" && m.type != "Solid infill")) continue;
    bool across = m.type == "Solid infill" && m.layer % 2 == 1;
    INFO("layer " << m.layer << " " << m.type << " at x " << m.x << ": " << line_angle(m));
    int found = -1;
    for (int bar : {0, 60, 120})
      if (angle_diff(line_angle(m), bar + (across ? 90 : 0)) < 1) found = bar;
    CHECK(found >= 0);
    directions[m.layer].insert(found);
  }
  CHECK(directions.size() >= 15);
  for (int layer = 3; layer < 17; ++layer) CHECK(directions[layer] == std::set<int>{0, 60, 120});
}

TEST_CASE("example svg-overlap: the three overlap modes make different islands") {
  TempDir dir("ex-svg");
  auto ex = run_example(dir, "svg-overlap");
  // "; N islands, A mm2 of material" on layer 0 of each.
  auto layer0 = [&](const std::string& run, int& islands, double& area) {
    std::smatch m;
    std::string text = ex.gcode(run).text;
    REQUIRE(std::regex_search(text, m, std::regex(R"(; ([0-9]+) islands, ([0-9.]+) mm2 of material)")));
    islands = std::stoi(m[1]);
    area = std::stod(m[2]);
  };
  int n = 0;
  double a = 0;
  // Square 900 mm², disc 452 mm², their lens 110 mm², white disc 154 mm², small square 36 mm².
  layer0("additive", n, a);
  CHECK(n == 1);
  CHECK(a == doctest::Approx(1242.3).epsilon(0.005));
  layer0("boolean", n, a);
  CHECK(n == 3);
  CHECK(a == doctest::Approx(1015.1).epsilon(0.005));
  layer0("subtractive", n, a);
  CHECK(n == 2);
  CHECK(a == doctest::Approx(1124.7).epsilon(0.005));
  auto sub = ex.gcode("subtractive");
  CHECK(sub.contains("mm2, 1 holes"));
  CHECK(sub.contains("; island 1: 36.0 mm2, 0 holes"));
}

TEST_CASE("example explain-profile: rulec explain names the deciding rules; the slice follows them") {
  TempDir dir("ex-explain");
  auto ex = run_example(dir, "explain-profile");
  std::string explain = read(ex.out / "explain.txt");
  CHECK(explain.find("speed = 15 mm/s\n  decided by rule \"first layer: slow, wide, hot\"") != std::string::npos);
  CHECK(explain.find("nozzle_temp = 240 °C\n  decided by rule \"first layer: slow, wide, hot\"") != std::string::npos);
  CHECK(explain.find("speed = 100 mm/s\n  decided by rule \"faster sparse infill\"") != std::string::npos);
  CHECK(explain.find("`layer.z_bottom >= 10 mm` is false (layer.z_bottom = 6 mm)") != std::string::npos);
  CHECK(explain.find("and, appended: rule \"announce\"") != std::string::npos);
  auto g = ex.gcode("explain-profile");
  CHECK(g.contains("M862.3 P \"MK3S\""));
  CHECK(g.contains("; profile: Prusa MK3S, PETG, first-layer feature, own rules"));
  CHECK(g.contains("M109 S240"));
  auto cooler = lines_starting(g, "M104 S235");
  REQUIRE(cooler.size() == 1);
  CHECK(g.layer_z.at(layer_of_line(g, cooler[0]) - 1) == doctest::Approx(10));
}

TEST_CASE("example other-layers: the step found from below, above and layers[0]") {
  TempDir dir("ex-other");
  auto g = run_example(dir, "other-layers").gcode("other-layers");
  auto step = lines_starting(g, "; step: the area drops from 1600 to 100 mm2 at z = 3.00 mm");
  REQUIRE(step.size() == 1);
  CHECK(layer_of_line(g, step[0]) == 15);
  CHECK(g.contains("; the first layer had 1600 mm2, 1 island"));
  std::map<int, std::set<double>> outer;
  for (const auto& m : g.moves)
    if (extrudes(m) && m.type == "External perimeter") outer[m.layer].insert(m.f);
  CHECK(outer[13] == std::set<double>{1500});
  CHECK(outer[14] == std::set<double>{1125});  // under the step: 75%
  for (int l = 15; l < 100; ++l)
    if (outer.count(l)) CHECK(*outer[l].rbegin() < 1500);  // small layers stretched to 10 s
}

TEST_CASE("example name-plate: a colour change where the letters begin, print-level settings") {
  TempDir dir("ex-plate");
  auto g = run_example(dir, "name-plate").gcode("name-plate");
  CHECK(g.contains("; name plate 54 x 15 x 3.0 mm"));
  auto change = lines_starting(g, "M600");
  REQUIRE(change.size() == 1);
  int layer = layer_of_line(g, change[0]);
  CHECK(g.layer_z.at(layer - 1) == doctest::Approx(2.0));
  // Two skirt loops: about twice the length of one loop around the plate.
  double skirt = 0;
  for (const auto& m : g.moves)
    if (extrudes(m) && m.type == "Skirt/Brim") skirt += length(m);
  CHECK(skirt > 2 * 2 * (54 + 15.2));
  CHECK(skirt < 2 * 2 * (54 + 15.2 + 16));
  auto first = layer_lines(g, 0);
  CHECK(std::find(first.begin(), first.end(), "M600 ; colour change") == first.end());
}

TEST_CASE("example supports: trees under the table's top, none under the low ledge, the interface slower") {
  TempDir dir("ex-supports");
  auto g = run_example(dir, "supports").gcode("supports");
  // The model is centred: x 80-120, y 90-110; the ledge round the front left leg: x 80-85.8, y 90-95.8.
  int support = 0, iface = 0, under_ledge = 0;
  double top = 0;
  for (const auto& m : g.moves) {
    if (!extrudes(m) || m.type.rfind("Support material", 0) != 0) continue;
    m.type == "Support material" ? ++support : ++iface;
    top = std::max(top, g.layer_z.at(m.layer));
    const double x = 0.5 * (m.x0 + m.x), y = 0.5 * (m.y0 + m.y);
    // Blocked: no contact with the ledge, so no interface under it (branches from the top may pass by).
    if (m.type == "Support material interface" && x > 80 && x < 85.8 && y > 90 && y < 95.8 && g.layer_z.at(m.layer) < 4)
      ++under_ledge;
    if (m.type == "Support material interface") CHECK(m.f <= 1800);
  }
  CHECK(support > 100);
  CHECK(iface > 20);
  CHECK(under_ledge == 0);
  CHECK(top == doctest::Approx(14.8));
}

TEST_CASE("example infill-patterns: a grid in the base, a gyroid in the column, loops in the pin") {
  TempDir dir("ex-infill-patterns");
  auto g = run_example(dir, "infill-patterns").gcode("infill-patterns");
  // The model is centred: the base x 75-125, y 85-115; the column x 83-99, y 92-108; the pin
  // x 111-117, y 97-103. Directions of the sparse infill's moves, in whole degrees [0, 180).
  auto directions = [&](int layer, double x0, double x1) {
    std::map<int, double> len;
    for (const auto& m : g.moves) {
      if (m.layer != layer || m.type != "Internal infill" || !(m.has_xy && m.de > 0)) continue;
      const double x = 0.5 * (m.x0 + m.x);
      if (x < x0 || x > x1) continue;
      const double l = std::hypot(m.x - m.x0, m.y - m.y0);
      const int a = static_cast<int>(std::lround(std::fmod(std::atan2(m.y - m.y0, m.x - m.x0) * 180 / std::numbers::pi + 360, 180))) % 180;
      len[a] += l;
    }
    return len;
  };
  auto share = [](const std::map<int, double>& len, std::initializer_list<int> angles) {
    double all = 0, in = 0;
    for (const auto& [a, l] : len) {
      all += l;
      for (int b : angles)
        if (std::abs(a - b) <= 1) in += l;
    }
    return all > 0 ? in / all : 0.0;
  };
  // Layer 15 (z 3 mm): the base's grid, both ways on one layer.
  auto base = directions(15, 75, 125);
  REQUIRE(!base.empty());
  CHECK(share(base, {45}) > 0.3);
  CHECK(share(base, {135}) > 0.3);
  // Layer 60 (z 12 mm): the column's gyroid, no single direction dominating.
  auto column = directions(60, 83, 99);
  REQUIRE(!column.empty());
  CHECK(share(column, {45, 135}) < 0.5);
  // Curves in many directions (a grid or zig-zag has 2; the gyroid's chords, about 9.5 a period
  // and branch, 20 here).
  CHECK(column.size() > 12);
  // Layer 45 (z 9 mm): the pin's concentric loops, along x and y.
  auto pin = directions(45, 111, 117);
  REQUIRE(!pin.empty());
  CHECK(share(pin, {0, 90}) > 0.6);
}

TEST_CASE("example dome-lid: thick layers on the base, thinner up the dome, seams in the inner corner, the base's top ironed") {
  TempDir dir("ex-dome-lid");
  auto g = run_example(dir, "dome-lid").gcode("dome-lid");
  REQUIRE(!g.layer_z.empty());
  CHECK(g.layer_z.rbegin()->second == doctest::Approx(17));
  CHECK(g.layer_z.size() < 75);  // 85 at 0.2 mm
  std::map<int, double> h;
  double z = 0;
  int base = 0, dome = 0, on_top = -1;
  for (const auto& [layer, top] : g.layer_z) {
    h[layer] = top - z;
    if (std::abs(top - 8) < 1e-6) on_top = layer;
    if (layer > 0 && top < 8 - 1e-6) base += h[layer] > 0.3 - 1e-6;
    if (top > 16.5 && top < 17 - 1e-6) dome += h[layer] < 0.2;
    z = top;
  }
  CHECK(on_top > 0);  // a layer ends on the base's top
  CHECK(base > 15);
  CHECK(dome >= 2);
  // The model is centred: the L spans x 85-115, y 85-115, its inner corner at (105, 105).
  std::map<int, std::pair<double, double>> starts;
  std::set<int> ironed;
  size_t last_wall = 0, first_iron = SIZE_MAX;
  for (const auto& m : g.moves) {
    if (!extrudes(m)) continue;
    if (m.type == "External perimeter" && !starts.count(m.layer)) starts[m.layer] = {m.x0, m.y0};
    if (m.type == "External perimeter" && m.layer == on_top) last_wall = std::max(last_wall, m.line);
    if (m.type == "Ironing") {
      ironed.insert(m.layer);
      first_iron = std::min(first_iron, m.line);
    }
  }
  CHECK(ironed == std::set<int>{on_top});
  CHECK(first_iron > last_wall);
  int corner = 0;
  for (const auto& [layer, p] : starts)
    if (g.layer_z.at(layer) < 8 - 1e-6) {
      CHECK(std::hypot(p.first - 105, p.second - 105) < 0.6);
      ++corner;
    }
  CHECK(corner > 15);
}
