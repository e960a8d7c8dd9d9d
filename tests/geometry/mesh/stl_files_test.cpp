// Small hand-made STL files in tests/data/stl, loaded from disk through load_stl, and random
// inputs that must load or fail cleanly.
#include <doctest/doctest.h>

#include <sys/mman.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <random>
#include <string>

#include "geometry/mesh/file_bytes.h"
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

TEST_CASE("read_file_bytes: bytes kept in huge pages are the file's, above and below 4 MiB") {
  // FileMemory is asked after the head check (so a loader can choose by what it saw), and only
  // for a regular file; the bytes read are the file's either way, and are freed either way.
  test::TempDir dir("file-bytes");
  std::mt19937 rng(404);
  for (const size_t size :
       {size_t{1}, size_t{3000}, (size_t{4} << 20) - 1, size_t{4} << 20, (size_t{9} << 20) + 7}) {
    CAPTURE(size);
    std::string bytes(size, '\0');
    for (char& c : bytes) c = static_cast<char>(rng());
    const std::string path = (dir.path() / "f.bin").string();
    std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    for (const geo::FileMemory memory : {geo::FileMemory::kHeap, geo::FileMemory::kHugePages}) {
      bool checked = false, asked_after = false;
      auto got = geo::read_file_bytes(
          path,
          [&](std::string_view head, std::optional<uint64_t> n) -> Result<uint64_t> {
            checked = true;
            CHECK(head == std::string_view(bytes).substr(0, geo::kHeadBytes));
            CHECK(n == size);
            return UINT64_MAX;
          },
          [&] {
            asked_after = checked;
            return memory;
          });
      REQUIRE_MESSAGE(got.ok(), got.error().to_string());
      CHECK(asked_after);
      CHECK(got->view() == bytes);
      const bool mapped = memory == geo::FileMemory::kHugePages && size >= (size_t{4} << 20);
      CHECK(got->data.get_deleter().mapped == (mapped ? geo::huge_length(size) : 0));
      if (mapped) CHECK(reinterpret_cast<uintptr_t>(got->data.get()) % (size_t{2} << 20) == 0);
    }
  }
}

TEST_CASE("map_huge: room at a 2 MiB boundary, whole 2 MiB long, every byte of it writable; no room is no room") {
  constexpr size_t kHuge = size_t{2} << 20;
  for (const size_t size : {size_t{1}, size_t{4095}, kHuge - 1, kHuge, kHuge + 1, 4 * kHuge + 4096 + 64 * 1024}) {
    CAPTURE(size);
    const size_t length = geo::huge_length(size);
    CHECK(length % kHuge == 0);
    CHECK(length >= size);
    CHECK(length < size + kHuge);
    char* p = geo::map_huge(size);
    REQUIRE(p != nullptr);
    CHECK(reinterpret_cast<uintptr_t>(p) % kHuge == 0);
    std::memset(p, 7, length);  // the rounding is the caller's too
    CHECK(p[0] == 7);
    CHECK(p[size - 1] == 7);
    CHECK(p[length - 1] == 7);
    CHECK(munmap(p, length) == 0);
  }
  CHECK(geo::map_huge(SIZE_MAX - 100) == nullptr);  // rounded up it would wrap
  CHECK(geo::map_huge(size_t{1} << 62) == nullptr);  // more than the address space
}
