// End to end: rules on the plate's objects (object.index, object.name), read on the G-code.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "apps/slice_command.h"
#include "gcode_reader.h"
#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "geometry/plate/threemf_write.h"
#include "plate_helpers.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::test::plate_e2e;
namespace fs = std::filesystem;

namespace {

// The wall loops of each part on `layer`: runs of perimeter extrusions (a run ends at a move that
// does not extrude), each counted in the part where it starts.
std::vector<int> wall_loops(const test::Gcode& g, int layer, const std::vector<Box>& in) {
  std::vector<int> n(in.size(), 0);
  bool run = false;
  for (const auto& m : g.moves) {
    if (m.layer != layer || !m.has_xy) continue;
    const bool wall = m.de > 0 && (m.type == "External perimeter" || m.type == "Perimeter");
    if (wall && !run)
      for (size_t k = 0; k < in.size(); ++k)
        if (m.x0 > in[k].min_x - 1 && m.x0 < in[k].max_x + 1 && m.y0 > in[k].min_y - 1 && m.y0 < in[k].max_y + 1)
          ++n[k];
    run = wall;
  }
  return n;
}

std::string write_rules(const test::TempDir& dir, const std::string& text) {
  const std::string path = (dir / "objects.rules").string();
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("plate e2e: a rule on object.index gives the second model four walls, the first keeps two") {
  test::TempDir dir("plate-rule-index");
  plate::PlateOptions p;
  p.files = {(dir / "wide.stl").string(), (dir / "small.stl").string()};
  REQUIRE(geo::write_stl_binary(p.files[0], geo::box({24, 20, 3})).ok());
  REQUIRE(geo::write_stl_binary(p.files[1], geo::box({16, 16, 3})).ok());
  pipeline::SliceOptions o = options(dir);
  o.rules = {write_rules(dir, "rule \"stronger\" when object.index == 1 { perimeters = 4 }\n")};
  Report report;
  auto r = app::slice(o, p, report);
  REQUIRE_MESSAGE(r.ok(), r.error().to_string());
  const test::Gcode g = test::read_gcode(o.output_gcode);
  const auto objects = parts(g, 7);
  REQUIRE(objects.size() == 2);
  const size_t wide = objects[0].w() > objects[1].w() ? 0 : 1;
  CHECK(objects[wide].w() == doctest::Approx(24).epsilon(0.03));
  const auto loops = wall_loops(g, 7, objects);
  CHECK(loops[wide] == 2);      // object 0: the profile's perimeters
  CHECK(loops[1 - wide] == 4);  // object 1: the rule's
  // Without the rule, both have two.
  o.rules.clear();
  REQUIRE(app::slice(o, p, report).ok());
  const test::Gcode plain = test::read_gcode(o.output_gcode);
  CHECK(wall_loops(plain, 7, parts(plain, 7)) == std::vector<int>{2, 2});
}

TEST_CASE("plate e2e: rules on object.name: a 3MF object's name, an STL's file name, copies included") {
  test::TempDir dir("plate-rule-name");
  const std::string job = (dir / "job.3mf").string();
  REQUIRE(plate::write_3mf(job, {object("lid", geo::box({20, 20, 3}), Eigen::Affine3d(Eigen::Translation3d(30, 30, 0)))})
              .ok());
  const std::string base = (dir / "base.stl").string();
  REQUIRE(geo::write_stl_binary(base, geo::box({36, 20, 3})).ok());
  plate::PlateOptions p;
  p.files = {job, base};
  p.copies = {{"lid", 2}};
  pipeline::SliceOptions o = options(dir);
  o.rules = {write_rules(dir,
                         "rule \"lids\" when object.name == \"lid\" { perimeters = 4 }\n"
                         "rule \"the base\" when object.name in (\"base\", \"plinth\") { perimeters = 3 }\n"
                         "rule \"others\" when object.name != \"lid\" and object.name != \"base\" { perimeters = 1 }\n")};
  Report report;
  auto r = app::slice(o, p, report);
  REQUIRE_MESSAGE(r.ok(), r.error().to_string());
  const test::Gcode g = test::read_gcode(o.output_gcode);
  const auto objects = parts(g, 7);
  REQUIRE(objects.size() == 3);
  const auto loops = wall_loops(g, 7, objects);
  for (size_t k = 0; k < objects.size(); ++k) {
    CAPTURE(k);
    const bool is_base = objects[k].w() > 30;
    CHECK(loops[k] == (is_base ? 3 : 4));  // the lid and its copy: 4; base.stl: 3
  }
  // "plinth" names no object on the plate: a likely typo, said once, with the names there are.
  REQUIRE(report.count("object-name") == 1);
  for (const Warning& w : report.warnings())
    if (w.code == "object-name") {
      CHECK(w.where.ends_with("objects.rules:2:46"));
      CHECK(w.message == "the rules compare object.name with \"plinth\", but no object has that name (the names: "
                         "'lid', 'base')");
    }
}

TEST_CASE("plate e2e: a bed that depends on the plate is refused: the plate is placed on the bed first") {
  test::TempDir dir("plate-bed-rule");
  plate::PlateOptions p;
  p.files = {(dir / "tall.stl").string()};
  REQUIRE(geo::write_stl_binary(p.files[0], geo::box({20, 20, 12})).ok());
  pipeline::SliceOptions o = options(dir);
  o.rules = {write_rules(dir, "rule \"big prints\" when print.height > 10 mm { bed_size_x = 150 mm }\n")};
  Report report;
  auto r = app::slice(o, p, report);
  REQUIRE_FALSE(r.ok());
  CHECK(has(r.error().message, "bed_size_x is 200 for an empty plate but 150 for this one"));
  CHECK(has(r.error().message, "decide the bed without reading them"));
  CHECK_FALSE(fs::exists(o.output_gcode));
}
