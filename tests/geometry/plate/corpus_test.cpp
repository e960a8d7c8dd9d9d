// The fuzz target's seed corpus (fuzz/make_3mf_corpus.py): every ok-*.3mf loads, every
// bad-*.3mf fails with a message, so the seeds are what their names say.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>

#include "geometry/plate/threemf.h"
#include "tests/support/fixtures.h"

using namespace tranche;
namespace fs = std::filesystem;

TEST_CASE("fuzz/make_3mf_corpus.py: ok seeds load, bad seeds fail cleanly") {
  test::TempDir dir("3mf-corpus");
  const std::string cmd = "python3 '" + (test::source_dir() / "fuzz" / "make_3mf_corpus.py").string() + "' '" +
                          dir.path().string() + "'";
  REQUIRE(std::system(cmd.c_str()) == 0);
  int ok = 0, bad = 0;
  for (const auto& e : fs::directory_iterator(dir.path())) {
    const std::string name = e.path().filename().string();
    INFO(name);
    Report report;
    auto objects = plate::parse_3mf(test::read_file(e.path()), name, report);
    if (name.starts_with("ok-")) {
      CHECK_MESSAGE(objects.ok(), (objects.ok() ? "" : objects.error().to_string()));
      ++ok;
    } else {
      REQUIRE_FALSE(objects.ok());
      CHECK(objects.error().to_string().find(name) == 0);
      ++bad;
    }
  }
  CHECK(ok >= 6);
  CHECK(bad >= 7);
}
