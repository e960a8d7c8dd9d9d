// The examples in docs/language.md and docs/diagnostics.md are checked exactly as written, and
// every diagnostic code the compiler can emit is documented with an example.
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "tests/compiler/expectations.h"
#include "tests/support/fixtures.h"

namespace fs = std::filesystem;

namespace {

using tranche::test::Block;
using tranche::test::rules_blocks;
std::string read(const fs::path& p) { return tranche::test::read_file(p); }

void check_examples(const char* doc) {
  fs::path root = tranche::test::source_dir();
  std::string md = read(root / "docs" / doc);
  REQUIRE_FALSE(md.empty());
  auto blocks = rules_blocks(md);
  CHECK(blocks.size() >= 5);
  for (const auto& b : blocks) {
    std::string name = std::string(doc) + "-line" + std::to_string(b.line) + ".rules";
    std::string problems =
        tranche::test::run_case(root / "docs", name, b.text, root / "tests" / "language" / "lib",
                                /*default_ok=*/true);
    INFO(doc << " block at line " << b.line << "\n" << b.text << problems);
    CHECK(problems.empty());
  }
}

}  // namespace

TEST_CASE("docs: every example in docs/language.md checks as documented") { check_examples("language.md"); }

TEST_CASE("docs: every example in docs/diagnostics.md gives the diagnostic it shows") {
  check_examples("diagnostics.md");
}

TEST_CASE(
    "docs: every code the compiler emits has a section, and a wrong example unless it cannot be shown") {
  fs::path root = tranche::test::source_dir();
  std::set<std::string> emitted;
  std::regex code_re("\"([EW][0-9]{3,4})\"");
  for (const char* dir : {"compiler", "grammar", "grammar/ast"}) {
    for (const auto& e : fs::directory_iterator(root / dir)) {
      if (e.path().extension() != ".cpp") continue;
      std::string src = read(e.path());
      for (std::sregex_iterator it(src.begin(), src.end(), code_re), end; it != end; ++it)
        emitted.insert((*it)[1]);
    }
  }
  CHECK(emitted.size() >= 50);
  std::string md = read(root / "docs" / "diagnostics.md");
  std::map<std::string, std::string> sections;  // code -> its text
  std::regex heading("^## ([EW][0-9]{3,4}): ");
  std::istringstream in(md);
  std::string line, current;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_search(line, m, heading))
      current = m[1];
    else if (line.rfind("## ", 0) == 0)
      current.clear();
    if (!current.empty()) sections[current] += line + "\n";
  }
  const std::set<std::string> not_showable = {"E0001", "E0011", "E0012", "E0013"};  // bytes, files, size
  for (const auto& code : emitted) {
    INFO(code);
    REQUIRE(sections.count(code) == 1);
    // The anchor text diagnostics and SARIF logs link to (compiler::docs_link).
    std::string link = tranche::compiler::docs_link(code);
    CHECK(link.starts_with("docs/diagnostics.md#"));
    CHECK(md.find("<a id=\"" + link.substr(link.find('#') + 1) + "\"></a>\n\n## " + code + ": ") != std::string::npos);
    if (not_showable.count(code)) continue;
    CHECK(sections[code].find("[" + code + "] at") != std::string::npos);
  }
  for (const auto& [code, _] : sections) {
    INFO(code);
    CHECK(emitted.count(code) == 1);  // no section for a code that no longer exists
  }
}

TEST_CASE("docs: every field and property of the schema is described in docs/language.md") {
  std::string md = read(tranche::test::source_dir() / "docs" / "language.md");
  for (const auto& f : tranche::schema::fields()) {
    INFO(f.name);
    CHECK(md.find("| `" + std::string(f.name) + "` |") != std::string::npos);
  }
  for (const auto& p : tranche::schema::properties()) {
    INFO(p.name);
    CHECK(md.find("| `" + std::string(p.name) + "` |") != std::string::npos);
  }
}
