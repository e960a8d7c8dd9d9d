#include "base/output_file.h"

#include <doctest/doctest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "base/input_file.h"
#include "base/run_files.h"
#include "tests/support/fixtures.h"

namespace fs = std::filesystem;
using tranche::OutputFile;
using tranche::Status;
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


namespace {

mode_t mode_of(const fs::path& p) {
  struct stat st {};
  ::stat(p.c_str(), &st);
  return st.st_mode & 07777;
}

Status write_all(const std::string& path, const std::string& bytes, const std::string& what = "the file") {
  auto f = OutputFile::create(path, what);
  if (!f) return f.error();
  if (Status s = f->write(bytes); !s) return s;
  return f->commit();
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Opens a FIFO for the G-code once its reader (another thread) has opened it.
tranche::Result<OutputFile> open_when_read(const fs::path& fifo) {
  for (int i = 0;; ++i) {
    auto f = OutputFile::create(fifo.string(), "the G-code");
    if (f.ok() || i == 200) return f;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

}  // namespace

TEST_CASE("output file: an existing file keeps its mode; a new one gets 0666 less the umask") {
  test::TempDir dir("output-mode");
  const fs::path old = dir / "old.gcode";
  { std::ofstream(old) << "old"; }
  ::chmod(old.c_str(), 0640);
  REQUIRE(write_all(old.string(), "new").ok());
  CHECK(read(old) == "new");
  CHECK(mode_of(old) == 0640);
  const mode_t saved = ::umask(027);
  const auto made = write_all((dir / "new.gcode").string(), "x");
  ::umask(saved);
  REQUIRE(made.ok());
  CHECK(mode_of(dir / "new.gcode") == 0640);
  const mode_t saved2 = ::umask(0);
  const auto made2 = write_all((dir / "open.gcode").string(), "x");
  ::umask(saved2);
  REQUIRE(made2.ok());
  CHECK(mode_of(dir / "open.gcode") == 0666);
}

TEST_CASE("output file: a read-only file is refused, and left alone") {
  if (::geteuid() == 0) {
    MESSAGE("skipped: root may write read-only files");
    return;
  }
  test::TempDir dir("output-ro");
  const fs::path ro = dir / "ro.gcode";
  { std::ofstream(ro) << "keep"; }
  ::chmod(ro.c_str(), 0444);
  auto s = write_all(ro.string(), "new");
  REQUIRE_FALSE(s.ok());
  CHECK(has(s.error().message, "read-only"));
  CHECK(read(ro) == "keep");
}

TEST_CASE("output file: a symlink is written through; the link stays a link") {
  test::TempDir dir("output-link");
  fs::create_directories(dir / "share");
  { std::ofstream(dir / "share" / "x.gcode") << "old"; }
  fs::create_symlink("share/x.gcode", dir / "latest.gcode");  // relative, as users make them
  REQUIRE(write_all((dir / "latest.gcode").string(), "new").ok());
  CHECK(fs::is_symlink(dir / "latest.gcode"));
  CHECK(read(dir / "share" / "x.gcode") == "new");
  // No temporary is left in either folder.
  CHECK(std::distance(fs::directory_iterator(dir / "share"), fs::directory_iterator()) == 1);
  // A link to a missing file creates the file where the link points.
  fs::create_symlink(dir / "share" / "later.gcode", dir / "dangling.gcode");
  REQUIRE(write_all((dir / "dangling.gcode").string(), "made").ok());
  CHECK(fs::is_symlink(dir / "dangling.gcode"));
  CHECK(read(dir / "share" / "later.gcode") == "made");
  // A loop of links is an error, not a hang.
  fs::create_symlink(dir / "b", dir / "a");
  fs::create_symlink(dir / "a", dir / "b");
  auto loop = OutputFile::create((dir / "a").string());
  REQUIRE_FALSE(loop.ok());
}

TEST_CASE("output file: a FIFO is written directly, only when the run succeeds; no reader is an error") {
  test::TempDir dir("output-fifo");
  const fs::path fifo = dir / "printer.fifo";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  auto none = OutputFile::create(fifo.string(), "the G-code");
  REQUIRE_FALSE(none.ok());
  CHECK(has(none.error().message, "no reader"));
  std::string got;
  std::thread reader([&] { got = read_file(fifo.string()); });
  {
    auto f = open_when_read(fifo);
    REQUIRE(f.ok());
    CHECK(f->direct());
    CHECK(f->temp_path().empty());
    REQUIRE(f->write("G1 X1\n; filament used = ----\n").ok());
    REQUIRE(f->patch(24, "12.5").ok());  // the header is filled in at the end, as the writer does
    REQUIRE(f->commit().ok());
  }
  reader.join();
  CHECK(got == "G1 X1\n; filament used = 12.5\n");
  CHECK(fs::is_fifo(fifo));
  CHECK(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()) == 1);
  // A failed run sends nothing: the reader sees the end of the stream at once.
  std::thread reader2([&] { got = read_file(fifo.string()); });
  {
    auto f = open_when_read(fifo);
    REQUIRE(f.ok());
    REQUIRE(f->write("half a job").ok());
  }  // destroyed without commit
  reader2.join();
  CHECK(got.empty());
}

TEST_CASE("output file: a character device is written directly, never replaced") {
  if (::geteuid() != 0) {
    MESSAGE("skipped: making a device node (mknod) needs root");
    return;
  }
  test::TempDir dir("output-dev");
  const fs::path null = dir / "null";  // a /dev/null of our own, never the real one
  REQUIRE(::mknod(null.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0);
  REQUIRE(write_all(null.string(), std::string(3 << 20, 'g')).ok());
  CHECK(fs::is_character_file(null));
  CHECK(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()) == 1);
}

TEST_CASE("output file: a size limit stops the write with a message") {
  test::TempDir dir("output-limit");
  auto f = OutputFile::create((dir / "big.gcode").string(), "the G-code");
  REQUIRE(f.ok());
  f->set_limit(10, " (--max-gcode-size)");
  REQUIRE(f->write("0123456789").ok());
  auto s = f->write("x");
  REQUIRE_FALSE(s.ok());
  CHECK(has(s.error().message, "the G-code would be larger than 10 bytes (--max-gcode-size); nothing was written"));
}

TEST_CASE("output file: an output that is an input of the run is refused, naming both") {
  test::TempDir dir("output-input");
  const fs::path model = dir / "self.stl";
  { std::ofstream(model) << "solid x\nendsolid x\n"; }
  fs::create_symlink(model, dir / "alias.stl");
  {
    tranche::RunFiles run;
    auto in = tranche::read_input(model.string(), tranche::kModelInput);
    REQUIRE(in.ok());
    for (const fs::path& out : {model, dir / "alias.stl", dir / "." / "self.stl"}) {
      auto f = OutputFile::create(out.string(), "the G-code");
      REQUIRE_FALSE(f.ok());
      CHECK(has(f.error().message, "refusing to write the G-code here"));
      CHECK(has(f.error().message, "the model of this run ('" + model.string() + "')"));
      CHECK(f.error().where == out.string());
    }
    // Two outputs of one run that are one file.
    auto a = OutputFile::create((dir / "a.gcode").string(), "the G-code");
    REQUIRE(a.ok());
    auto b = OutputFile::create((dir / "a.gcode").string(), "the SVG export");
    REQUIRE_FALSE(b.ok());
    CHECK(has(b.error().message, "the G-code is already written to this file"));
  }
  CHECK(read(model) == "solid x\nendsolid x\n");
  // Outside a run nothing is compared (rulec fmt rewrites its input on purpose).
  CHECK(write_all(model.string(), "formatted").ok());
}

TEST_CASE("output file: a signal during the write removes the temporary and keeps the old file") {
  test::TempDir dir("output-signal");
  const fs::path out = dir / "out.gcode";
  { std::ofstream(out) << "previous"; }
  for (int sig : {SIGINT, SIGTERM}) {
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      // The test runner handles these signals itself; a tool's process leaves them at their
      // default, where OutputFile's handler goes.
      ::signal(SIGINT, SIG_DFL);
      ::signal(SIGTERM, SIG_DFL);
      auto f = OutputFile::create(out.string(), "the G-code");
      if (!f || !f->write(std::string(2 << 20, 'x'))) ::_exit(3);
      ::raise(sig);
      ::_exit(4);  // not reached: the signal ends the process
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == sig);
    CHECK(read(out) == "previous");
    CHECK(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()) == 1);
  }
}
