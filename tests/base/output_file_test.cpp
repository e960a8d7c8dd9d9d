#include "base/output_file.h"

#include <doctest/doctest.h>

#include <filesystem>

#include "tests/support/fixtures.h"

namespace fs = std::filesystem;
using tranche::OutputFile;
using tranche::test::read_file;
namespace test = tranche::test;

namespace {
std::string read(const fs::path& p) { return read_file(p.string()); }
}  // namespace

TEST_CASE("output file: nothing at the destination until commit; no leftovers on failure") {
  test::TempDir dir("output-file");
  fs::path dest = dir / "out.gcode";
  {
    auto f = OutputFile::create(dest.string());
    REQUIRE(f.ok());
    REQUIRE(f->write("; header 0000\n").ok());
    CHECK_FALSE(fs::exists(dest));
    CHECK(fs::exists(f->temp_path()));
  }  // destroyed without commit
  CHECK_FALSE(fs::exists(dest));
  CHECK(fs::is_empty(dir.path()));
  {
    auto f = OutputFile::create(dest.string());
    REQUIRE(f.ok());
    REQUIRE(f->write("; header 0000\n").ok());
    REQUIRE(f->write(std::string(3 << 20, 'x')).ok());  // beyond the buffer: patch must reach the file
    REQUIRE(f->patch(9, "1234").ok());
    REQUIRE(f->commit().ok());
  }
  CHECK(read(dest).substr(0, 14) == "; header 1234\n");
  CHECK(fs::file_size(dest) == 14 + (3u << 20));
  auto bad = OutputFile::create((dir / "missing" / "x.gcode").string());
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().message.find("does not exist") != std::string::npos);
}

