#include "base/input_file.h"

#include <doctest/doctest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <thread>

#include "tests/support/fixtures.h"

namespace fs = std::filesystem;
using tranche::InputKind;
using tranche::read_input;
namespace test = tranche::test;

namespace {

constexpr InputKind kSmall{"the test file", 16};

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("input file: a regular file is read whole, up to its bound") {
  test::TempDir dir("input");
  { std::ofstream(dir / "ok.txt") << "0123456789abcdef"; }
  auto ok = read_input((dir / "ok.txt").string(), kSmall);
  REQUIRE(ok.ok());
  CHECK(*ok == "0123456789abcdef");
  { std::ofstream(dir / "big.txt") << "0123456789abcdefg"; }
  auto big = read_input((dir / "big.txt").string(), kSmall);
  REQUIRE_FALSE(big.ok());
  CHECK(big.error().where == (dir / "big.txt").string());
  CHECK(has(big.error().message, "the test file is 17 bytes, more than the 16 bytes read at most"));
  { std::ofstream(dir / "empty.txt"); }
  auto empty = read_input((dir / "empty.txt").string(), kSmall);
  REQUIRE(empty.ok());
  CHECK(empty->empty());
}

TEST_CASE("input file: a huge sparse file is refused from its size, without reading it") {
  test::TempDir dir("input-sparse");
  const fs::path p = dir / "sparse.rules";
  { std::ofstream(p) << ""; }
  fs::resize_file(p, uint64_t{2} << 30);
  auto r = read_input(p.string(), tranche::kRulesInput);
  REQUIRE_FALSE(r.ok());
  CHECK(has(r.error().message, "the rules file is 2 GiB, more than the 16 MiB read at most"));
}

TEST_CASE("input file: missing files and folders are errors that say so") {
  test::TempDir dir("input-missing");
  auto missing = read_input((dir / "nope.rules").string(), tranche::kRulesInput);
  REQUIRE_FALSE(missing.ok());
  CHECK(has(missing.error().message, "cannot open the rules file: No such file or directory — check the path"));
  auto folder = read_input(dir.path().string(), tranche::kRulesInput);
  REQUIRE_FALSE(folder.ok());
  CHECK(has(folder.error().message, "is a directory, not the rules file"));
}

TEST_CASE("input file: a FIFO is read with the same bound, an endless one refused with a clear message") {
  test::TempDir dir("input-fifo");
  const fs::path fifo = dir / "in.fifo";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  std::thread small([&] { std::ofstream(fifo) << "rule { }"; });
  auto ok = read_input(fifo.string(), kSmall);
  small.join();
  REQUIRE(ok.ok());
  CHECK(*ok == "rule { }");
  ::signal(SIGPIPE, SIG_IGN);  // the writer learns that the reader went away from write()
  std::atomic<bool> stop{false};
  std::thread endless([&] {  // like /dev/zero, until the reader goes away
    const int fd = ::open(fifo.c_str(), O_WRONLY);
    const std::string zeros(4096, '\0');
    while (!stop && ::write(fd, zeros.data(), zeros.size()) > 0) {
    }
    ::close(fd);
  });
  auto r = read_input(fifo.string(), tranche::InputKind{"the rules file", 1 << 20});
  stop = true;
  endless.join();
  REQUIRE_FALSE(r.ok());
  CHECK(has(r.error().message, "a pipe or FIFO gave more than 1 MiB, the most that is read of the rules file"));
}

TEST_CASE("input file: size_text") {
  CHECK(tranche::size_text(300) == "300 bytes");
  CHECK(tranche::size_text(16 << 20) == "16 MiB");
  CHECK(tranche::size_text(uint64_t{4} << 30) == "4 GiB");
  CHECK(tranche::size_text(3 << 19) == "1.5 MiB");
}
