// End to end: `tranche slice` from an STL file to the layer exports.
#include "apps/slice_command.h"

#include <doctest/doctest.h>

#include <pugixml.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::geo;
using tranche::app::slice;
using tranche::pipeline::SliceOptions;

namespace {

std::string write_model(const test::TempDir& dir, const std::string& name, const Mesh& m) {
  const std::string path = (dir / name).string();
  REQUIRE(write_stl_binary(path, m).ok());
  return path;
}

size_t files_in(const std::filesystem::path& dir) {
  return static_cast<size_t>(
      std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()));
}

// Layer areas (mm²) from a layer group's tranche:area attributes.
std::vector<double> svg_layer_areas(const std::string& path) {
  pugi::xml_document doc;
  auto res = doc.load_file(path.c_str());
  REQUIRE_MESSAGE(res, res.description());
  std::vector<double> areas;
  for (pugi::xml_node g : doc.child("svg").children("g"))
    if (std::string_view(g.attribute("class").value()) == "layer") areas.push_back(g.attribute("tranche:area").as_double());
  return areas;
}

}  // namespace

SCENARIO("slicing a cube to SVG and JSON") {
  test::TempDir dir("pipeline");
  SliceOptions o;
  o.model = write_model(dir, "cube.stl", box({10, 10, 10}, {100, 50, 20}));  // lifted: placed at z = 0
  o.export_svg = (dir / "cube.svg").string();
  o.export_layers = (dir / "cube.json").string();
  o.quiet = true;
  Report report;
  auto r = slice(o, report);
  REQUIRE_MESSAGE(r.ok(), (r.ok() ? "" : r.error().to_string()));
  THEN("50 layers of 100 mm², both files written, one warning: the cube floated and was dropped onto the bed") {
    CHECK(r->layers == 50);
    CHECK(r->triangles == 12);
    CHECK(r->written == std::vector<std::string>{o.export_svg, o.export_layers});
    auto areas = svg_layer_areas(o.export_svg);
    REQUIRE(areas.size() == 50);
    for (double a : areas) CHECK(a == doctest::Approx(100));
    std::ifstream json(o.export_layers);
    std::string first;
    std::getline(json, first);
    CHECK(first.rfind("{\"format\": \"tranche-layers\", \"version\": 2", 0) == 0);
    CHECK(report.size() == 1);
    CHECK(report.count("plate-dropped") == 1);
    CHECK(files_in(dir.path()) == 3);  // no temporary files left behind
  }
}

SCENARIO("errors the user can act on") {
  test::TempDir dir("pipeline-errors");
  Report report;
  SliceOptions o;
  o.quiet = true;
  o.model = write_model(dir, "cube.stl", box({10, 10, 10}));
  o.export_svg = (dir / "out.svg").string();
  GIVEN("-o with a --set that names no property") {
    o.output_gcode = (dir / "out.gcode").string();
    o.sets = {{"layer_hieght", "0.1"}};
    auto r = slice(o, report);
    REQUIRE(!r.ok());
    CHECK(r.error().message.find("did you mean `--set layer_height=0.1`?") != std::string::npos);
    CHECK(files_in(dir.path()) == 1);  // nothing written
  }
  GIVEN("no output at all") {
    o.export_svg.clear();
    auto r = slice(o, report);
    REQUIRE(!r.ok());
    CHECK(r.error().message.find("--export-svg") != std::string::npos);
  }
  GIVEN("a flat model") {
    Mesh flat;
    flat.vertices = {{0, 0, 1}, {10, 0, 1}, {0, 10, 1}, {10, 10, 1}};
    flat.triangles = {{0, 1, 2}, {2, 1, 3}};
    o.model = write_model(dir, "flat.stl", flat);
    auto r = slice(o, report);
    REQUIRE(!r.ok());
    CHECK(r.error().where == o.model);
    CHECK(r.error().message.find("flat") != std::string::npos);
    CHECK(!std::filesystem::exists(o.export_svg));
  }
  GIVEN("a surface with no volume") {
    Mesh fin;
    fin.vertices = {{0, 0, 0}, {10, 0, 0}, {5, 0, 8}};
    fin.triangles = {{0, 1, 2}};
    o.model = write_model(dir, "fin.stl", fin);
    auto r = slice(o, report);
    REQUIRE(!r.ok());
    CHECK(r.error().message.find("nothing to print") != std::string::npos);
    CHECK(!std::filesystem::exists(o.export_svg));
  }
  GIVEN("a missing model") {
    o.model = (dir / "nope.stl").string();
    auto r = slice(o, report);
    REQUIRE(!r.ok());
    CHECK(r.error().to_string().find("nope.stl") != std::string::npos);
  }
  GIVEN("an export into a folder that does not exist") {
    o.export_svg = (dir / "no-such-folder" / "out.svg").string();
    auto r = slice(o, report);
    REQUIRE(!r.ok());
    CHECK(r.error().where == o.export_svg);
  }
}

SCENARIO("an open mesh yields every layer, with warnings") {
  test::TempDir dir("pipeline-open");
  Mesh m = box({10, 10, 4});
  std::vector<std::array<uint32_t, 3>> kept;
  for (const auto& t : m.triangles)
    if (!(m.vertices[t[0]].y == 10 && m.vertices[t[1]].y == 10 && m.vertices[t[2]].y == 10))
      kept.push_back(t);
  m.triangles = kept;
  SliceOptions o;
  o.quiet = true;
  o.model = write_model(dir, "open.stl", m);
  o.export_svg = (dir / "open.svg").string();
  Report report;
  auto r = slice(o, report);
  REQUIRE(r.ok());
  CHECK(r->layers == 20);
  for (double a : svg_layer_areas(o.export_svg)) CHECK(a == doctest::Approx(100));
  CHECK(report.count("mesh-open") == 1);
  CHECK(report.count("open-loop") == 20);
}

TEST_CASE("the committed demo model is the generated one, and slices cleanly") {
  const auto path = (test::source_dir() / "examples" / "models" / "demo.stl").string();
  Report report;
  auto loaded = load_stl(path, report);
  REQUIRE(loaded.ok());
  const Mesh demo = demo_model();
  CHECK(loaded->triangles.size() == demo.triangles.size());
  CHECK(loaded->volume() == doctest::Approx(demo.volume()).epsilon(1e-5));
  test::TempDir dir("pipeline-demo");
  SliceOptions o;
  o.quiet = true;
  o.model = path;
  o.export_layers = (dir / "demo.json").string();
  auto r = slice(o, report);
  REQUIRE(r.ok());
  CHECK(r->layers == 75);
  CHECK(report.empty());
}

TEST_CASE("the Stanford bunny (open, 223 boundary edges) loses no layer") {
  // From the npm package stl-models (scripts/fetch-models.sh); metres with Y up.
  const char* home = std::getenv("HOME");
  const std::filesystem::path src =
      std::filesystem::path(home ? home : "/tmp") / ".cache/tranche/models/objects/bunny.bin.stl";
  if (!std::filesystem::exists(src)) {
    MESSAGE("skipped: " << src << " is missing; run scripts/fetch-models.sh");
    return;
  }
  Report report;
  auto bunny = load_stl(src.string(), report);
  REQUIRE(bunny.ok());
  for (auto& v : bunny->vertices) v = {v.x * 1000, -v.z * 1000, v.y * 1000};
  test::TempDir dir("pipeline-bunny");
  SliceOptions o;
  o.quiet = true;
  o.model = write_model(dir, "bunny.stl", *bunny);
  o.export_svg = (dir / "bunny.svg").string();
  auto r = slice(o, report);
  REQUIRE(r.ok());
  const BBox3 b = bunny->bbox();
  CHECK(r->layers == static_cast<int>(std::ceil((b.max.z - b.min.z) / 0.2 - 0.25)));
  auto areas = svg_layer_areas(o.export_svg);
  REQUIRE(areas.size() == static_cast<size_t>(r->layers));
  size_t empty = 0;
  for (double a : areas) empty += !(a > 0);
  CHECK(empty == 0);
  CHECK(report.count("mesh-open") == 1);
  CHECK(report.count("open-loop") > 0);
}
