#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "geometry/mesh/stl.h"
#include "tests/geometry/mesh/stl_helpers.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::test::stl;
using tranche::test::TempDir;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

geo::Mesh two_cubes() {
  geo::Mesh m;
  m.name = "two cubes";
  for (float x0 : {0.0f, 3.5f}) {
    const auto base = static_cast<uint32_t>(m.vertices.size());
    const float a = x0, b = x0 + 1.25f;
    const float v[8][3] = {{a, 0, 0}, {b, 0, 0}, {b, 2, 0}, {a, 2, 0},
                           {a, 0, 3}, {b, 0, 3}, {b, 2, 3}, {a, 2, 3}};
    for (const auto& p : v) m.vertices.push_back({p[0], p[1], p[2]});
    const uint32_t f[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                               {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    for (const auto& t : f) m.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  }
  return m;
}

}  // namespace

TEST_CASE("binary round trip: write then load gives the same vertices and triangles") {
  TempDir dir("stl-roundtrip");
  const geo::Mesh in = two_cubes();
  const std::string path = (dir / "cubes.stl").string();
  REQUIRE(geo::write_stl_binary(path, in).ok());
  CHECK(std::filesystem::file_size(path) == 84 + 50 * in.triangles.size());

  Report report;
  auto out = geo::load_stl(path, report);
  REQUIRE_MESSAGE(out.ok(), out.error().to_string());
  CHECK(report.empty());
  CHECK(out->name == "two cubes");
  // Welding: each triangle's three corners come back as shared ids, in first-seen order.
  REQUIRE(out->vertices.size() == 16);
  REQUIRE(out->triangles.size() == in.triangles.size());
  for (size_t i = 0; i < in.triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const geo::Vec3& a = in.vertices[in.triangles[i][k]];
      const geo::Vec3& b = out->vertices[out->triangles[i][k]];
      CHECK(a.x == b.x);
      CHECK(a.y == b.y);
      CHECK(a.z == b.z);
    }
  }
  CHECK(out->volume() == doctest::Approx(2 * 1.25 * 2 * 3));
  // Normals are written from the winding, so the reload has no normal warnings and they point outward.
  const std::string bytes = [&] {
    std::ifstream f(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), {});
  }();
  float nz;
  std::memcpy(&nz, bytes.data() + 84 + 8, 4);  // first triangle is the bottom face: normal (0, 0, -1)
  CHECK(nz == -1.0f);
  // No temporary file is left beside the output.
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  CHECK(files == 1);
}

TEST_CASE("welding: bitwise-equal corners share an id, -0 and +0 weld, near-equal ones do not") {
  auto tris = cube();
  Report report;
  auto m = parse(binary_stl(tris), report);
  REQUIRE(m.ok());
  CHECK(m->vertices.size() == 8);
  CHECK(m->triangles.size() == 12);
  CHECK(m->volume() == doctest::Approx(1.0));

  // The same cube with some zeros written as -0: still 8 vertices.
  for (auto& t : tris) {
    for (auto& c : t) {
      if (c == 0 && (&c - t.data()) % 2 == 0) c = -0.0f;
    }
  }
  auto m2 = parse(binary_stl(tris), report);
  REQUIRE(m2.ok());
  CHECK(m2->vertices.size() == 8);

  // Moving one corner of one triangle by one float ulp splits it off as a separate vertex.
  auto tris3 = cube();
  tris3[0][0] = std::nextafter(0.0f, 1.0f);
  auto m3 = parse(binary_stl(tris3), report);
  REQUIRE(m3.ok());
  CHECK(m3->vertices.size() == 9);
}

TEST_CASE("binary that starts with 'solid' is read as binary when the count matches the size") {
  Report report;
  auto m = parse(binary_stl(cube(), BinaryOptions().with_header("solid cube exported by a careless tool")),
                 report, "solidbin.stl");
  REQUIRE_MESSAGE(m.ok(), m.error().to_string());
  CHECK(m->triangles.size() == 12);
  CHECK(m->name == "cube exported by a careless tool");
  CHECK(report.empty());

  // Same, but with trailing bytes: the size no longer agrees, yet NULs show it is binary.
  Report report2;
  auto m2 = parse(binary_stl(cube(), BinaryOptions().with_header("solid x")) + std::string(7, '\0'), report2,
                  "solidbin.stl");
  REQUIRE_MESSAGE(m2.ok(), m2.error().to_string());
  CHECK(m2->triangles.size() == 12);
  CHECK(report2.count("stl-extra-data") == 1);
}

TEST_CASE("binary: name from the header, else the file stem") {
  Report report;
  auto named =
      parse(binary_stl(cube(), BinaryOptions().with_header("  bracket v2  ")), report, "dir/file.stl");
  REQUIRE(named.ok());
  CHECK(named->name == "bracket v2");
  auto blank = parse(binary_stl(cube(), BinaryOptions()), report, "dir/part-7.stl");
  REQUIRE(blank.ok());
  CHECK(blank->name == "part-7");
  std::string junk = "\x01\x02\xff";
  auto unprintable = parse(binary_stl(cube(), BinaryOptions().with_header(junk)), report, "dir/raw.stl");
  REQUIRE(unprintable.ok());
  CHECK(unprintable->name == "raw");
}

TEST_CASE("binary: nonzero attribute words are ignored silently, zero normals are fine") {
  Report report;
  auto m = parse(binary_stl(cube(), BinaryOptions().with_attribute(0x7c1f).with_zero_normals()), report);
  REQUIRE(m.ok());
  CHECK(m->triangles.size() == 12);
  CHECK(report.empty());
}

TEST_CASE("binary: normals that disagree with the winding give one summarised warning") {
  Report report;
  auto m = parse(binary_stl(cube(), BinaryOptions().with_flipped_normals()), report, "flipped.stl");
  REQUIRE(m.ok());
  CHECK(m->triangles.size() == 12);
  REQUIRE(report.count("stl-normal") == 1);
  const auto w = report.warnings().front();
  CHECK(w.where == "flipped.stl, triangle 1");
  CHECK(has(w.message, "12 of 12 facets"));
  CHECK(m->volume() == doctest::Approx(1.0));  // the winding wins
}

TEST_CASE("binary: extra data after the last triangle is a warning") {
  Report report;
  auto m = parse(binary_stl(cube()) + std::string(60, 'x'), report, "extra.stl");
  REQUIRE(m.ok());
  CHECK(m->triangles.size() == 12);
  REQUIRE(report.count("stl-extra-data") == 1);
  CHECK(has(report.warnings().front().message, "60 bytes after the last of the header's 12 triangles"));
  CHECK(has(report.warnings().front().message, "room for 1 more"));
}

TEST_CASE("binary errors name the file, the triangle and the problem") {
  const std::string full = binary_stl(cube());
  SUBCASE("truncated") {
    const std::string e = error_of(full.substr(0, full.size() - 30), "cut.stl");
    CHECK(has(e, "cut.stl, triangle 12: "));
    CHECK(has(e, "header says 12 triangles, file holds 11 complete ones"));
    CHECK(has(e, "truncated"));
  }
  SUBCASE("count larger than the data") {
    const std::string e = error_of(binary_stl(cube(), BinaryOptions().with_count(66)), "count.stl");
    CHECK(has(e, "count.stl, triangle 13: "));
    CHECK(has(e, "header says 66 triangles, file holds 12 complete ones"));
  }
  SUBCASE("huge claimed count fails before any allocation") {
    const std::string e = error_of(binary_stl(cube(), BinaryOptions().with_count(0xFFFFFFFFll)), "huge.stl");
    CHECK(has(e, "header says 4294967295 triangles, file holds 12 complete ones"));
    std::string header_only(80, 'h');
    put_u32(header_only, 4000000000u);
    CHECK(
        has(error_of(header_only, "h.stl"), "header says 4000000000 triangles, file holds 0 complete ones"));
  }
  SUBCASE("zero triangles") {
    const std::string e = error_of(binary_stl({}), "none.stl");
    CHECK(has(e, "none.stl: header says 0 triangles"));
    CHECK(has(error_of(binary_stl({}) + "abc", "none.stl"), "(3 bytes follow it)"));
  }
  SUBCASE("NaN and infinite coordinates") {
    auto tris = cube();
    tris[4][7] = std::numeric_limits<float>::quiet_NaN();
    std::string e = error_of(binary_stl(tris), "nan.stl");
    CHECK(has(e, "nan.stl, triangle 5: corner 3 has a coordinate that is not a finite number (nan)"));
    tris = cube();
    tris[0][0] = -std::numeric_limits<float>::infinity();
    e = error_of(binary_stl(tris), "inf.stl");
    CHECK(has(e, "inf.stl, triangle 1: corner 1"));
    CHECK(has(e, "(-inf)"));
  }
  SUBCASE("tiny files") {
    CHECK(has(error_of("", "empty.stl"), "empty.stl: the file is empty (0 bytes)"));
    CHECK(has(error_of(std::string(1, '\x07'), "one.stl"), "file is 1 bytes: too short for a binary STL"));
    CHECK(has(error_of("s", "s.stl"), "not an STL file"));
    CHECK(has(error_of("solid", "solid.stl"), "the file ends without 'endsolid'"));
  }
  SUBCASE("text that is not an STL") {
    const std::string e =
        error_of("<html><body>404 not found</body></html>\n" + std::string(100, ' '), "page.stl");
    CHECK(has(e, "page.stl: not an STL file: it is text but does not start with 'solid'"));
    CHECK(has(e, "<html>"));
  }
}

TEST_CASE("degenerate triangles are dropped with one summarised warning") {
  auto tris = cube();
  Tri sliver = tris[3];
  sliver[6] = sliver[3], sliver[7] = sliver[4], sliver[8] = sliver[5];  // corner c == corner b
  Tri point{};
  point.fill(9.0f);  // all three corners equal, and at a point no other triangle uses
  tris.insert(tris.begin() + 5, sliver);
  tris.push_back(point);
  Report report;
  auto m = parse(binary_stl(tris, BinaryOptions().with_zero_normals()), report, "deg.stl");
  REQUIRE(m.ok());
  CHECK(m->triangles.size() == 12);
  CHECK(m->vertices.size() == 8);  // the lone point (9, 9, 9) is not kept
  REQUIRE(report.count("stl-degenerate") == 1);
  CHECK(report.size() == 1);
  const auto w = report.warnings().front();
  CHECK(w.where == "deg.stl, triangle 6");
  CHECK(has(w.message, "dropped 2 degenerate triangles of 14"));
  for (const auto& t : m->triangles) {
    for (uint32_t id : t) CHECK(id < m->vertices.size());
  }
}

TEST_CASE("a model whose triangles are all degenerate is an error") {
  Tri t{};
  t.fill(1.0f);
  const std::string e = error_of(binary_stl({t, t}), "flat.stl");
  CHECK(has(e, "flat.stl: all 2 triangles are degenerate"));
}

TEST_CASE("load_stl: unreadable paths give the errno text and the path") {
  Report report;
  auto missing = geo::load_stl("/nonexistent/dir/model.stl", report);
  REQUIRE(!missing.ok());
  CHECK(missing.error().where == "/nonexistent/dir/model.stl");
  CHECK(has(missing.error().message, "No such file or directory"));
  TempDir dir("stl-dir");
  auto is_dir = geo::load_stl(dir.path().string(), report);
  REQUIRE(!is_dir.ok());
  CHECK(has(is_dir.error().message, "is a directory"));
}

TEST_CASE("write_stl_binary: failures leave no file and say why") {
  geo::Mesh m = two_cubes();
  auto st = geo::write_stl_binary("/nonexistent/dir/out.stl", m);
  REQUIRE(!st.ok());
  CHECK(has(st.error().message, "the folder '/nonexistent/dir' does not exist"));

  TempDir dir("stl-write");
  const std::string path = (dir / "bad.stl").string();
  m.triangles.push_back({0, 1, 99});
  st = geo::write_stl_binary(path, m);
  REQUIRE(!st.ok());
  CHECK(has(st.error().to_string(), "triangle 25: vertex id 99 is out of range"));
  CHECK(!std::filesystem::exists(path));

  // Coordinates beyond float range cannot be written (and must not be cast: that is undefined).
  m = two_cubes();
  m.vertices[5].y = 1e300;
  st = geo::write_stl_binary(path, m);
  REQUIRE(!st.ok());
  CHECK(has(st.error().to_string(), "does not fit a 32-bit float"));
  CHECK(!std::filesystem::exists(path));

  // A name starting with "solid" is not written at the start of the header.
  m = two_cubes();
  m.name = "Solid block";
  REQUIRE(geo::write_stl_binary(path, m).ok());
  std::ifstream f(path, std::ios::binary);
  std::string head(5, '\0');
  f.read(head.data(), 5);
  CHECK(head != "Solid");
  Report report;
  auto back = geo::load_stl(path, report);
  REQUIRE(back.ok());
  CHECK(has(back->name, "Solid block"));
}
