// End to end: `tranche slice --explain` on a real slice (the library call and the executable).
#include <doctest/doctest.h>
#include <fmt/format.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "apps/slice_command.h"
#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "tests/support/fixtures.h"

using namespace tranche;
namespace fs = std::filesystem;

namespace {

// Line 2 halves the outer wall's speed; line 3 adds G-code before it.
const char* kWallRules =
    "# walls\n"
    "rule \"slow walls\" when path.kind == outer_perimeter { speed = speed * 50% }\n"
    "rule \"pa\" when path.kind == outer_perimeter { before path { gcode \"M900 K0.045\" } }\n";

struct Job {
  test::TempDir dir{"preview-e2e"};
  pipeline::SliceOptions o;
  std::string rules;
  Job() {
    o.quiet = true;
    o.model = (dir / "cube.stl").string();
    REQUIRE(geo::write_stl_binary(o.model, geo::box({20, 10, 5})).ok());
    rules = (dir / "walls.rules").string();
    std::ofstream(rules) << kWallRules;
    o.rules = {rules};
  }
  Result<pipeline::SliceSummary> run() {
    Report report;
    return app::slice(o, report);
  }
};

struct Run {
  int status = -1;
  std::string out;
};

Run tranche_exe(const std::string& args) {
  std::string cmd = "'";  // appended, not added: GCC 12 warns (-Wrestrict) wrongly on "'" + string
  cmd.append((test::binary_dir() / "apps" / "tranche").string()).append("' ").append(args).append(" 2>&1");
  Run r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int raw = pclose(p);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

}  // namespace

TEST_CASE("tranche slice --explain: the decided values of a real layer's paths, their chains, executors, replacer") {
  Job j;
  j.o.explain = "layer=3 island=0 path=outer_perimeter";
  auto r = j.run();
  REQUIRE_MESSAGE(r.ok(), r.error().to_string());
  const std::string& e = r->explanation;
  INFO(e);
  CHECK(e.rfind("layer 3 (z 0.80 mm), island 0, path ", 0) == 0);
  CHECK(e.find(": outer_perimeter, perimeter 0, ") != std::string::npos);
  CHECK(e.find("  speed = ") != std::string::npos);
  CHECK(e.find("60 mm/s schema default -> ") != std::string::npos);
  CHECK(e.find(fmt::format(" rule \"slow walls\" ({}:2)", j.rules)) != std::string::npos);
  CHECK(e.find("  flow = ") != std::string::npos);
  CHECK(e.find(fmt::format("  before path: rule \"pa\" ({}:3) wrote: M900 K0.045", j.rules)) != std::string::npos);
  CHECK(e.find("  no replacer: the default G-code") != std::string::npos);
  CHECK(r->written.empty());  // alone, --explain writes nothing
  // Every path of the layer; paths decided alike (two copies of the block) are explained once.
  j.o.explain = "layer=3";
  plate::PlateOptions two;
  two.files = {j.o.model};
  two.copies = {*plate::parse_copies("2")};
  Report report;
  auto all = app::slice(j.o, two, report);
  REQUIRE_MESSAGE(all.ok(), all.error().to_string());
  INFO(all->explanation);
  CHECK(all->explanation.find(": infill, cell 0") != std::string::npos);
  for (const char* island : {"island 0, path 2: outer_perimeter", "island 1, path 2: outer_perimeter"})
    CHECK(all->explanation.find(island) != std::string::npos);
  // The island printed second repeats nothing: each of its paths is "decided as" the first's.
  size_t alike = 0;
  for (size_t at = 0; (at = all->explanation.find("\n  decided as layer 3 (z 0.80 mm), island ", at)) != std::string::npos; ++at)
    ++alike;
  CHECK(alike == 3);
  // Specs that do not parse or match nothing are refused, saying what to write or what there is.
  for (auto [spec, says] : {std::pair{"layer=99", "past the top: the print has 25 layers (0 to 24)"},
                            {"layer=3 island=4", "layer 3 has 1 island (0 to 0)"},
                            {"layer=3 path=bridge", "no path of layer 3 matches; the layer has "},
                            {"layr=3", "'layr' is not a key"},
                            {"island=0", "which layer? write layer=N"},
                            {"layer=three", "layer= needs a whole number"},
                            {"layer=3 path=wall", "path= is a path kind"}}) {
    j.o.explain = spec;
    auto bad = j.run();
    REQUIRE_FALSE(bad.ok());
    CHECK(bad.error().where == "--explain");
    CHECK_MESSAGE(bad.error().message.find(says) != std::string::npos, bad.error().message);
  }
}

TEST_CASE("tranche slice --explain, the executable: the explanation on stdout, exit 1 and a message for a bad spec") {
  Job j;
  const std::string common = "slice '" + j.o.model + "' --rules '" + j.rules + "' --quiet";
  const Run ok = tranche_exe(common + " --explain 'layer=2 path=outer_perimeter'");
  INFO(ok.out);
  CHECK(ok.status == 0);
  CHECK(ok.out.find("layer 2 (z 0.60 mm), island 0, path ") != std::string::npos);
  CHECK(ok.out.find("rule \"slow walls\" (" + j.rules + ":2)") != std::string::npos);
  CHECK(ok.out.find("wrote ") == std::string::npos);
  const Run bad = tranche_exe(common + " --explain 'layer=2 path=bridge'");
  CHECK(bad.status == 1);
  CHECK(bad.out.find("error: --explain: no path of layer 2 matches; the layer has ") != std::string::npos);
  const Run missing = tranche_exe(common + " --explain");
  CHECK(missing.status == 2);
  CHECK(missing.out.find("--explain needs which paths") != std::string::npos);
}
