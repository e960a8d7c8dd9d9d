#include <doctest/doctest.h>

#include <string>

#include "geometry/mesh/stl.h"
#include "tests/geometry/mesh/stl_helpers.h"

using namespace tranche;
using namespace tranche::test::stl;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// One facet with the given body lines between `facet normal ...` and `endfacet`.
std::string facet(const std::string& normal, const std::string& body) {
  return "facet normal " + normal + "\n outer loop\n" + body + " endloop\nendfacet\n";
}
const std::string kV = "  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n";  // normal (0, 0, 1)

}  // namespace

TEST_CASE("ASCII: a generated cube loads, welds and keeps its name") {
  Report report;
  auto m = parse(ascii_stl(cube(2, 0.5f), "my part"), report, "p.stl");
  REQUIRE_MESSAGE(m.ok(), m.error().to_string());
  CHECK(report.empty());
  CHECK(m->name == "my part");
  CHECK(m->vertices.size() == 8);
  CHECK(m->triangles.size() == 12);
  CHECK(m->volume() == doctest::Approx(0.125));
  CHECK(m->bbox().min.x == 2.0);
  CHECK(m->bbox().max.z == 2.5);
}

TEST_CASE("ASCII and binary of the same model give identical meshes") {
  auto tris = cube(-1.3f, 0.7f);
  Report report;
  auto a = parse(ascii_stl(tris), report);
  auto b = parse(binary_stl(tris), report);
  REQUIRE(a.ok());
  REQUIRE(b.ok());
  REQUIRE(a->vertices.size() == b->vertices.size());
  for (size_t i = 0; i < a->vertices.size(); ++i) {
    CHECK(a->vertices[i].x == b->vertices[i].x);
    CHECK(a->vertices[i].y == b->vertices[i].y);
    CHECK(a->vertices[i].z == b->vertices[i].z);
  }
  CHECK(a->triangles == b->triangles);
}

TEST_CASE("ASCII: CRLF, tabs, mixed-case keywords, '+' signs and exponents are accepted silently") {
  std::string s = ascii_stl(cube(), "crlf", "\r\n");
  s.replace(s.find("facet"), 5, "FaCeT");
  s.replace(s.find("outer loop"), 10, "OUTER Loop");
  s.replace(s.find("endsolid"), 8, "ENDSOLID");
  for (auto& c : s) {
    if (c == ' ') c = '\t';
  }
  Report report;
  auto m = parse(s, report);
  REQUIRE_MESSAGE(m.ok(), m.error().to_string());
  CHECK(report.empty());
  CHECK(m->triangles.size() == 12);
  CHECK(m->name == "crlf");

  auto exps =
      parse("solid e\n" + facet("+0e0 0E+00 1.0e-0", "vertex +0 0 0\nvertex 1e0 0 0\nvertex 0 .1e1 0\n") +
                "endsolid e\n",
            report);
  REQUIRE_MESSAGE(exps.ok(), exps.error().to_string());
  CHECK(exps->vertices[1].x == 1.0);
  CHECK(exps->vertices[2].y == 1.0);
  CHECK(report.empty());
}

TEST_CASE("ASCII: byte order mark, leading blank lines, lone CR line ends") {
  Report report;
  auto bom = parse("\xEF\xBB\xBF\n\n  solid bom\n" + facet("0 0 1", kV) + "endsolid bom\n", report);
  REQUIRE_MESSAGE(bom.ok(), bom.error().to_string());
  CHECK(bom->name == "bom");
  std::string mac = "solid mac\r" + facet("0 0 1", kV) + "endsolid mac\r";
  for (auto& c : mac) {
    if (c == '\n') c = '\r';
  }
  auto m = parse(mac, report);
  REQUIRE(m.ok());
  CHECK(m->name == "mac");
  // Lines still count with lone CRs: the garbage is on line 3.
  std::string bad = "solid mac\rfacet normal 0 0 1\router lop\r";
  CHECK(has(error_of(bad, "mac.stl"), "mac.stl:3: expected 'loop' after 'outer', found 'lop'"));
  CHECK(report.empty());
}

TEST_CASE("ASCII: minified on one line, nameless solids, several solids in one file") {
  Report report;
  std::string one_line =
      "solid tiny facet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 0 0 vertex 0 1 0 endloop "
      "endfacet endsolid tiny";
  auto m = parse(one_line, report);
  REQUIRE_MESSAGE(m.ok(), m.error().to_string());
  CHECK(m->name == "tiny");
  CHECK(m->triangles.size() == 1);

  auto nameless = parse("solid\n" + facet("0 0 1", kV) + "endsolid\n", report, "dir/stem.stl");
  REQUIRE(nameless.ok());
  CHECK(nameless->name == "stem");

  const std::string two = "solid a\n" + facet("0 0 1", kV) + "endsolid a\nsolid b\n" +
                          facet("0 0 1", "vertex 5 5 5\nvertex 6 5 5\nvertex 5 6 5\n") + "endsolid b\n";
  auto merged = parse(two, report);
  REQUIRE(merged.ok());
  CHECK(merged->triangles.size() == 2);
  CHECK(merged->vertices.size() == 6);
  CHECK(merged->name == "a");
  CHECK(report.empty());
}

TEST_CASE("ASCII warnings: normals, names, trailing text") {
  SUBCASE("normal that disagrees with the winding") {
    Report report;
    auto m = parse("solid w\n" + facet("0 0 1", kV) + facet("0 0 1", kV) + facet("0 0 -1", kV) +
                       facet("0 0 0", kV) + "endsolid w\n",
                   report, "w.stl");
    REQUIRE(m.ok());
    REQUIRE(report.count("stl-normal") == 1);
    CHECK(report.size() == 1);
    CHECK(report.warnings()[0].where == "w.stl:16");
    CHECK(has(report.warnings()[0].message, "1 of 4 facets have a normal that disagrees"));
  }
  SUBCASE("missing and NaN normals") {
    Report report;
    auto m = parse("solid w\nfacet normal\nouter loop\n" + kV + "endloop\nendfacet\n" +
                       facet("NaN NaN NaN", kV) + facet("nan inf 0", kV) + "endsolid w\n",
                   report, "n.stl");
    REQUIRE_MESSAGE(m.ok(), m.error().to_string());
    CHECK(report.count("stl-normal") == 2);
    const auto ws = report.warnings();
    CHECK(ws[0].where == "n.stl:2");
    CHECK(has(ws[0].message, "1 facet without normal values"));
    CHECK(ws[1].where == "n.stl:9");
    CHECK(has(ws[1].message, "2 facets with a normal that is not a finite number"));
  }
  SUBCASE("endsolid name mismatch") {
    Report report;
    auto m =
        parse("solid tetra hedron\n" + facet("0 0 1", kV) + "endsolid something else\n", report, "x.stl");
    REQUIRE(m.ok());
    CHECK(m->name == "tetra hedron");
    REQUIRE(report.count("stl-name") == 1);
    CHECK(report.warnings()[0].where == "x.stl:9");
    CHECK(has(report.warnings()[0].message, "'endsolid something else' does not match 'solid tetra hedron'"));
  }
  SUBCASE("text after endsolid") {
    Report report;
    auto m = parse("solid t\n" + facet("0 0 1", kV) + "endsolid t\n\nthanks for printing\n", report, "x.stl");
    REQUIRE(m.ok());
    REQUIRE(report.count("stl-trailing") == 1);
    CHECK(report.warnings()[0].where == "x.stl:11");
  }
  SUBCASE("degenerate facet") {
    Report report;
    auto m = parse("solid t\n" + facet("0 0 1", kV) +
                       facet("0 0 0", "vertex 1 1 1\nvertex 1 1 1\nvertex 0 0 0\n") + "endsolid t\n",
                   report, "d.stl");
    REQUIRE(m.ok());
    CHECK(m->triangles.size() == 1);
    CHECK(m->vertices.size() == 3);
    REQUIRE(report.count("stl-degenerate") == 1);
    CHECK(report.warnings()[0].where == "d.stl:9");
  }
}

TEST_CASE("ASCII errors name the file, the line and the problem") {
  const std::string head = "solid t\n";
  const std::string good = facet("0 0 1", kV);  // lines 2-8
  SUBCASE("facet with 2 vertices") {
    const std::string e =
        error_of(head + good + facet("0 0 1", "vertex 0 0 0\nvertex 1 0 0\n") + "endsolid t\n", "f.stl");
    CHECK(has(e, "f.stl:9: facet has 2 vertices, an STL facet needs exactly 3"));
  }
  SUBCASE("facet with 4 vertices") {
    const std::string e = error_of(head + facet("0 0 1", kV + "vertex 1 1 0\n") + "endsolid t\n", "f.stl");
    CHECK(has(e, "f.stl:2: facet has 4 vertices, an STL facet needs exactly 3"));
  }
  SUBCASE("outer loop without endloop") {
    const std::string e =
        error_of(head + "facet normal 0 0 1\nouter loop\n" + kV + "endfacet\nendsolid t\n", "f.stl");
    CHECK(has(e, "f.stl:7: 'outer loop' at line 3 has no 'endloop' (found 'endfacet')"));
  }
  SUBCASE("missing endsolid") {
    const std::string e = error_of(head + good + good, "f.stl");
    CHECK(has(e, "f.stl:15: the file ends without 'endsolid' (solid at line 1, 2 facets read)"));
  }
  SUBCASE("truncated inside a facet") {
    const std::string full = head + good;
    std::string e = error_of(full.substr(0, full.find("vertex 1 0 0")), "f.stl");
    CHECK(has(e, "the file ends inside the facet at line 2"));
    e = error_of(head + "facet normal 0 0 1\nouter loop\nvertex 1 2", "f.stl");
    CHECK(has(e, "f.stl:4: the file ends inside a vertex (its z coordinate is missing)"));
    e = error_of(head + "facet normal 0 0 1\nouter", "f.stl");
    CHECK(has(e, "f.stl:3: the file ends where 'loop' should follow 'outer'"));
  }
  SUBCASE("garbage tokens") {
    std::string e = error_of(head + good + "facte normal 0 0 1\n", "f.stl");
    CHECK(has(e, "f.stl:9: expected 'facet' or 'endsolid', found 'facte'"));
    e = error_of(head + "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvrtex 1 0 0\n", "f.stl");
    CHECK(has(e, "f.stl:5: expected 'vertex' or 'endloop', found 'vrtex'"));
    e = error_of(head + "facet normal 0 0 1\nouter loop\n" + kV + "endloop\nendfact\n", "f.stl");
    CHECK(has(e, "f.stl:8: expected 'endfacet' after 'endloop', found 'endfact'"));
    e = error_of(head + std::string("\x01\x02zz") + "\n", "f.stl");
    CHECK(has(e, "f.stl:2: expected 'facet' or 'endsolid', found '\\x01\\x02zz'"));
  }
  SUBCASE("numbers that do not parse") {
    std::string e = error_of(head + "facet normal 0 0 1\nouter loop\nvertex 0 1.2.3 0\n", "f.stl");
    CHECK(has(e, "f.stl:4: expected a number for the vertex y coordinate, found '1.2.3'"));
    e = error_of(head + "facet normal 0 0 x\n", "f.stl");
    CHECK(has(e, "f.stl:2: expected a number for the normal z coordinate, found 'x'"));
    e = error_of(head + "facet normal 0 0 1\nouter loop\nvertex 0,5 0 0\n", "f.stl");
    CHECK(has(e, "found '0,5'"));
  }
  SUBCASE("NaN, infinite and out-of-range coordinates") {
    std::string e = error_of(head + "facet normal 0 0 1\nouter loop\nvertex nan 0 0\n", "f.stl");
    CHECK(has(e, "f.stl:4: vertex x coordinate 'nan' is not a finite number"));
    e = error_of(head + "facet normal 0 0 1\nouter loop\nvertex 0 0 -inf\n", "f.stl");
    CHECK(has(e, "vertex z coordinate '-inf' is not a finite number"));
    e = error_of(head + "facet normal 0 0 1\nouter loop\nvertex 0 1e39 0\n", "f.stl");
    CHECK(has(e, "f.stl:4: vertex y coordinate '1e39' is out of range for a 32-bit float"));
    // Values too small for a float round to zero instead.
    Report report;
    auto m = parse(head + facet("0 0 1", "vertex 1e-50 0 0\nvertex 1 0 0\nvertex 0 1 0\n") + "endsolid t\n",
                   report);
    REQUIRE(m.ok());
    CHECK(m->vertices[0].x == 0.0);
  }
  SUBCASE("zero facets") {
    std::string e = error_of("solid empty\nendsolid empty\n", "f.stl");
    CHECK(has(e, "f.stl: the file has no facets (solid 'empty' is empty)"));
  }
  SUBCASE("long garbage is shortened and escaped in messages") {
    const std::string e = error_of(head + std::string(1000, 'q') + "\n", "f.stl");
    CHECK(has(e, "found 'qqqqqqqqqqqqqqqqqqqqqqqq...'"));
    CHECK(e.size() < 200);
  }
}
