// End to end: the files of a run (docs/cli.md, "Files and safety"). An output that is an input of
// the run — the model, a --rules file, a file the rules use, the printer profile — or another
// output is refused before anything is written, and the input is left as it was.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "apps/slice_command.h"
#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "tests/support/fixtures.h"

using namespace tranche;
namespace fs = std::filesystem;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string write(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

}  // namespace

TEST_CASE("files: an output that is an input of the run is refused, naming both, and the input survives") {
  test::TempDir dir("files");
  const std::string model = (dir / "self.stl").string();
  REQUIRE(geo::write_stl_binary(model, geo::box({10, 10, 2})).ok());
  const std::string model_bytes = test::read_file(model);
  const std::string rules = write(dir / "my.rules", "rule \"slow\" { speed = 20 mm/s }\n");
  const std::string uses = write(dir / "uses.rules", "use \"./my\"\n");
  Report report;

  pipeline::SliceOptions o;
  o.model = model;
  o.quiet = true;
  o.output_gcode = model;
  auto self = app::slice(o, report);
  REQUIRE_FALSE(self.ok());
  CHECK(self.error().where == model);
  CHECK(has(self.error().message, "refusing to write the G-code here: this file is a model of this run"));
  CHECK(test::read_file(model) == model_bytes);

  o.output_gcode = (dir / "out.gcode").string();
  o.export_svg = model;
  auto svg = app::slice(o, report);
  REQUIRE_FALSE(svg.ok());
  CHECK(has(svg.error().message, "refusing to write the SVG export here"));
  CHECK_FALSE(fs::exists(dir / "out.gcode"));

  o.export_svg.clear();
  o.rules = {uses};
  o.output_gcode = rules;  // a file the --rules file uses
  auto used = app::slice(o, report);
  REQUIRE_FALSE(used.ok());
  CHECK(has(used.error().message, "refusing to write the G-code here: this file is the rules file of this run"));
  CHECK(test::read_file(rules) == "rule \"slow\" { speed = 20 mm/s }\n");

  o.rules.clear();
  o.output_gcode = (dir / "same").string();
  o.export_layers = (dir / "same").string();
  auto twice = app::slice(o, report);
  REQUIRE_FALSE(twice.ok());
  CHECK(has(twice.error().message, "the G-code is already written to this file"));
  CHECK_FALSE(fs::exists(dir / "same"));

  o.export_layers.clear();
  o.output_gcode = (dir / "ok.gcode").string();
  auto ok = app::slice(o, report);
  REQUIRE_MESSAGE(ok.ok(), ok.error().to_string());
  CHECK(fs::exists(dir / "ok.gcode"));
  // The next run is a run of its own: yesterday's output may be today's model.
  auto again = app::slice(o, report);
  REQUIRE_MESSAGE(again.ok(), again.error().to_string());
}

TEST_CASE("files: a G-code larger than --max-gcode-size is an error, and nothing is written") {
  test::TempDir dir("files-cap");
  const std::string model = (dir / "tall.stl").string();
  REQUIRE(geo::write_stl_binary(model, geo::box({60, 60, 30})).ok());
  const std::string out = write(dir / "out.gcode", "previous\n");
  pipeline::SliceOptions o;
  o.model = model;
  o.quiet = true;
  o.sets = {{"infill_density", "100%"}};
  o.output_gcode = out;
  o.max_gcode_mb = 1;
  Report report;
  auto r = app::slice(o, report);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().where == out);
  CHECK(has(r.error().message, "the G-code would be larger than 1 MiB (--max-gcode-size 1: raise it"));
  CHECK(test::read_file(out) == "previous\n");
  o.max_gcode_mb = 0;  // no limit
  auto unlimited = app::slice(o, report);
  REQUIRE_MESSAGE(unlimited.ok(), unlimited.error().to_string());
  CHECK(fs::file_size(out) > (1u << 20));
}
