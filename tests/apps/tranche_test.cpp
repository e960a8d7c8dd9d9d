// The tranche executable given bad model files, as a user runs it: a non-zero exit, a message
// that names the file and what is wrong, and no G-code written.
#include <doctest/doctest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <string>

#include "geometry/mesh/primitives.h"
#include "geometry/plate/threemf_write.h"
#include "tests/apps/run_command.h"
#include "tests/support/fixtures.h"

namespace fs = std::filesystem;
using namespace tranche;
using namespace tranche::test;

namespace {


// Runs `tranche ARGS` through the shell, stderr with stdout.
Run tranche_cmd(const std::string& args) { return run_app("tranche", args, "2>&1 < /dev/null"); }

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// `tranche slice MODEL -o out.gcode` fails, naming the model and saying `what`; nothing is written.
void refused(const TempDir& dir, const fs::path& model, const std::string& what) {
  const fs::path out = dir.path() / "out.gcode";
  Run r = tranche_cmd("slice '" + model.string() + "' -o '" + out.string() + "' --quiet");
  CAPTURE(r.out);
  CHECK(r.status != 0);
  CHECK(has(r.out, model.string()));
  CHECK(has(r.out, what));
  CHECK_FALSE(fs::exists(out));
}

}  // namespace

TEST_CASE("tranche slice: a corrupt 3MF is refused, naming the file, and nothing is written") {
  TempDir dir("tranche-bad-3mf");
  const fs::path good = dir.path() / "good.3mf";
  plate::Object cube;
  cube.name = "cube";
  cube.mesh = geo::box({10, 10, 3});
  REQUIRE(plate::write_3mf(good.string(), {cube}).ok());
  // Cut short: the ZIP's directory at its end is lost.
  std::ifstream in(good, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const fs::path cut = dir.path() / "cut.3mf";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  refused(dir, cut, "ZIP");
  // Not a ZIP at all, though named .3mf.
  const fs::path text = dir.path() / "notes.3mf";
  std::ofstream(text) << "these are not the droids you are looking for\n";
  refused(dir, text, "not a 3MF file: a 3MF file is a ZIP archive, and this is text starting with 'these are not");
}

TEST_CASE("tranche slice: a broken OBJ is refused, naming the file and its line, and nothing is written") {
  TempDir dir("tranche-bad-obj");
  const fs::path two = dir.path() / "two.obj";
  std::ofstream(two) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n";
  refused(dir, two, "two.obj:4: a face with 2 vertices");
  const fs::path missing = dir.path() / "missing.obj";
  std::ofstream(missing) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";
  refused(dir, missing, "vertex");
}
