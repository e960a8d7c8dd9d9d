// 3MF input: packages lib3mf writes, packages written by hand as PrusaSlicer, OrcaSlicer and
// Bambu Studio lay them out, and broken ones that must fail with a message, never a crash.
#include <doctest/doctest.h>

#include <cmath>

#include "geometry/mesh/primitives.h"
#include "geometry/plate/threemf.h"
#include "geometry/plate/threemf_write.h"
#include "tests/geometry/plate/plate_fixtures.h"

using namespace tranche;
using namespace tranche::test::plate;
using tranche::plate::Object;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

Result<std::vector<Object>> load(const std::string& bytes, Report& report) {
  return tranche::plate::parse_3mf(bytes, "plate.3mf", report);
}

std::string error_of(const std::string& bytes) {
  Report report;
  auto r = load(bytes, report);
  REQUIRE_FALSE(r.ok());
  return r.error().to_string();
}

Object object(const std::string& name, geo::Mesh mesh, const Eigen::Affine3d& t) {
  Object o;
  o.name = name;
  o.mesh = std::move(mesh);
  o.transform = t;
  return o;
}

}  // namespace

TEST_CASE("3mf: a package lib3mf wrote gives back every build item, its name and transform") {
  Eigen::Affine3d ta = Eigen::Affine3d::Identity(), tb = Eigen::Affine3d::Identity();
  ta.translate(Eigen::Vector3d(30, 40, 0));
  tb.translate(Eigen::Vector3d(100, 50, 0)).rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  auto bytes = tranche::plate::write_3mf_bytes(
      {object("box", geo::box({10, 20, 5}), ta), object("pin", geo::cylinder(3, 8, 24), tb)});
  REQUIRE_MESSAGE(bytes.ok(), bytes.error().to_string());
  Report report;
  auto objects = load(*bytes, report);
  REQUIRE_MESSAGE(objects.ok(), objects.error().to_string());
  CHECK(report.empty());
  REQUIRE(objects->size() == 2);
  const Object& a = (*objects)[0];
  const Object& b = (*objects)[1];
  CHECK(a.name == "box");
  CHECK(b.name == "pin");
  CHECK(a.file == "plate.3mf");
  CHECK(a.placed);
  CHECK(a.mesh.triangles.size() == 12);
  CHECK(b.mesh.triangles.size() == 96);
  CHECK(a.mesh.volume() == doctest::Approx(1000));
  const auto box = tranche::plate::world_bbox(a);
  CHECK(box.min.x == doctest::Approx(30));
  CHECK(box.max.y == doctest::Approx(60));
  // The pin turned a quarter about z, then moved to (100, 50).
  CHECK(b.transform.translation().x() == doctest::Approx(100));
  CHECK(b.transform.linear()(1, 0) == doctest::Approx(1));
}

TEST_CASE("3mf: a build item's transform turns the object as the specification says") {
  // Row-vector form of the spec: x' = -y + 5, y' = x + 6, z' = z + 7 (a quarter turn about z).
  const std::string m = model("<object id=\"7\" name=\"bar\" type=\"model\">" + box_mesh(10, 20, 5) + "</object>",
                              "<item objectid=\"7\" transform=\"0 1 0 -1 0 0 0 0 1 5 6 7\"/>");
  Report report;
  auto objects = load(package(m), report);
  REQUIRE_MESSAGE(objects.ok(), objects.error().to_string());
  REQUIRE(objects->size() == 1);
  const auto b = tranche::plate::world_bbox((*objects)[0]);
  CHECK(b.min.x == doctest::Approx(-15));
  CHECK(b.max.x == doctest::Approx(5));
  CHECK(b.min.y == doctest::Approx(6));
  CHECK(b.max.y == doctest::Approx(16));
  CHECK(b.min.z == doctest::Approx(7));
  CHECK(tranche::plate::world_mesh((*objects)[0]).volume() == doctest::Approx(1000));
}

TEST_CASE("3mf: units are converted to mm, in the meshes and the transforms") {
  const std::string m = model("<object id=\"1\" type=\"model\">" + box_mesh(1, 1, 1) + "</object>",
                              "<item objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 1 2 0 0\"/>", "inch");
  Report report;
  auto objects = load(package(m), report);
  REQUIRE_MESSAGE(objects.ok(), objects.error().to_string());
  const auto b = tranche::plate::world_bbox((*objects)[0]);
  CHECK(b.min.x == doctest::Approx(50.8));
  CHECK(b.max.x == doctest::Approx(76.2));
  CHECK((*objects)[0].mesh.volume() == doctest::Approx(25.4 * 25.4 * 25.4));
  CHECK((*objects)[0].name == "plate");  // no name in the file: the file's stem
}

TEST_CASE("3mf: components are flattened into their object; a mirror keeps the outside out") {
  const std::string m =
      model("<object id=\"1\" name=\"part\" type=\"model\">" + box_mesh(10, 10, 10) +
                "</object><object id=\"2\" name=\"pair\" type=\"model\"><components><component objectid=\"1\"/>"
                "<component objectid=\"1\" transform=\"-1 0 0 0 1 0 0 0 1 40 0 0\"/></components></object>",
            "<item objectid=\"2\"/><item objectid=\"2\" transform=\"1 0 0 0 1 0 0 0 1 0 50 0\"/>");
  Report report;
  auto objects = load(package(m), report);
  REQUIRE_MESSAGE(objects.ok(), objects.error().to_string());
  REQUIRE(objects->size() == 2);
  const Object& o = (*objects)[0];
  CHECK(o.name == "pair");
  CHECK(o.mesh.triangles.size() == 24);
  CHECK(o.mesh.volume() == doctest::Approx(2000));  // the mirrored copy is not inside out
  const auto b = tranche::plate::world_bbox(o);
  CHECK(b.min.x == doctest::Approx(0));
  CHECK(b.max.x == doctest::Approx(40));
  // The second build item of the same object is its copy.
  CHECK((*objects)[0].copy == 0);
  CHECK((*objects)[1].copy == 1);
  CHECK(tranche::plate::world_bbox((*objects)[1]).min.y == doctest::Approx(50));
}

TEST_CASE("3mf: PrusaSlicer's modifiers are left out and its settings noted, never an error") {
  const std::string m = model("<object id=\"1\" name=\"cubes\" type=\"model\">" + two_box_mesh() + "</object>",
                              "<item objectid=\"1\"/>");
  const std::string config =
      "<?xml version=\"1.0\"?><config><object id=\"1\" instances_count=\"1\">"
      "<metadata type=\"object\" key=\"name\" value=\"cubes\"/>"
      "<metadata type=\"object\" key=\"fill_density\" value=\"40%\"/>"
      "<volume firstid=\"0\" lastid=\"11\"><metadata type=\"volume\" key=\"name\" value=\"body\"/>"
      "<metadata type=\"volume\" key=\"volume_type\" value=\"ModelPart\"/></volume>"
      "<volume firstid=\"12\" lastid=\"23\"><metadata type=\"volume\" key=\"name\" value=\"denser\"/>"
      "<metadata type=\"volume\" key=\"volume_type\" value=\"ParameterModifier\"/></volume></object></config>";
  Report report;
  auto objects = load(package(m, {{"Metadata/Slic3r_PE_model.config", config},
                                  {"Metadata/Slic3r_PE.config", "; layer_height = 0.2\n"}}),
                      report);
  REQUIRE_MESSAGE(objects.ok(), objects.error().to_string());
  REQUIRE(objects->size() == 1);
  CHECK((*objects)[0].mesh.triangles.size() == 12);
  CHECK((*objects)[0].mesh.volume() == doctest::Approx(1000));
  CHECK(report.count("3mf-ignored") == 3);
  std::string all;
  for (const auto& w : report.warnings()) all += w.message + "\n";
  CHECK(has(all, "'denser' (ParameterModifier)"));
  CHECK(has(all, "fill_density"));
  CHECK(has(all, "Metadata/Slic3r_PE.config"));
}

TEST_CASE("3mf: objects kept in other model parts (Bambu Studio, OrcaSlicer) are followed") {
  const std::string root =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?><model unit=\"millimeter\" " + std::string(kNs) +
      " requiredextensions=\"p\"><resources><object id=\"3\" type=\"model\"><components>"
      "<component p:path=\"/3D/Objects/object_1.model\" objectid=\"1\"/>"
      "<component p:path=\"/3D/Objects/object_1.model\" objectid=\"2\"/></components></object></resources>"
      "<build><item objectid=\"3\" transform=\"1 0 0 0 1 0 0 0 1 100 100 0\"/></build></model>";
  const std::string part = model("<object id=\"1\" type=\"model\">" + box_mesh(10, 10, 10) +
                                     "</object><object id=\"2\" type=\"model\">" + box_mesh(4, 4, 4, 2) + "</object>",
                                 "");
  const std::string settings =
      "<?xml version=\"1.0\"?><config><object id=\"3\"><metadata key=\"name\" value=\"Widget\"/>"
      "<metadata key=\"wall_loops\" value=\"4\"/><part id=\"1\" subtype=\"normal_part\"/>"
      "<part id=\"2\" subtype=\"modifier_part\"/></object></config>";
  Report report;
  auto objects = load(package(root, {{"3D/Objects/object_1.model", part},
                                     {"Metadata/model_settings.config", settings},
                                     {"Metadata/project_settings.config", "{}"}}),
                      report);
  REQUIRE_MESSAGE(objects.ok(), objects.error().to_string());
  REQUIRE(objects->size() == 1);
  const Object& o = (*objects)[0];
  CHECK(o.name == "Widget");
  CHECK(o.mesh.triangles.size() == 12);  // the modifier is left out
  CHECK(tranche::plate::world_bbox(o).min.x == doctest::Approx(100));
  CHECK(report.count("3mf-ignored") == 3);  // per-object settings, the modifier, the project settings
}

TEST_CASE("3mf: broken packages fail with a message naming the file and what is wrong") {
  const std::string good = model("<object id=\"1\" type=\"model\">" + box_mesh(10, 10, 10) + "</object>",
                                 "<item objectid=\"1\"/>");
  const std::string pkg = package(good);
  SUBCASE("truncated") {
    const std::string e = error_of(pkg.substr(0, pkg.size() / 2));
    CHECK(has(e, "plate.3mf"));
    CHECK(has(e, "damaged or truncated"));
  }
  SUBCASE("a ZIP archive that holds no 3D model") {
    const std::string e = error_of(tranche::plate::write_stored_zip({{"readme.txt", "hi"}, {"part.stl", "solid"}}));
    CHECK(has(e, "not a 3MF package"));
    CHECK(has(e, "part.stl"));
    CHECK(has(e, "extract the model"));
  }
  SUBCASE("the model part is missing") {
    const std::string e =
        error_of(tranche::plate::write_stored_zip({{"[Content_Types].xml", kContentTypes}, {"_rels/.rels", kRels}}));
    CHECK(has(e, "no model part '3D/3dmodel.model'"));
  }
  SUBCASE("broken XML") {
    const std::string e = error_of(package(good.substr(0, good.size() - 40)));
    CHECK(has(e, "plate.3mf"));
    CHECK(has(e, "lib3mf"));
  }
  SUBCASE("a triangle index out of range") {
    std::string bad = good;
    bad.replace(bad.find("v3=\"1\""), 6, "v3=\"99\"");
    CHECK(has(error_of(package(bad)), "index out of range"));
  }
  SUBCASE("a transform that cannot be inverted") {
    const std::string flat = model("<object id=\"1\" name=\"flat\" type=\"model\">" + box_mesh(10, 10, 10) + "</object>",
                                   "<item objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 0 0 0 0\"/>");
    const std::string e = error_of(package(flat));
    CHECK(has(e, "'flat'"));
    CHECK(has(e, "flattens"));
  }
  SUBCASE("a coordinate that is not a number") {
    std::string bad = good;
    bad.replace(bad.find("x=\"0\""), 5, "x=\"nan\"");
    CHECK(has(error_of(package(bad)), "coordinate"));
  }
  SUBCASE("no build items") { CHECK(has(error_of(package(model("<object id=\"1\" type=\"model\">" + box_mesh(1, 1, 1) + "</object>", ""))), "no build items")); }
  SUBCASE("a component refers to a part that is not there") {
    const std::string root = model("<object id=\"3\" type=\"model\"><components><component "
                                   "p:path=\"/3D/Objects/gone.model\" objectid=\"1\"/></components></object>",
                                   "<item objectid=\"3\"/>");
    CHECK(has(error_of(package(root, {{"3D/Objects/other.model", model("", "")}})), "gone.model"));
  }
}

TEST_CASE("3mf: support objects are left out with a warning") {
  const std::string m = model("<object id=\"1\" name=\"body\" type=\"model\">" + box_mesh(10, 10, 10) +
                                  "</object><object id=\"2\" name=\"prop\" type=\"support\">" + box_mesh(2, 2, 2) +
                                  "</object>",
                              "<item objectid=\"1\"/><item objectid=\"2\"/>");
  Report report;
  auto objects = load(package(m, {}, true), report);
  REQUIRE_MESSAGE(objects.ok(), objects.error().to_string());
  CHECK(objects->size() == 1);
  CHECK(report.count("3mf-ignored") == 1);
}

TEST_CASE("3mf: objects welded together report as one by one: warnings in item order, the first error") {
  // A box with one extra triangle that welds to a degenerate one; a box of which every triangle
  // is degenerate (all its corners at one point); a support object (a warning of its own).
  std::string with_degenerate = box_mesh(10, 10, 10);
  with_degenerate.replace(with_degenerate.find("</triangles>"), 0, "<triangle v1=\"0\" v2=\"0\" v3=\"1\"/>");
  const std::string flat_mesh =
      "<mesh><vertices><vertex x=\"1\" y=\"1\" z=\"1\"/><vertex x=\"1\" y=\"1\" z=\"1\"/><vertex x=\"1\" y=\"1\" "
      "z=\"1\"/></vertices><triangles><triangle v1=\"0\" v2=\"1\" v3=\"2\"/></triangles></mesh>";
  const std::string objects = "<object id=\"1\" name=\"first\" type=\"model\">" + with_degenerate +
                              "</object><object id=\"2\" name=\"prop\" type=\"support\">" + box_mesh(2, 2, 2) +
                              "</object><object id=\"3\" name=\"second\" type=\"model\">" + with_degenerate +
                              "</object><object id=\"4\" name=\"point\" type=\"model\">" + flat_mesh + "</object>";
  SUBCASE("all load: the warnings in the order of the items") {
    Report report;
    auto r = load(package(model(objects, "<item objectid=\"3\"/><item objectid=\"2\"/><item objectid=\"1\"/>")), report);
    REQUIRE_MESSAGE(r.ok(), r.error().to_string());
    REQUIRE(r->size() == 2);
    CHECK((*r)[0].name == "second");
    CHECK((*r)[1].name == "first");
    CHECK((*r)[0].mesh.triangles.size() == 12);
    const auto w = report.warnings();
    REQUIRE(w.size() == 3);
    CHECK(w[0].code == "mesh-degenerate");
    CHECK(has(w[0].where, "'second'"));
    CHECK(w[1].code == "3mf-ignored");
    CHECK(w[2].code == "mesh-degenerate");
    CHECK(has(w[2].where, "'first'"));
  }
  SUBCASE("an object with no surface: its error, after the warnings of the items before it") {
    Report report;
    auto r = load(package(model(objects, "<item objectid=\"1\"/><item objectid=\"4\"/><item objectid=\"3\"/>")), report);
    REQUIRE_FALSE(r.ok());
    CHECK(has(r.error().to_string(), "'point'"));
    CHECK(has(r.error().to_string(), "all 1 triangles are degenerate"));
    const auto w = report.warnings();
    REQUIRE(w.size() == 1);  // the first object's; the third is not reached
    CHECK(has(w[0].where, "'first'"));
  }
  SUBCASE("a build item lib3mf refuses after an object that cannot be welded: the weld's error comes first") {
    Report report;
    auto r = load(package(model(objects, "<item objectid=\"4\"/><item objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 0 0 0 0\"/>")),
                  report);
    REQUIRE_FALSE(r.ok());
    CHECK(has(r.error().to_string(), "'point'"));
  }
  SUBCASE("a repeated build item shares its object's mesh") {
    Report report;
    auto r = load(package(model(objects, "<item objectid=\"1\"/><item objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 1 30 0 0\"/>")),
                  report);
    REQUIRE_MESSAGE(r.ok(), r.error().to_string());
    REQUIRE(r->size() == 2);
    CHECK((*r)[1].copy == 1);
    CHECK((*r)[1].mesh.triangles == (*r)[0].mesh.triangles);
    CHECK((*r)[1].mesh.vertices.size() == (*r)[0].mesh.vertices.size());
    CHECK(report.count("mesh-degenerate") == 1);
  }
}
