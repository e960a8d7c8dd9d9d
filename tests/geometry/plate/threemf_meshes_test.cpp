// The 3MF loader's own reading of plain meshes (threemf_meshes.h): what it takes, what it leaves
// to lib3mf, and that a model loads the same either way.
#include <doctest/doctest.h>

#include <algorithm>
#include <charconv>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <random>

#include "geometry/mesh/primitives.h"
#include "geometry/mesh/weld.h"
#include "geometry/plate/threemf.h"
#include "geometry/plate/threemf_meshes.h"
#include "geometry/plate/threemf_write.h"
#include "geometry/plate/zip.h"
#include "tests/geometry/plate/plate_fixtures.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::test::plate;
namespace threemf = tranche::plate::threemf;
using Triangles = std::vector<std::array<uint32_t, 3>>;

namespace {

// x, y, z of each vertex of `m`.
std::vector<float> flat(const threemf::MeshData& m) {
  std::vector<float> out;
  for (const auto& v : m.vertices)
    for (double c : {v.x, v.y, v.z}) out.push_back(static_cast<float>(c));
  return out;
}

}  // namespace

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
  CHECK(flat(m) == std::vector<float>{0, 0, 0, 1.5f, 0, 0, 0, 10, 2});
  CHECK(m.triangles == Triangles{{0, 1, 2}});
  CHECK(m.ordered);
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

TEST_CASE("3mf meshes: duplicate and -0 vertices, unused ones and degenerate triangles weld as their corners do") {
  // The scanner puts a mesh in the welder's order as it reads it; whether the mesh is then taken
  // whole (object 3), shared by two objects (object 1, also a turned component of object 2) or
  // read by lib3mf (a comment in each mesh), each object is what welding its triangles' corners
  // gives, as an STL of them would: the same vertices in the same order, triangles and warnings.
  const std::vector<std::string> v = {"0", "0", "0",  "10", "0", "0",   "0",  "10", "0", "0", "0", "10",
                                      "1e1", "0", "-0", "-0", "0", "-0", "5", "5",  "5", "10", "10", "10"};
  // Vertex 4 is vertex 1 again, 5 is vertex 0 with -0, 6 is used by no triangle; triangles 3 and 6
  // are degenerate (1 = 4), triangle 5 uses vertex 5 (0 with -0) first.
  const std::vector<uint32_t> t = {7, 4, 2, 0, 2, 1, 3, 1, 2, 1, 4, 3, 5, 3, 2, 0, 1, 3, 4, 1, 7, 2, 3, 7};
  std::string mesh = "<mesh><vertices>";
  for (size_t i = 0; i < v.size(); i += 3)
    mesh += fmt::format("<vertex x=\"{}\" y=\"{}\" z=\"{}\"/>", v[i], v[i + 1], v[i + 2]);
  mesh += "</vertices><triangles>";
  for (size_t i = 0; i < t.size(); i += 3)
    mesh += fmt::format("<triangle v1=\"{}\" v2=\"{}\" v3=\"{}\"/>", t[i], t[i + 1], t[i + 2]);
  mesh += "</triangles></mesh>";
  const std::string xml = model(
      "<object id=\"1\" type=\"model\">" + mesh + "</object><object id=\"2\" type=\"model\"><components><component "
      "objectid=\"1\" transform=\"0 1 0 -1 0 0 0 0 1 20 0 0\"/></components></object><object id=\"3\" "
      "type=\"model\">" + mesh + "</object>",
      "<item objectid=\"1\"/><item objectid=\"2\"/><item objectid=\"3\"/>");
  const auto split = threemf::split_meshes(xml);
  REQUIRE(split.meshes.size() == 2);
  CHECK(split.meshes.at(1).ordered);
  CHECK(split.meshes.at(1).triangles.size() == 8);  // degenerate ones kept: PrusaSlicer's volumes count them
  std::string slow_xml = xml;
  for (size_t at = slow_xml.find("<vertices>"); at != std::string::npos; at = slow_xml.find("<vertices>", at + 1))
    slow_xml.insert(at + 10, "<!-- lib3mf reads it -->");
  REQUIRE(threemf::split_meshes(slow_xml).meshes.empty());
  Report fast_report, slow_report;
  auto fast = tranche::plate::parse_3mf(package(xml), "m.3mf", fast_report);
  auto slow = tranche::plate::parse_3mf(package(slow_xml), "m.3mf", slow_report);
  REQUIRE(fast.ok());
  REQUIRE(slow.ok());
  REQUIRE(fast->size() == 3);
  REQUIRE(slow->size() == 3);
  // Object 1 (and 3) as an STL of the corners: weld_corners, bit for bit (-0 welded into +0).
  std::vector<float> corners;
  for (uint32_t i : t)
    for (int k = 0; k < 3; ++k) corners.push_back(static_cast<float>(std::stod(v[3 * i + k])));
  Report corner_report;
  auto welded = geo::weld_corners(corners, "m.3mf, object 'm'", corner_report);
  REQUIRE(welded.ok());
  CHECK(welded->vertices.size() == 5);  // 0, 1, 2, 3 and 7: 4 and 5 welded, 6 unused
  CHECK(welded->triangles.size() == 6);
  const auto same_mesh = [](const geo::Mesh& a, const geo::Mesh& b) {
    if (a.vertices.size() != b.vertices.size() || a.triangles != b.triangles) return false;
    for (size_t k = 0; k < a.vertices.size(); ++k)
      if (std::memcmp(&a.vertices[k], &b.vertices[k], sizeof a.vertices[k]) != 0) return false;
    return true;
  };
  for (size_t i = 0; i < 3; ++i) {
    CAPTURE(i);
    CHECK(same_mesh((*fast)[i].mesh, (*slow)[i].mesh));
    if (i != 1) CHECK(same_mesh((*fast)[i].mesh, *welded));
  }
  const auto wf = fast_report.warnings(), ws = slow_report.warnings();
  REQUIRE(wf.size() == 3);
  REQUIRE(ws.size() == 3);
  for (size_t i = 0; i < 3; ++i) {
    CHECK(wf[i].message == ws[i].message);
    CHECK(wf[i].message == "dropped 2 degenerate triangles of 8 (two corners at the same point)");
  }
}

TEST_CASE("3mf meshes: forms the scanner leaves to lib3mf load as the plain form does, or fail naming the file") {
  // A vertex or a triangle not closed by itself: lib3mf reads those meshes. A character reference
  // in a number (which lib3mf 1.8 does not read) or a number neither reads: an error naming the
  // file, never a number read wrong.
  const std::string plain = box_mesh(10, 10, 10);
  auto load = [](const std::string& mesh) {
    Report report;
    return tranche::plate::parse_3mf(
        package(model("<object id=\"1\" name=\"box\" type=\"model\">" + mesh + "</object>", "<item objectid=\"1\"/>")),
        "odd.3mf", report);
  };
  const auto want = load(plain);
  REQUIRE(want.ok());
  std::string open_vertex = plain;
  open_vertex.replace(open_vertex.find("z=\"0\"/>"), 7, "z=\"0\"></vertex>");
  std::string reference = plain;
  reference.replace(reference.find("x=\"10\""), 6, "x=\"&#49;0\"");  // "10"
  std::string open_triangle = plain;
  open_triangle.replace(open_triangle.find("v3=\"1\"/>"), 8, "v3=\"1\" ></triangle>");
  for (const std::string& odd : {open_vertex, open_triangle}) {
    CAPTURE(odd);
    CHECK(threemf::split_meshes(model("<object id=\"1\">" + odd + "</object>", "")).meshes.empty());
    const auto got = load(odd);
    REQUIRE(got.ok());
    REQUIRE(got->size() == 1);
    CHECK((*got)[0].mesh.triangles == (*want)[0].mesh.triangles);
    REQUIRE((*got)[0].mesh.vertices.size() == (*want)[0].mesh.vertices.size());
    for (size_t i = 0; i < (*got)[0].mesh.vertices.size(); ++i) {
      CHECK((*got)[0].mesh.vertices[i].x == (*want)[0].mesh.vertices[i].x);
      CHECK((*got)[0].mesh.vertices[i].y == (*want)[0].mesh.vertices[i].y);
      CHECK((*got)[0].mesh.vertices[i].z == (*want)[0].mesh.vertices[i].z);
    }
  }
  // lib3mf 1.8 reads all of these as a number (0, or the number they begin with): refused with
  // where they are (the vertex x="10" is on line 2, the first triangle's v2 on line 3).
  for (const std::string bad : {"abc", "", "1.2.3", "--1", "1e", "0x10", "1,5", "nan", "- 1"}) {
    CAPTURE(bad);
    std::string m = plain;
    m.replace(m.find("x=\"10\""), 6, fmt::format("\n x=\"{}\"", bad));
    auto got = load(m);
    REQUIRE_FALSE(got.ok());
    std::string e = got.error().to_string();
    CHECK(e.find("odd.3mf, 3D/3dmodel.model: line 2, object 1: vertex 1 has the coordinate x=\"" + bad +
                 "\", which is not a number") != std::string::npos);
    CHECK(e.find("export it again") != std::string::npos);
    m = plain;
    m.replace(m.find("v2=\"2\""), 6, fmt::format("v2=\"{}\"", bad));
    m.replace(m.find("<triangles>"), 0, "\n\n");
    got = load(m);
    REQUIRE_FALSE(got.ok());
    e = got.error().to_string();
    CHECK(e.find("line 3, object 1: triangle 0 has the vertex index v2=\"" + bad + "\", which is not a number") !=
          std::string::npos);
  }
  // Numbers the specification writes, which the scanner leaves to lib3mf: read.
  for (const std::string fine : {"+10", " 10 ", "1e1", "10.0", ".5e2"}) {
    CAPTURE(fine);
    std::string m = plain;
    m.replace(m.find("x=\"10\""), 6, fmt::format("x=\"{}\"", fine));
    CHECK(load(m).ok());
  }
  // In a comment, which lib3mf skips, nothing is refused.
  std::string commented = plain;
  commented.replace(commented.find("x=\"10\""), 6, "x=\"abc\"");
  commented = "<!-- " + commented + " -->" + plain;
  CHECK(load(commented).ok());
  CHECK(threemf::split_meshes(model("<object id=\"1\">" + reference + "</object>", "")).meshes.empty());
  const auto got = load(reference);
  REQUIRE_FALSE(got.ok());
  CHECK(got.error().to_string().find("odd.3mf") != std::string::npos);
  CHECK(got.error().to_string().find("cannot be read") != std::string::npos);
}

namespace {

// The x coordinates the scanner reads from `texts`, each the x of a vertex of one mesh (its own y,
// so that no two vertices are equal; each used, in order, by a triangle: the welder's order is
// the text's).
std::vector<float> scanned_x(const std::vector<std::string>& texts) {
  std::string v, t;
  for (size_t i = 0; i < texts.size(); ++i) {
    v += "<vertex x=\"" + texts[i] + "\" y=\"" + std::to_string(i) + "\" z=\"0\"/>";
    t += fmt::format("<triangle v1=\"{0}\" v2=\"{0}\" v3=\"{0}\"/>", i);
  }
  const std::string xml = model("<object id=\"1\" type=\"model\"><mesh><vertices>" + v + "</vertices><triangles>" +
                                    t + "</triangles></mesh></object>",
                                "<item objectid=\"1\"/>");
  const auto s = threemf::split_meshes(xml);
  REQUIRE(s.meshes.size() == 1);
  const auto& m = s.meshes.at(1);
  std::vector<float> out;
  for (const auto& p : m.vertices) out.push_back(static_cast<float>(p.x));
  return out;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("3mf meshes: numbers are read to the float std::from_chars reads, in every form") {
  std::vector<std::string> texts = {
      "0", "-0", "1", "-1.5", "19.000000", "18.998026", "0.125643", "5.", "007.250", "1e1", "1.5E-3",
      "-2.5e+2", "3.4028234e38", "1e-40",                   // a subnormal float: from_chars reads it
      "16777217", "16777219", "-16777217.00", "8388609.5",  // exactly halfway between two floats
      "0.1", "0.2", "0.3", "123456.789012345", "1234567890123456789", "0.000000000000000000001",
      "3.141592653589793238462643383279",
      // longer than the 16 bytes the scanner converts at once
      "1.0000000000000000000000000000000000000000000000001",
      "-12.50000000000000000000000000000000000000000000000",
      "0.000000000000000000000000000000000000100000000000000000000000000000"};
  std::mt19937 rng(1313);
  std::uniform_real_distribution<double> u(-500, 500);
  for (int i = 0; i < 3000; ++i) {
    const double d = u(rng);
    texts.push_back(fmt::format("{:.{}f}", d, i % 12));  // fixed, 0 to 11 decimals
    texts.push_back(fmt::format("{:.{}g}", d, 1 + i % 17));
    texts.push_back(fmt::format("{}", static_cast<float>(d)));  // shortest round trip
    // Within a few units of a double of a point halfway between two floats (15 digits), where a
    // double rounded twice could round the wrong way.
    const float f = static_cast<float>(d);
    const double half = (static_cast<double>(f) + std::nextafter(f, 1e9f)) / 2;
    texts.push_back(fmt::format("{:.{}g}", half, 13 + i % 3));
    texts.push_back(fmt::format("{:.{}f}", half, 9 + i % 3));
  }
  // Digit strings of every length up to 17, some signed, most with a point after any digit (the
  // scanner converts up to 16 bytes at once), zeros often.
  std::uniform_int_distribution<int> len(1, 17), digit(0, 9), coin(0, 3);
  for (int i = 0; i < 4000; ++i) {
    const int n = len(rng);
    const int point = coin(rng) == 0 ? n : std::uniform_int_distribution<int>(1, n)(rng);  // digits before it
    std::string t = coin(rng) == 0 ? "-" : "";
    for (int k = 0; k < n; ++k) {
      if (k == point) t += '.';
      t += static_cast<char>('0' + (coin(rng) == 0 ? 0 : digit(rng)));
    }
    if (point == n && coin(rng) == 0) t += '.';  // "5."
    texts.push_back(t);
  }
  // Every form the 16-byte conversion looks up (its length, where its point is, a sign or not),
  // and those around it, each with digits drawn several times: 1 to 16 digits, the point after
  // any of them or none, "5." too.
  for (int n = 1; n <= 16; ++n)
    for (int point = 1; point <= n + 1; ++point)  // digits before it; n + 1: "5."-like, n: none
      for (int minus = 0; minus < 2; ++minus)
        for (int draw = 0; draw < 6; ++draw) {
          std::string t = minus ? "-" : "";
          for (int k = 0; k < n; ++k) {
            if (k == point) t += '.';
            t += static_cast<char>('0' + (draw == 0 ? 9 : coin(rng) == 0 ? 0 : digit(rng)));
          }
          if (point == n + 1) t += '.';
          texts.push_back(t);
        }
  // With the CPU's SSSE3 instructions (where it has them) and without.
  for (const threemf::Simd simd : {threemf::Simd::kAvx2, threemf::Simd::kSsse3, threemf::Simd::kNone}) {
    CAPTURE(static_cast<int>(simd));
    threemf::limit_simd(simd);
    const std::vector<float> got = scanned_x(texts);
    threemf::limit_simd(threemf::Simd::kAvx2);
    REQUIRE(got.size() == texts.size());
    int wrong = 0;
    for (size_t i = 0; i < texts.size(); ++i) {
      float want = 0;
      const auto [end, ec] = std::from_chars(texts[i].data(), texts[i].data() + texts[i].size(), want);
      REQUIRE(ec == std::errc());
      REQUIRE(end == texts[i].data() + texts[i].size());
      if (want == 0) want = 0.0f;  // in the welder's order -0 is +0, as in every welded mesh
      if (!same_bits(got[i], want)) {
        if (++wrong < 10) MESSAGE(texts[i], ": ", got[i], " instead of ", want);
      }
    }
    CHECK(wrong == 0);
    CHECK(same_bits(got[1], 0.0f));  // "-0"
    CHECK(got[14] == 16777216.0f);   // halfway: to even
    CHECK(got[15] == 16777220.0f);
  }
}

TEST_CASE("3mf meshes: indices are read as std::from_chars reads them; too large ones are left to lib3mf") {
  auto indices = [](const std::string& v1) {
    const std::string xml = model("<object id=\"1\"><mesh><vertices><vertex x=\"0\" y=\"0\" z=\"0\"/><vertex x=\"1\" "
                                  "y=\"0\" z=\"0\"/><vertex x=\"0\" y=\"1\" z=\"0\"/></vertices><triangles><triangle "
                                  "v1=\"" + v1 + "\" v2=\"1\" v3=\"2\"/></triangles></mesh></object>",
                                  "<item objectid=\"1\"/>");
    return threemf::split_meshes(xml);
  };
  CHECK(indices("0").meshes.at(1).triangles == Triangles{{0, 1, 2}});
  CHECK(indices("0000").meshes.at(1).triangles == Triangles{{0, 1, 2}});
  for (const char* bad : {"4294967296", "99999999999999999999", "-0", "+0", "0x0", "", "1.0", " 0"}) {
    CAPTURE(bad);
    CHECK(indices(bad).meshes.empty());
  }
}

TEST_CASE("3mf meshes: unusual whitespace and attribute order are read the same") {
  const std::string plain = model(
      "<object id=\"3\"><mesh><vertices><vertex x=\"1\" y=\"2\" z=\"3\"/><vertex x=\"4\" y=\"5\" z=\"6\"/><vertex "
      "x=\"7\" y=\"8\" z=\"9\"/></vertices><triangles><triangle v1=\"0\" v2=\"1\" v3=\"2\"/></triangles></mesh></object>",
      "<item objectid=\"3\"/>");
  const std::string odd = model(
      "<object\n id = '3'\t>\r\n <mesh >\n\t<vertices\n>\n\t\t<vertex\n\t\t\tz = \"3\"  y='2'\r\n x=\"1\" />\n"
      "<vertex x=\"4\"\ty=\"5\"\nz=\"6\"/><vertex  x=\"7\"  y=\"8\"  z=\"9\"  /></vertices>\n<triangles>"
      "<triangle v3=\"2\" p1=\"0\" v1=\"0\" v2 = '1' />\n</triangles>\n</mesh></object>",
      "<item objectid=\"3\"/>");
  const auto a = threemf::split_meshes(plain), b = threemf::split_meshes(odd);
  REQUIRE(a.meshes.size() == 1);
  REQUIRE(b.meshes.size() == 1);
  CHECK(flat(a.meshes.at(3)) == flat(b.meshes.at(3)));
  CHECK(a.meshes.at(3).triangles == b.meshes.at(3).triangles);
  CHECK(flat(b.meshes.at(3)) == std::vector<float>{1, 2, 3, 4, 5, 6, 7, 8, 9});
  // With a comment among the vertices, the mesh is left to lib3mf, which reads the same.
  std::string spaced = odd;
  spaced.replace(spaced.find("</vertices>"), 0, "<!-- lib3mf's -->");
  REQUIRE(threemf::split_meshes(spaced).meshes.empty());
  Report report;
  auto fast = tranche::plate::parse_3mf(package(odd), "odd.3mf", report);
  auto slow = tranche::plate::parse_3mf(package(spaced), "odd.3mf", report);
  REQUIRE_MESSAGE(fast.ok(), fast.error().to_string());
  REQUIRE_MESSAGE(slow.ok(), slow.error().to_string());
  REQUIRE(fast->size() == 1);
  REQUIRE(slow->size() == 1);
  CHECK((*fast)[0].mesh.triangles == (*slow)[0].mesh.triangles);
  REQUIRE((*fast)[0].mesh.vertices.size() == 3);
  REQUIRE((*slow)[0].mesh.vertices.size() == 3);
  for (size_t i = 0; i < 3; ++i) {
    CHECK((*fast)[0].mesh.vertices[i].x == (*slow)[0].mesh.vertices[i].x);
    CHECK((*fast)[0].mesh.vertices[i].z == (*slow)[0].mesh.vertices[i].z);
  }
}

TEST_CASE("3mf meshes: many objects are read in order, as one pass would read them") {
  // 40 objects (more than are read ahead at once); object 5's mesh holds, in an attribute value,
  // the text of an object 77 with a mesh (passed over: it is inside a mesh read); object 9 is
  // given twice (the second left to lib3mf); an object tag never closed ends the reading.
  std::string resources;
  for (int id = 1; id <= 40; ++id) {
    std::string mesh = box_mesh(id, 1, 1);
    if (id == 5)
      mesh.replace(mesh.find("<triangle ") + 9, 0,
                   " p1='<object id=\"77\"><mesh><vertices><vertex x=\"0\" y=\"0\" z=\"0\"/><vertex x=\"1\" y=\"0\" "
                   "z=\"0\"/><vertex x=\"0\" y=\"1\" z=\"0\"/></vertices><triangles><triangle v1=\"0\" v2=\"1\" "
                   "v3=\"2\"/></triangles></mesh></object>'");
    resources += fmt::format("<object id=\"{}\" type=\"model\">{}</object>", id, mesh);
    if (id == 20) resources += "<object id=\"9\" type=\"model\">" + box_mesh(99, 1, 1) + "</object>";
  }
  const auto s = threemf::split_meshes(model(resources, "<item objectid=\"1\"/>"));
  REQUIRE(s.meshes.size() == 40);
  for (int id = 1; id <= 40; ++id) {
    CAPTURE(id);
    REQUIRE(s.meshes.count(id));
    const auto f = flat(s.meshes.at(id));
    CHECK(*std::max_element(f.begin(), f.end()) ==
          static_cast<float>(std::max(id, 1)));
    CHECK(s.meshes.at(id).triangles.size() == 12);
  }
  CHECK_FALSE(s.meshes.count(77));
  CHECK(s.model.find("x=\"99\"") != std::string::npos);  // the second object 9, left in place
  CHECK(s.model.find("object id=\"77\"") == std::string::npos);  // gone with object 5's mesh

  auto box_object = [](int id) {
    return fmt::format("<object id=\"{}\" type=\"model\">{}</object>", id, box_mesh(1, 1, 1));
  };
  const std::string cut = model(box_object(1) + "<object id=\"2\" name=\"never closed" + box_object(3), "");
  const auto c = threemf::split_meshes(cut);
  CHECK(c.meshes.size() == 1);
  CHECK(c.meshes.count(1));
}

namespace {

// split_meshes_streamed on `xml` handed over in pieces of at most `piece` bytes.
std::optional<threemf::SplitModel> streamed(const std::string& xml, size_t piece) {
  size_t at = 0;
  return threemf::split_meshes_streamed([&](char* out, size_t n) -> std::optional<size_t> {
    const size_t k = std::min({n, piece, xml.size() - at});
    std::memcpy(out, xml.data() + at, k);
    at += k;
    return k;
  });
}

// split_meshes_streamed on `xml` handed over in chunks of `piece` bytes (the last shorter), each
// in memory of its own with the room the Chunks interface promises before it; every chunk given
// back, and none given back twice.
std::optional<threemf::SplitModel> chunked(const std::string& xml, size_t piece) {
  struct Fake : threemf::Chunks {
    const std::string& xml;
    size_t piece, at = 0;
    std::map<char*, std::unique_ptr<char[]>> out;
    Fake(const std::string& x, size_t p) : xml(x), piece(p) {}
    std::optional<Chunk> next() override {
      const size_t k = std::min(piece, xml.size() - at);
      if (k == 0) return Chunk{};
      auto memory = std::make_unique<char[]>(kRoom + k);
      std::memcpy(memory.get() + kRoom, xml.data() + at, k);
      at += k;
      char* data = memory.get();
      out.emplace(data, std::move(memory));
      return Chunk{data, k};
    }
    void give_back(char* data) override { CHECK(out.erase(data) == 1); }
  } fake(xml, piece);
  auto s = threemf::split_meshes_streamed(fake);
  CHECK(fake.out.empty());
  return s;
}

// Whether two splits are the same: the same model text, the same meshes bit for bit.
bool same_split(const threemf::SplitModel& a, const threemf::SplitModel& b) {
  if (a.model != b.model || a.meshes.size() != b.meshes.size()) return false;
  for (const auto& [id, m] : a.meshes) {
    const auto it = b.meshes.find(id);
    if (it == b.meshes.end() || m.triangles != it->second.triangles ||
        m.vertices.size() != it->second.vertices.size() ||
        std::memcmp(m.vertices.data(), it->second.vertices.data(), m.vertices.size() * sizeof(m.vertices[0])) != 0)
      return false;
  }
  return true;
}

// The mesh of a torus of n × n/2 vertices as a 3MF writer writes it: several MiB of text for a few hundred n.
std::string torus_mesh(int n) {
  const geo::Mesh t = geo::torus(20, 5, n, n / 2);
  std::string out = "<mesh>\n <vertices>\n";
  for (const auto& v : t.vertices) out += fmt::format("  <vertex x=\"{}\" y=\"{}\" z=\"{}\" />\n", v.x, v.y, v.z);
  out += " </vertices>\n <triangles>\n";
  for (const auto& f : t.triangles) out += fmt::format("  <triangle v1=\"{}\" v2=\"{}\" v3=\"{}\" />\n", f[0], f[1], f[2]);
  return out + " </triangles>\n</mesh>";
}

}  // namespace

TEST_CASE("3mf meshes: the part read in a stream splits as the whole text does") {
  // Small models (the whole text in one window) and large ones (many windows, with objects,
  // components and build items between meshes), handed over in pieces of every size.
  std::vector<std::string> texts;
  texts.push_back(model("<object id=\"7\" type=\"model\">" + box_mesh(1, 2, 3) +
                            "</object><object id=\"8\"><components><component objectid=\"7\"/></components></object>",
                        "<item objectid=\"8\"/>"));
  texts.push_back(model("<object\n id = '3'\t>\r\n <mesh >\n\t<vertices\n>\n\t\t<vertex\n\t\t\tz = \"3\"  y='2'\r\n "
                        "x=\"1\" />\n<vertex x=\"4\"\ty=\"5\"\nz=\"6\"/><vertex  x=\"7\"  y=\"8\"  z=\"9\"  /></vertices>"
                        "\n<triangles><triangle v3=\"2\" p1=\"0\" v1=\"0\" v2 = '1' />\n</triangles>\n</mesh></object>",
                        "<item objectid=\"3\"/>"));
  std::string resources;
  for (int id = 1; id <= 40; ++id) {
    resources += fmt::format("<object id=\"{}\" type=\"model\">{}</object>", id, box_mesh(id, 1, 1));
    if (id == 20) resources += "<object id=\"9\" type=\"model\">" + box_mesh(99, 1, 1) + "</object>";  // taken
  }
  texts.push_back(model(resources, "<item objectid=\"1\"/>"));
  texts.push_back(model(fmt::format("<object id=\"1\">{}</object><object id=\"2\" name=\"never closed<object id=\"3\">{}",
                                    box_mesh(1, 1, 1), box_mesh(1, 1, 1)),
                        ""));
  // Large: three tori of several MiB each, a components object between them, a small box whose
  // mesh lib3mf is left (a comment in it) at the end.
  const std::string big = torus_mesh(300);
  REQUIRE(big.size() > (size_t{3} << 20));
  std::string commented = box_mesh(1, 1, 1);
  commented.replace(commented.find("<vertices>"), 10, "<vertices><!-- lib3mf's -->");
  texts.push_back(model("<object id=\"1\" type=\"model\">" + big +
                            "</object>\n<object id=\"2\"><components><component objectid=\"1\"/></components></object>"
                            "<object id=\"3\" name=\"b\">" + big + "</object><object id=\"4\">" + big +
                            "</object><object id=\"5\">" + commented + "</object>",
                        "<item objectid=\"2\"/><item objectid=\"3\"/><item objectid=\"4\"/><item objectid=\"5\"/>"));
  for (size_t t = 0; t < texts.size(); ++t) {
    const threemf::SplitModel whole = threemf::split_meshes(texts[t]);
    REQUIRE(!whole.meshes.empty());
    for (size_t piece : {size_t{1}, size_t{7}, size_t{4093}, size_t{1} << 20, size_t{3} << 20}) {
      if (piece == 1 && texts[t].size() > (size_t{1} << 20)) continue;  // a byte at a time: small texts only
      CAPTURE(t);
      CAPTURE(piece);
      const auto s = streamed(texts[t], piece);
      REQUIRE(s);
      CHECK(same_split(*s, whole));
      // Chunks shorter than the window's look-ahead are joined by copying: small texts only.
      if (piece < 4093 && texts[t].size() > (size_t{64} << 10)) continue;
      const auto c = chunked(texts[t], piece);
      REQUIRE(c);
      CHECK(same_split(*c, whole));
    }
  }
  CHECK(threemf::split_meshes(texts.back()).meshes.size() == 3);
}

TEST_CASE("3mf meshes: where the stream cannot say what the whole text gives, it gives up") {
  const std::string big = torus_mesh(300);
  auto one = [](const std::string& mesh) { return model("<object id=\"1\">" + mesh + "</object>", "<item objectid=\"1\"/>"); };
  // A mesh left to lib3mf found after the window moved on: the text before it is gone.
  std::string late = big;
  late.replace(late.rfind("<triangle "), 0, "<!-- lib3mf's -->");
  CHECK(threemf::split_meshes(one(late)).meshes.empty());
  CHECK_FALSE(streamed(one(late), 4093));
  // An element longer than the whole window (a little over 1 MiB).
  std::string wide = big;
  wide.replace(wide.find("<vertex ") + 7, 0, std::string(size_t{1200} << 10, ' '));
  REQUIRE(threemf::split_meshes(one(wide)).meshes.size() == 1);  // read whole: the spaces are allowed
  CHECK_FALSE(streamed(one(wide), 1 << 20));
  // Text that cannot be read.
  size_t calls = 0;
  CHECK_FALSE(threemf::split_meshes_streamed([&](char*, size_t) -> std::optional<size_t> {
    ++calls;
    return std::nullopt;
  }));
  CHECK(calls == 1);
  // No mesh at all: nothing, as split_meshes.
  const auto none = streamed(model("<object id=\"1\"><components/></object>", ""), 100);
  REQUIRE(none);
  CHECK(none->meshes.empty());
  CHECK(none->model.empty());
}

TEST_CASE("3mf meshes: a large model part loads the same streamed, read whole, and through lib3mf") {
  // Past the size from which the part is inflated ahead on a second thread (4 MiB). The same model
  // with a comment in its last mesh's triangles: the stream gives up there, the part is read
  // whole, and lib3mf reads that mesh.
  const std::string big = torus_mesh(300);
  const std::string box = box_mesh(10, 20, 5, 60);
  const std::string plain = model("<object id=\"1\" name=\"torus\">" + big + "</object><object id=\"2\" name=\"box\">" + box +
                                      "</object>",
                                  "<item objectid=\"1\"/><item objectid=\"2\" transform=\"1 0 0 0 1 0 0 0 1 0 0 3\"/>");
  std::string commented = plain;
  commented.replace(commented.rfind("<triangle "), 0, "<!-- lib3mf's -->");
  std::string late_torus = plain;  // the torus's own mesh left to lib3mf, found late
  late_torus.replace(late_torus.find("</triangles>"), 0, "<!-- lib3mf's -->");
  REQUIRE(plain.size() > (size_t{4} << 20));
  Report report;
  auto a = tranche::plate::parse_3mf(package(plain), "big.3mf", report);
  REQUIRE_MESSAGE(a.ok(), a.error().to_string());
  REQUIRE(a->size() == 2);
  for (const std::string& other : {commented, late_torus}) {
    for (bool stored : {false, true}) {
      CAPTURE(stored);
      auto b = tranche::plate::parse_3mf(package(other, {}, stored), "big.3mf", report);
      REQUIRE_MESSAGE(b.ok(), b.error().to_string());
      REQUIRE(b->size() == 2);
      for (size_t i = 0; i < 2; ++i) {
        CAPTURE(i);
        CHECK((*a)[i].name == (*b)[i].name);
        CHECK((*a)[i].transform.matrix() == (*b)[i].transform.matrix());
        CHECK((*a)[i].mesh.triangles == (*b)[i].mesh.triangles);
        const auto &av = (*a)[i].mesh.vertices, &bv = (*b)[i].mesh.vertices;
        REQUIRE(av.size() == bv.size());
        size_t differ = 0;
        for (size_t k = 0; k < av.size(); ++k) differ += !(av[k].x == bv[k].x && av[k].y == bv[k].y && av[k].z == bv[k].z);
        CHECK(differ == 0);
      }
    }
  }
  CHECK((*a)[0].mesh.triangles.size() == geo::torus(20, 5, 300, 150).triangles.size());
  CHECK(report.empty());
}

TEST_CASE("3mf meshes: changed large texts: the stream gives the whole text's split, or gives up") {
  // A text over several windows, changed at random places (a digit, spaces after a tag, or any of
  // the characters the scanner looks at): wherever the change falls (near a window's edge or
  // not), a split the stream returns is the one split_meshes returns.
  const std::string base = model("<object id=\"1\">" + torus_mesh(200) + "</object><object id=\"2\"><components>"
                                 "<component objectid=\"1\"/></components></object><object id=\"3\">" +
                                     torus_mesh(200) + "</object>",
                                 "<item objectid=\"2\"/><item objectid=\"3\"/>");
  REQUIRE(base.size() > (size_t{3} << 20));
  std::mt19937 rng(2613);
  const std::string alphabet = "<>/\"'= .-e0123456789jx!?";
  int gave_up = 0, same = 0;
  for (int round = 0; round < 40; ++round) {
    std::string text = base;
    const int edits = 1 + round % 3;
    for (int k = 0; k < edits; ++k) {
      // Near the 1 MiB steps the window moves by, half the time; anywhere, the other half.
      size_t at = rng() % text.size();
      if (round % 2) at = std::min(text.size() - 1, ((rng() % 3) + 1) * (size_t{1} << 20) - 64 + rng() % 128);
      switch (rng() % 3) {
        case 0:  // a digit changed: still a mesh, other values
          at = text.find_first_of("0123456789", at);
          if (at != std::string::npos) text[at] = static_cast<char>('0' + rng() % 10);
          break;
        case 1:  // spaces after a tag: still the same mesh
          at = text.find('>', at);
          if (at != std::string::npos) text.insert(at + 1, std::string(1 + rng() % 300, rng() % 2 ? ' ' : '\n'));
          break;
        default: {  // anything
          const char c = alphabet[rng() % alphabet.size()];
          if (rng() % 2) text[at] = c;
          else text.insert(at, 1, c);
        }
      }
    }
    CAPTURE(round);
    const auto s = streamed(text, 65521);
    if (!s) {
      ++gave_up;
      continue;
    }
    CHECK(same_split(*s, threemf::split_meshes(text)));
    ++same;
  }
  MESSAGE(same, " changed texts split the same streamed, ", gave_up, " given up");
  CHECK(same >= 10);
}

TEST_CASE("3mf meshes: a large model part damaged half-way is refused, streamed or not") {
  // The stream (inflated ahead on a second thread) fails after reading part of the meshes; the
  // part is then read whole, which fails too, and says how. (lib3mf, which checks no CRC, read
  // such a part as XML and blamed an attribute.)
  const std::string plain =
      model("<object id=\"1\" name=\"torus\">" + torus_mesh(300) + "</object>", "<item objectid=\"1\"/>");
  const std::string good = package(plain);
  const size_t at = good.find("3D/3dmodel.model");
  REQUIRE(at != std::string::npos);
  Report report;
  REQUIRE(tranche::plate::parse_3mf(good, "big.3mf", report).ok());
  for (size_t where : {size_t{2}, size_t{3}}) {  // half-way and two thirds into the archive
    std::string bad = good;
    for (size_t k = 0; k < 64; ++k) bad[bad.size() * (where - 1) / where + k] ^= 0x5a;
    CAPTURE(where);
    auto r = tranche::plate::parse_3mf(bad, "big.3mf", report);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().to_string().find("big.3mf, 3D/3dmodel.model") != std::string::npos);
    CHECK(r.error().to_string().find("the ZIP entry is damaged or truncated") != std::string::npos);
  }
}

namespace {

// A mesh of `nv` vertices and `nt` triangles written in the many ways a writer may: mostly the
// plain form (`<vertex x=".." y=".." z=".." />`, read whole with AVX2 where the CPU has it), with
// spaces of every kind and length between elements, `/>` and ` />`, indices with leading zeros
// (up to ten digits), coordinates of every form (exponents, a leading '+', long mantissas, -0),
// and now and then an element in another form (attributes in another order, single quotes,
// spaces around '=', another attribute). `damage`: one byte of the elements changed at random.
std::string random_mesh(std::mt19937& rng, int nv, int nt, bool damage) {
  const auto pick = [&](int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); };
  static const char* kGaps[] = {"",       "\n",   "\n\t\t\t\t\t",         " ",
                                "\r\n\t", "\t\t", "                    ", "\n  "};
  const auto gap = [&] { return std::string(kGaps[pick(8)]); };
  std::uniform_real_distribution<double> u(-300, 300);
  const auto coordinate = [&]() -> std::string {
    switch (pick(12)) {
      case 0:
        return "0";
      case 1:
        return "-0";
      case 2:
        return fmt::format("{:.3e}", u(rng));
      case 3:
        return pick(40) == 0 ? fmt::format("+{:.2f}", std::fabs(u(rng))) : "1.5E-2";  // '+': left to lib3mf
      case 4:
        return fmt::format("{:.17f}", u(rng));  // longer than 16 bytes
      case 5:
        return fmt::format("{}", static_cast<float>(u(rng)));
      default:
        return fmt::format("{:.{}f}", u(rng), pick(9));
    }
  };
  const auto index = [&](int i) {
    std::string s = std::to_string(i);
    return std::string(pick(4) == 0 ? pick(10 - std::min<int>(9, static_cast<int>(s.size()))) : 0, '0') + s;
  };
  const auto tail = [&] { return pick(3) == 0 ? "/>" : " />"; };
  std::string out = "<mesh>" + gap() + "<vertices>";
  for (int i = 0; i < nv; ++i) {
    out += gap();
    const std::string x = coordinate(), y = coordinate(), z = coordinate();
    switch (pick(20)) {
      case 0:
        out += fmt::format("<vertex y=\"{}\" x=\"{}\" z=\"{}\" />", y, x, z);
        break;
      case 1:
        out += fmt::format("<vertex x='{}' y='{}' z='{}'/>", x, y, z);
        break;
      case 2:
        out += fmt::format("<vertex x = \"{}\" y=\"{}\" z=\"{}\"/>", x, y, z);
        break;
      default:
        out += fmt::format("<vertex x=\"{}\" y=\"{}\" z=\"{}\"{}", x, y, z, tail());
        break;
    }
  }
  out += gap() + "</vertices>" + gap() + "<triangles>";
  for (int i = 0; i < nt; ++i) {
    out += gap();
    const std::string a = index(pick(nv)), b = index(pick(nv)), c = index(pick(nv));
    switch (pick(20)) {
      case 0:
        out += fmt::format("<triangle v2=\"{}\" v1=\"{}\" v3=\"{}\" />", b, a, c);
        break;
      case 1:
        out += fmt::format("<triangle v1=\"{}\" v2=\"{}\" v3=\"{}\" p1=\"0\"/>", a, b, c);
        break;
      case 2:
        out += fmt::format("<triangle v1='{}' v2='{}' v3='{}'/>", a, b, c);
        break;
      default:
        out += fmt::format("<triangle v1=\"{}\" v2=\"{}\" v3=\"{}\"{}", a, b, c, tail());
        break;
    }
  }
  out += gap() + "</triangles>" + gap() + "</mesh>";
  if (damage) {
    static const char kBytes[] = {'a', '"', '<', '>', ' ', '-', '.', '9', '\'', '/', '=', '\n', 'e'};
    const size_t first = out.find("<vertex"), last = out.rfind("</triangles>");
    out[first + std::uniform_int_distribution<size_t>(0, last - first - 1)(rng)] =
        kBytes[pick(sizeof kBytes)];
  }
  return out;
}

}  // namespace

TEST_CASE("3mf meshes: elements read whole with AVX2 give what reading them one attribute at a time gives") {
  // The same texts read at each level of vector instructions (threemf::limit_simd): the same meshes
  // bit for bit, the same meshes left to lib3mf, the same values refused (and the same words),
  // read whole or streamed. Texts damaged at one byte included: what each level then reads,
  // leaves or refuses is the same.
  std::mt19937 rng(1339);
  int read = 0, damaged_read = 0, refused = 0;
  for (int k = 0; k < 160; ++k) {
    CAPTURE(k);
    const bool damage = k % 2 == 1;
    const int nv = std::uniform_int_distribution<int>(3, 300)(rng);
    const int nt = std::uniform_int_distribution<int>(1, 500)(rng);
    const std::string xml =
        model(fmt::format("<object id=\"4\" type=\"model\">{}</object>", random_mesh(rng, nv, nt, damage)),
              "<item objectid=\"4\"/>");
    threemf::limit_simd(threemf::Simd::kNone);
    const threemf::SplitModel plain = threemf::split_meshes(xml);
    const auto plain_streamed = streamed(xml, 4093);
    threemf::limit_simd(threemf::Simd::kSsse3);
    const threemf::SplitModel ssse3 = threemf::split_meshes(xml);
    threemf::limit_simd(threemf::Simd::kAvx2);
    const threemf::SplitModel avx2 = threemf::split_meshes(xml);
    const auto avx2_streamed = streamed(xml, 4093);
    CHECK(same_split(plain, avx2));
    CHECK(same_split(plain, ssse3));
    CHECK(plain.bad == avx2.bad);
    CHECK(plain.bad == ssse3.bad);
    CHECK(plain_streamed.has_value() == avx2_streamed.has_value());
    if (plain_streamed && avx2_streamed) CHECK(same_split(*plain_streamed, *avx2_streamed));
    if (!avx2.meshes.empty()) ++(damage ? damaged_read : read);
    refused += !avx2.bad.empty();
  }
  // Most undamaged texts are read (some hold a '+' coordinate, which leaves the mesh to lib3mf);
  // damage leaves some to lib3mf, and some of them are refused.
  CHECK(read > 10);
  CHECK(damaged_read > 2);
  CHECK(refused > 5);
  MESSAGE("read ", read, " of 80 texts, ", damaged_read, " of 80 damaged ones; ", refused, " refused");
}

TEST_CASE("3mf meshes: indices of every length read whole with AVX2 are those std::from_chars reads") {
  // 3000 vertices, triangles whose indices have 1 to 10 digits (leading zeros), in the plain form
  // between spaces of every kind: the triangles read are the indices written.
  std::mt19937 rng(2024);
  const int nv = 3000;
  std::string v, t;
  for (int i = 0; i < nv; ++i)
    v += fmt::format("\n<vertex x=\"{}\" y=\"{}.5\" z=\"-{}\" />", i, i % 7, i % 11);
  Triangles want;
  std::vector<std::string> written;
  for (int i = 0; i < 6000; ++i) {
    std::array<uint32_t, 3> tri{};
    std::string text[3];
    for (int k = 0; k < 3; ++k) {
      tri[k] = std::uniform_int_distribution<uint32_t>(0, nv - 1)(rng);
      const std::string digits = std::to_string(tri[k]);
      text[k] = std::string(std::uniform_int_distribution<size_t>(0, 10 - digits.size())(rng), '0') + digits;
      uint32_t back = 0;
      REQUIRE(std::from_chars(text[k].data(), text[k].data() + text[k].size(), back).ec == std::errc());
      REQUIRE(back == tri[k]);
    }
    want.push_back(tri);
    t += fmt::format("{}<triangle v1=\"{}\" v2=\"{}\" v3=\"{}\"{}",
                     i % 3 == 0   ? "\n\t\t"
                     : i % 3 == 1 ? ""
                                  : " ",
                     text[0], text[1], text[2], i % 5 == 0 ? "/>" : " />");
  }
  const std::string xml = model(
      "<object id=\"1\"><mesh><vertices>" + v + "</vertices><triangles>" + t + "</triangles></mesh></object>",
      "<item objectid=\"1\"/>");
  for (const threemf::Simd simd : {threemf::Simd::kAvx2, threemf::Simd::kNone}) {
    CAPTURE(static_cast<int>(simd));
    threemf::limit_simd(simd);
    const auto s = threemf::split_meshes(xml);
    threemf::limit_simd(threemf::Simd::kAvx2);
    REQUIRE(s.meshes.size() == 1);
    // In the welder's order the vertices are numbered by first use; x of each is its index written.
    const auto& m = s.meshes.at(1);
    REQUIRE(m.triangles.size() == want.size());
    int wrong = 0;
    for (size_t i = 0; i < want.size(); ++i)
      for (int k = 0; k < 3; ++k) wrong += m.vertices[m.triangles[i][k]].x != static_cast<double>(want[i][k]);
    CHECK(wrong == 0);
  }
}

TEST_CASE("3mf meshes: a mesh whose arrays take huge pages is read as the whole text reads it") {
  // 116 000 vertices and twice as many triangles: each of the mesh's arrays over 2 MiB. Room that
  // malloc has just mapped is taken again, rounded to whole 2 MiB of mapped memory (huge pages for
  // what the elements fill); room used before (as in this test's process, most often) is kept as
  // it was reserved. The meshes are those the whole text gives either way, and the room is one
  // of the two, never more than 2 MiB beyond the elements.
  const std::string text =
      model("<object id=\"1\">" + torus_mesh(482) + "</object>", "<item objectid=\"1\"/>");
  const threemf::SplitModel whole = threemf::split_meshes(text);
  constexpr size_t kHuge = size_t{2} << 20;
  for (int read = 0; read < 3; ++read) {
    CAPTURE(read);
    const auto c = chunked(text, size_t{1} << 20);
    REQUIRE(c);
    REQUIRE(c->meshes.size() == 1);
    CHECK(same_split(*c, whole));
    const threemf::MeshData& m = c->meshes.at(1);
    const size_t nv = m.vertices.size(), nt = m.triangles.size();
    REQUIRE(nv * sizeof(m.vertices[0]) > kHuge);
    REQUIRE(nt * sizeof(m.triangles[0]) > kHuge);
    // Reserved: nv vertices and 2 nv + 1 triangles; or rounded: the room and malloc's header (64
    // bytes) whole 2 MiB but for less than one element.
    const auto as_reserved_or_rounded = [&](size_t capacity, size_t reserved, size_t element) {
      const size_t room = capacity * element + 64;
      return capacity == reserved || (capacity > reserved && room - reserved * element < kHuge + 64 &&
                                      (room % kHuge == 0 || kHuge - room % kHuge < element));
    };
    CHECK(as_reserved_or_rounded(m.vertices.capacity(), nv, sizeof(m.vertices[0])));
    CHECK(as_reserved_or_rounded(m.triangles.capacity(), 2 * nv + 1, sizeof(m.triangles[0])));
  }
}
