// OBJ input, and loading any model file by its content rather than its name.
#include <doctest/doctest.h>

#include <fstream>

#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "geometry/plate/detect.h"
#include "geometry/plate/model_file.h"
#include "geometry/plate/obj.h"
#include "geometry/plate/threemf_write.h"
#include "tests/geometry/plate/plate_fixtures.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::test::plate;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string obj_error(const std::string& text) {
  Report report;
  auto r = tranche::plate::parse_obj(text, "part.obj", report);
  REQUIRE_FALSE(r.ok());
  return r.error().to_string();
}

void write(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
}

}  // namespace

TEST_CASE("obj: quads and polygons are triangulated into one closed object") {
  Report report;
  auto objects = tranche::plate::parse_obj(cube_obj(10), "cube.obj", report);
  REQUIRE_MESSAGE(objects.ok(), objects.error().to_string());
  REQUIRE(objects->size() == 1);
  const auto& o = (*objects)[0];
  CHECK(o.name == "cube");
  CHECK_FALSE(o.placed);
  CHECK(o.mesh.triangles.size() == 12);
  CHECK(o.mesh.vertices.size() == 8);
  CHECK(o.mesh.volume() == doctest::Approx(1000));
  CHECK(report.empty());

  // A concave pentagon, negative (relative) indices and v/vt/vn forms.
  const std::string penta =
      "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 5 2 0\nv 0 10 0\nvt 0 0\nvn 0 0 1\nf -5/1/1 -4//1 -3 -1 -2/1\n";
  auto flat = tranche::plate::parse_obj(penta, "penta.obj", report);
  REQUIRE_MESSAGE(flat.ok(), flat.error().to_string());
  CHECK((*flat)[0].mesh.triangles.size() == 3);
}

TEST_CASE("obj: faces with too few vertices or vertices that do not exist fail with their line") {
  CHECK(obj_error("v 0 0 0\nv 1 0 0\nf 1 2\n") == "part.obj:3: a face with 2 vertices: a face needs at least 3");
  CHECK(obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 7\n") ==
        "part.obj:5: the face refers to vertex 7, but the file has 3 vertices");
  CHECK(has(obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), "part.obj:4: vertex number 0"));
  CHECK(has(obj_error("v 0 0 0\nf -2 -1 1\n"), "part.obj:2: the face refers to vertex -2"));
  CHECK(has(obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 a 3\n"), "'a' is not a vertex number"));
  CHECK(has(obj_error("# only points\nv 0 0 0\nv 1 0 0\n"), "no faces"));
}

TEST_CASE("detect: the content decides, not the name") {
  using tranche::plate::Format;
  CHECK(tranche::plate::detect_format(package(model("", ""))).format == Format::ThreeMf);
  CHECK(tranche::plate::detect_format(cube_obj()).format == Format::Obj);
  CHECK(tranche::plate::detect_format("solid x\nendsolid x\n").format == Format::Stl);
  CHECK(tranche::plate::detect_format("solid x\nendsolid x\n").sure);
  CHECK_FALSE(tranche::plate::detect_format("just some words\n").sure);
  CHECK(tranche::plate::detect_format("<?xml version=\"1.0\"?>\n<svg width=\"1\"/>").format == Format::Svg);
  CHECK(tranche::plate::detect_format("\x89PNG\r\n\x1a\n....").what == "a PNG image, not a model");
  CHECK(has(tranche::plate::detect_format(";FLAVOR:Marlin\nG28\nG1 X10\n").what, "G-code"));
  CHECK(has(tranche::plate::detect_format("ISO-10303-21;\nHEADER;").what, "STEP"));
  CHECK(has(tranche::plate::detect_format("<?xml version=\"1.0\"?><amf unit=\"mm\">").what, "AMF"));
}

TEST_CASE("load_model_file: a 3MF named .stl loads; other files say what they are") {
  test::TempDir dir("model-file");
  tranche::plate::Object box;
  box.name = "box";
  box.mesh = geo::box({10, 10, 10});
  auto bytes = tranche::plate::write_3mf_bytes({box});
  REQUIRE(bytes.ok());
  write(dir / "really-a-3mf.stl", *bytes);
  Report report;
  auto objects = tranche::plate::load_model_file((dir / "really-a-3mf.stl").string(), report);
  REQUIRE_MESSAGE(objects.ok(), objects.error().to_string());
  CHECK((*objects)[0].name == "box");

  REQUIRE(geo::write_stl_binary((dir / "part.stl").string(), geo::box({5, 5, 5})).ok());
  auto stl = tranche::plate::load_model_file((dir / "part.stl").string(), report);
  REQUIRE_MESSAGE(stl.ok(), stl.error().to_string());
  CHECK((*stl)[0].name == "part");
  CHECK_FALSE((*stl)[0].placed);

  write(dir / "cube.stl", cube_obj());
  auto obj = tranche::plate::load_model_file((dir / "cube.stl").string(), report);
  REQUIRE_MESSAGE(obj.ok(), obj.error().to_string());
  CHECK((*obj)[0].mesh.triangles.size() == 12);

  write(dir / "photo.stl", "\x89PNG\r\n\x1a\n0000000000");
  auto png = tranche::plate::load_model_file((dir / "photo.stl").string(), report);
  REQUIRE_FALSE(png.ok());
  CHECK(png.error().to_string() == (dir / "photo.stl").string() + ": this is a PNG image, not a model");

  std::filesystem::create_directories(dir / "folder.3mf");
  auto folder = tranche::plate::load_model_file((dir / "folder.3mf").string(), report);
  REQUIRE_FALSE(folder.ok());
  CHECK(has(folder.error().message, "is a directory, not the model"));

  write(dir / "drawing.stl", "<svg xmlns=\"http://www.w3.org/2000/svg\"/>");
  auto svg = tranche::plate::load_model_file((dir / "drawing.stl").string(), report);
  REQUIRE_FALSE(svg.ok());
  CHECK(has(svg.error().message, "SVG drawing"));
}
