// Large files: the binary STL header is checked against the file's size before the file is read,
// so a 2 GB sparse file costs no memory; streams are read with the model bound.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "geometry/mesh/stl.h"
#include "tests/geometry/mesh/stl_helpers.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::test::stl;
using tranche::test::TempDir;
namespace fs = std::filesystem;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The most resident memory the process has used so far, bytes.
uint64_t peak_memory_bytes() {
  struct rusage u {};
  ::getrusage(RUSAGE_SELF, &u);
  return static_cast<uint64_t>(u.ru_maxrss) * 1024;
}

// A 2 GiB file with `head` at its start and nothing (a hole) after it.
std::string sparse_file(const TempDir& dir, const std::string& name, const std::string& head) {
  const std::string path = (dir / name).string();
  write_file(path, head);
  fs::resize_file(path, uint64_t{2} << 30);
  return path;
}

}  // namespace

TEST_CASE("a 2 GB sparse STL is refused from its header, without reading it") {
  TempDir dir("stl-sparse");
  const uint64_t before = peak_memory_bytes();
  const auto start = std::chrono::steady_clock::now();
  Report report;
  auto zero = geo::load_stl(sparse_file(dir, "zero.stl", std::string(84, '\0')), report);
  REQUIRE_FALSE(zero.ok());
  CHECK(has(zero.error().message, "header says 0 triangles"));
  std::string lying(84, '\0');
  lying[80] = '\xff', lying[81] = '\xff', lying[82] = '\xff', lying[83] = '\x7f';  // more than 2 GB holds
  auto big = geo::load_stl(sparse_file(dir, "big.stl", lying), report);
  REQUIRE_FALSE(big.ok());
  CHECK(has(big.error().message, "header says 2147483647 triangles"));
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 2);
  CHECK(peak_memory_bytes() < before + (uint64_t{256} << 20));
}

TEST_CASE("a binary STL followed by a 2 GB hole: only its triangles are read, the rest is a warning") {
  TempDir dir("stl-sparse-tail");
  const uint64_t before = peak_memory_bytes();
  Report report;
  auto mesh = geo::load_stl(sparse_file(dir, "tail.stl", binary_stl(cube())), report);
  REQUIRE_MESSAGE(mesh.ok(), mesh.error().to_string());
  CHECK(mesh->triangles.size() == 12);
  REQUIRE(report.warnings().size() == 1);
  CHECK(report.warnings()[0].code == "stl-extra-data");
  CHECK(has(report.warnings()[0].message, std::to_string((uint64_t{2} << 30) - 684) + " bytes after the last"));
  CHECK(peak_memory_bytes() < before + (uint64_t{256} << 20));
}

TEST_CASE("an endless stream of zeros as a model stops at its header") {
  TempDir dir("stl-fifo");
  const fs::path fifo = dir / "zero.stl";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  ::signal(SIGPIPE, SIG_IGN);
  std::atomic<bool> stop{false};
  std::thread zeros([&] {
    const int fd = ::open(fifo.c_str(), O_WRONLY);
    const std::string z(65536, '\0');
    while (!stop && ::write(fd, z.data(), z.size()) > 0) {
    }
    ::close(fd);
  });
  Report report;
  auto mesh = geo::load_stl(fifo.string(), report);
  stop = true;
  zeros.join();
  REQUIRE_FALSE(mesh.ok());
  CHECK(has(mesh.error().message, "header says 0 triangles"));
}
