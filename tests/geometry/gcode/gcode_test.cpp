#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "geometry/gcode/layer_text.h"
#include "geometry/gcode/numbers.h"
#include "geometry/gcode/writer.h"
#include "tests/support/print_fixture.h"

using namespace tranche;
using namespace tranche::gcode;
namespace fs = std::filesystem;

namespace {
std::string fixed(int64_t v, int d) {
  std::string s;
  append_fixed(s, v, d);
  return s;
}
std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
}  // namespace

TEST_CASE("numbers: minimal fixed-point words") {
  CHECK(fixed(12500, 3) == "12.5");
  CHECK(fixed(12000, 3) == "12");
  CHECK(fixed(-50, 3) == "-0.05");
  CHECK(fixed(1234, 5) == "0.01234");
  CHECK(fixed(0, 5) == "0");
  CHECK(fixed(-80000, 5) == "-0.8");
}

TEST_CASE("fan commands per flavour") {
  CHECK(fan_command(schema::Flavor::Marlin, 1.0) == "M106 S255");
  CHECK(fan_command(schema::Flavor::Marlin, 0.0) == "M107");
  CHECK(fan_command(schema::Flavor::Klipper, 0.5) == "M106 S128");
  CHECK(fan_command(schema::Flavor::RepRapFirmware, 0.5) == "M106 P0 S0.5");
  CHECK(fan_command(schema::Flavor::RepRapFirmware, 0.0) == "M106 P0 S0");
}

// A file the tests read locally but git ignores is missing from every clean clone (CI broke so,
// on stdlib/gcode/*.gcode and a `*.gcode` ignore pattern).
TEST_CASE("stdlib: no shipped file is ignored by git") {
  fs::path src = test::source_dir();
  if (!fs::exists(src / ".git") || std::system("git --version >/dev/null 2>&1") != 0) return;
  for (const auto& e : fs::recursive_directory_iterator(src / "stdlib")) {
    if (!e.is_regular_file()) continue;
    std::string cmd = "git -C '" + src.string() + "' check-ignore -q '" + e.path().string() + "'";
    INFO(e.path().string());
    CHECK(std::system(cmd.c_str()) != 0);
  }
}

TEST_CASE("durations as PrusaSlicer writes them") {
  CHECK(format_duration(8) == "8s");
  CHECK(format_duration(27 * 60 + 8) == "27m 8s");
  CHECK(format_duration(3600 + 120 + 3) == "1h 2m 3s");
  CHECK(format_duration(86400 + 3600) == "1d 1h 0m 0s");
}

TEST_CASE("the G-code writer: a small cube gives a complete file with header values filled in") {
  test::TempDir dir("gcode-cube");
  test::PrintFixture f(test::prism_layers(10, {test::square_mm(0, 0, 10, 10)}), {}, {{"skirt_loops", "0"}});
  const std::string out = (dir / "cube.gcode").string();
  auto w = GcodeWriter::open(out, *f.setup, f.cascade->executors(), GcodeInfo{"cube", {}, {}, {}});
  REQUIRE(w.ok());
  for (int i = 0; i < 10; ++i) {
    auto plan = f.plan(i);
    auto text = format_layer(*f.setup, f.cascade->executors(), plan);
    REQUIRE(text.ok());
    REQUIRE((*w)->layer(*text, plan.time_s, plan.height).ok());
    CHECK_FALSE(std::filesystem::exists(out));  // nothing at the destination until finished
  }
  auto r = (*w)->finish();
  REQUIRE_MESSAGE(r.ok(), (r.ok() ? "" : r.error().to_string()));
  CHECK(r->layers == 10);
  CHECK(r->filament_mm > 0);
  CHECK(r->time_s > 0);
  std::string g = read(out);
  CHECK(g.find(";LAYER_COUNT:10") != std::string::npos);
  CHECK(g.find(";LAYER:9\n") != std::string::npos);
  CHECK(g.find(";TYPE:External perimeter") != std::string::npos);
  CHECK(g.find(";TYPE:Top solid infill") != std::string::npos);
  CHECK(g.find(";TYPE:Internal infill") != std::string::npos);
  CHECK(g.find("M82") != std::string::npos);
  // The patched header agrees with the footer.
  auto footer = g.find("; filament used [mm] = ", g.size() - 400);
  REQUIRE(footer != std::string::npos);
  std::string value = g.substr(footer + 23, g.find('\n', footer) - footer - 23);
  CHECK(g.find("; filament used [mm] = " + value) < 300);
  CHECK(g.find("; estimated printing time (normal mode) = " + format_duration(r->time_s)) < 200);
  // No rules, so no start G-code: the first layer's temperatures are set and waited for.
  CHECK(g.find("M190 S60 ;") < g.find("M82"));
  CHECK(g.find("M109 S210") < g.find("M82"));
  // Fan: off on layer 0 (the built-in defaults), on from layer 1.
  CHECK(g.find("M107") < g.find(";LAYER:1\n"));
  CHECK(g.find("M106 S255") > g.find(";LAYER:1\n"));
  CHECK(g.find("M106 S255") < g.find(";LAYER:2\n"));
}
