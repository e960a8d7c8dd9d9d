// The 3MF loader's own reading of plain meshes (threemf_meshes.h): what it takes, what it leaves
// to lib3mf, and that a model loads the same either way.
#include <doctest/doctest.h>

#include <fstream>
#include <iterator>

#include "geometry/mesh/primitives.h"
#include "geometry/plate/threemf.h"
#include "geometry/plate/threemf_meshes.h"
#include "geometry/plate/threemf_write.h"
#include "geometry/plate/zip.h"
#include "tests/geometry/plate/plate_fixtures.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::test::plate;
namespace threemf = tranche::plate::threemf;

TEST_CASE("3mf meshes: plain meshes are read and replaced by placeholders that name their object") {
  const std::string xml = model(
      "<object id=\"7\" type=\"model\"><mesh>\n <vertices><vertex x=\"0\" y=\"0\" z=\"0\"/><vertex x='1.5' y=\"0\" "
      "z=\"0\" /><vertex z=\"2\" x=\"0\" y=\"1e1\"/></vertices>\n<triangles><triangle v1=\"0\" v2=\"1\" v3=\"2\" "
      "p1=\"4\"/></triangles></mesh></object><object id=\"8\"><components><component objectid=\"7\"/></components>"
      "</object>",
      "<item objectid=\"8\"/>");
  const threemf::SplitModel s = threemf::split_meshes(xml);
  REQUIRE(s.meshes.size() == 1);
  const threemf::MeshData& m = s.meshes.at(7);
  CHECK(m.vertices == std::vector<float>{0, 0, 0, 1.5f, 0, 0, 0, 10, 2});
  CHECK(m.triangles == std::vector<uint32_t>{0, 1, 2});
  CHECK(s.model.find("1.5") == std::string::npos);
  CHECK(s.model.find("<components><component objectid=\"7\"/></components>") != std::string::npos);
  const float a[3] = {7, -7777, 0}, b[3] = {7, -7776, 0}, c[3] = {7, -7777, 1};
  CHECK(threemf::placeholder_id(a, b, c) == 7u);
  const float d[3] = {7, -7777, 2};
  CHECK_FALSE(threemf::placeholder_id(a, b, d));
}

TEST_CASE("3mf meshes: what the scanner does not follow is left to lib3mf") {
  auto left = [](const std::string& mesh) {
    return threemf::split_meshes(model("<object id=\"1\" type=\"model\">" + mesh + "</object>", "<item objectid=\"1\"/>"))
        .meshes.empty();
  };
  CHECK_FALSE(left(box_mesh(1, 1, 1)));
  std::string nan = box_mesh(1, 1, 1);
  nan.replace(nan.find("x=\"0\""), 5, "x=\"nan\"");
  CHECK(left(nan));
  std::string out_of_range = box_mesh(1, 1, 1);
  out_of_range.replace(out_of_range.find("v3=\"1\""), 6, "v3=\"99\"");
  CHECK(left(out_of_range));
  std::string plus = box_mesh(1, 1, 1);
  plus.replace(plus.find("x=\"0\""), 5, "x=\"+0\"");
  CHECK(left(plus));
  CHECK(left("<mesh><vertices></vertices><triangles></triangles></mesh>"));
  CHECK(left("<m:mesh><m:vertices/></m:mesh>"));
  std::string commented = box_mesh(1, 1, 1);
  commented.replace(commented.find("<vertices>"), 10, "<vertices><!-- a comment -->");
  CHECK(left(commented));
}

TEST_CASE("3mf meshes: a model loads the same through the scanner as through lib3mf alone") {
  // A torus and a box turned by its build item: read once as written, once with a comment in each
  // mesh, which leaves every mesh to lib3mf.
  tranche::plate::Object torus, box;
  torus.name = "torus";
  torus.mesh = geo::torus(20, 5, 48, 24);
  torus.transform = Eigen::Translation3d(50, 50, 5);
  box.name = "box";
  box.mesh = geo::box({10, 20, 5});
  box.transform = Eigen::Translation3d(120, 40, 0) * Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ());
  test::TempDir dir("3mf-meshes");
  const std::string file = (dir / "two.3mf").string();
  REQUIRE(tranche::plate::write_3mf(file, {torus, box}).ok());
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto zip = tranche::plate::ZipArchive::open(bytes, file);
  REQUIRE(zip.ok());
  auto xml = zip->read(*zip->find("3D/3dmodel.model"));
  REQUIRE(xml.ok());
  CHECK(threemf::split_meshes(*xml).meshes.size() == 2);
  std::string slow_xml = *xml;
  for (size_t at = slow_xml.find("<vertices>"); at != std::string::npos; at = slow_xml.find("<vertices>", at + 1))
    slow_xml.insert(at + 10, "<!-- lib3mf reads it -->");
  REQUIRE(threemf::split_meshes(slow_xml).meshes.empty());
  const std::string commented = package(slow_xml);
  Report report;
  auto fast = tranche::plate::parse_3mf(bytes, "two.3mf", report);
  auto slow = tranche::plate::parse_3mf(commented, "two.3mf", report);
  REQUIRE(fast.ok());
  REQUIRE(slow.ok());
  REQUIRE(fast->size() == 2);
  REQUIRE(slow->size() == 2);
  for (size_t i = 0; i < 2; ++i) {
    CAPTURE(i);
    CHECK((*fast)[i].name == (*slow)[i].name);
    CHECK((*fast)[i].transform.matrix() == (*slow)[i].transform.matrix());
    const auto &fv = (*fast)[i].mesh.vertices, &sv = (*slow)[i].mesh.vertices;
    REQUIRE(fv.size() == sv.size());
    bool same = true;
    for (size_t k = 0; k < fv.size(); ++k) same = same && fv[k].x == sv[k].x && fv[k].y == sv[k].y && fv[k].z == sv[k].z;
    CHECK(same);
    CHECK((*fast)[i].mesh.triangles == (*slow)[i].mesh.triangles);
    CHECK((*fast)[i].mesh.triangles.size() == (i == 0 ? torus : box).mesh.triangles.size());
  }
  CHECK(report.empty());
}
