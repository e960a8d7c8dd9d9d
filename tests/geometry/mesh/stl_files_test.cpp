// Small hand-made STL files in tests/data/stl, loaded from disk through load_stl, and random
// inputs that must load or fail cleanly.
#include <doctest/doctest.h>

#include <random>
#include <string>

#include "geometry/mesh/stl.h"
#include "tests/geometry/mesh/stl_helpers.h"
#include "tests/support/fixtures.h"

using namespace tranche;

namespace {

std::string data(const std::string& name) { return (test::source_dir() / "tests/data/stl" / name).string(); }
bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("fixture files: each loads or fails as documented") {
  SUBCASE("CRLF, tabs and mixed-case keywords load silently") {
    Report report;
    auto m = geo::load_stl(data("crlf_tabs_mixed_case.stl"), report);
    REQUIRE_MESSAGE(m.ok(), m.error().to_string());
    CHECK(report.empty());
    CHECK(m->name == "crlf tetra");
    CHECK(m->vertices.size() == 4);
    CHECK(m->triangles.size() == 4);
    CHECK(m->volume() == doctest::Approx(1.0 / 6));
  }
  SUBCASE("binary with a 'solid' header") {
    Report report;
    auto m = geo::load_stl(data("solid_header.bin.stl"), report);
    REQUIRE_MESSAGE(m.ok(), m.error().to_string());
    CHECK(report.empty());
    CHECK(m->name == "tetra written as binary");
    CHECK(m->triangles.size() == 4);
  }
  SUBCASE("truncated binary") {
    Report report;
    const std::string path = data("truncated.bin.stl");
    auto m = geo::load_stl(path, report);
    REQUIRE(!m.ok());
    CHECK(m.error().where == path + ", triangle 4");
    CHECK(has(m.error().message, "header says 4 triangles, file holds 3 complete ones"));
  }
  SUBCASE("a facet with four vertices") {
    Report report;
    const std::string path = data("four_vertices.stl");
    auto m = geo::load_stl(path, report);
    REQUIRE(!m.ok());
    CHECK(m.error().where == path + ":2");
    CHECK(has(m.error().message, "facet has 4 vertices"));
  }
  SUBCASE("a flipped normal") {
    Report report;
    const std::string path = data("flipped_normal.stl");
    auto m = geo::load_stl(path, report);
    REQUIRE(m.ok());
    REQUIRE(report.count("stl-normal") == 1);
    CHECK(report.warnings()[0].where == path + ":9");
  }
}

TEST_CASE("random bytes and mutated files never crash and always give a message") {
  std::mt19937 rng(12345);
  const std::string seeds[] = {test::stl::binary_stl(test::stl::cube()),
                               test::stl::ascii_stl(test::stl::cube())};
  size_t loaded = 0, failed = 0;
  for (int round = 0; round < 3000; ++round) {
    std::string bytes;
    if (round % 3 == 0) {
      bytes.resize(rng() % 400);
      for (auto& c : bytes) c = static_cast<char>(rng());
      if (round % 2 == 0) bytes = "solid " + bytes;
    } else {
      bytes = seeds[round % 2];
      const int edits = 1 + static_cast<int>(rng() % 8);
      for (int e = 0; e < edits; ++e) {
        const size_t at = rng() % bytes.size();
        switch (rng() % 3) {
          case 0:
            bytes[at] = static_cast<char>(rng());
            break;
          case 1:
            bytes.erase(at, rng() % 16);
            break;
          default:
            bytes =
                bytes.substr(0, at) + std::string(1 + rng() % 4, static_cast<char>(rng())) + bytes.substr(at);
        }
        if (bytes.empty()) bytes.push_back('x');
      }
    }
    Report report;
    auto m = geo::parse_stl(bytes, "rand.stl", report);
    if (m.ok()) {
      ++loaded;
      REQUIRE(!m->triangles.empty());
      for (const auto& t : m->triangles) {
        for (uint32_t id : t) REQUIRE(id < m->vertices.size());
      }
    } else {
      ++failed;
      REQUIRE(has(m.error().to_string(), "rand.stl"));
      REQUIRE(m.error().message.size() > 10);
    }
  }
  // Both outcomes occur: the mutations are neither all harmless nor all fatal.
  CHECK(loaded > 100);
  CHECK(failed > 100);
}
