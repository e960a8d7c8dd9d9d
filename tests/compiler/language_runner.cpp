// Runs every tests/language/*.rules case against its inline `# expect` lines (expectations.h).
#include <algorithm>
#include <fstream>
#include <sstream>

#include "grammar/parse.h"
#include "tests/compiler/expectations.h"
#include "tests/support/fixtures.h"

namespace fs = std::filesystem;

TEST_CASE("language conformance: every tests/language case gives exactly the diagnostics it expects") {
  fs::path dir = tranche::test::source_dir() / "tests" / "language";
  std::vector<fs::path> cases;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".rules") cases.push_back(entry.path());
  std::sort(cases.begin(), cases.end());
  REQUIRE(cases.size() >= 80);
  // The corpus of typical mistakes (users of other slicers, beginners): each caught, with a help.
  CHECK(std::count_if(cases.begin(), cases.end(),
                      [](const fs::path& p) { return p.filename().string().starts_with("mistake_"); }) >= 40);
  for (const auto& path : cases) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    // An empty file cannot hold an `# expect` line: it must check clean.
    bool empty = text.str().empty();
    size_t fallbacks = tranche::grammar::ll_fallbacks();
    std::string problems =
        tranche::test::run_case(dir, path.filename().string(), text.str(), dir / "lib", empty);
    // Files without syntax errors parse with SLL prediction alone.
    bool syntax_error = text.str().find("error[E000") != std::string::npos;
    if (!syntax_error && tranche::grammar::ll_fallbacks() != fallbacks)
      problems += "  needed the full-LL pass\n";
    INFO(path.filename().string() << "\n" << problems);
    CHECK(problems.empty());
  }
}
