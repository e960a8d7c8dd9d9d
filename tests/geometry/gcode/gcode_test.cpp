#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "geometry/gcode/layer_text.h"
#include "geometry/gcode/numbers.h"
#include "geometry/gcode/print.h"
#include "runtime/context/defaults.h"
#include "runtime/context/overrides.h"
#include "tests/support/fixtures.h"

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
geo::Ring square(double x0, double y0, double x1, double y1) {
  return {geo::to_point(x0, y0), geo::to_point(x1, y0), geo::to_point(x1, y1), geo::to_point(x0, y1)};
}
std::vector<geo::Layer> cube_layers(int n, double size) {
  std::vector<geo::Layer> layers(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    auto& l = layers[static_cast<size_t>(i)];
    l.index = i;
    l.z_bottom = 0.2 * i;
    l.z_top = 0.2 * (i + 1);
    geo::Island isl;
    isl.shape.outer = square(0, 0, size, size);
    l.islands.push_back(isl);
  }
  return layers;
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

TEST_CASE("write_gcode: a small cube gives a complete file with header values filled in") {
  test::TempDir dir("gcode-cube");
  auto layers = cube_layers(10, 10);
  ctx::BuiltinDefaults defaults;
  auto over = ctx::Overrides::parse({{"skirt_loops", "0"}});
  REQUIRE(over.ok());
  GcodeJob job;
  job.output = (dir / "cube.gcode").string();
  job.layers = layers;
  job.rules.defaults = &defaults;
  job.rules.decider = &*over;
  Report report;
  auto r = write_gcode(job, report);
  REQUIRE_MESSAGE(r.ok(), (r.ok() ? "" : r.error().to_string()));
  CHECK(r->layers == 10);
  CHECK(r->filament_mm > 0);
  CHECK(r->time_s > 0);
  std::string g = read(job.output);
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
