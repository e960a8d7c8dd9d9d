// User documentation that must not drift from the code:
// - every ```rules block of docs/guide.md compiles as written (or gives its `# expect` diagnostic);
// - the Fields, Properties and enum tables of docs/language.md are the schema's, regenerated here;
//   its units, events and functions are those of the schema and the compiler;
// - docs/cli.md documents exactly the options `tranche --help` and `rulec --help` print;
// - relative links in the user documentation point at files that exist.
#include <array>
#include <cstdlib>
#include <cstdio>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "runtime/schema/schema.h"
#include "tests/compiler/expectations.h"
#include "tests/support/fixtures.h"

namespace fs = std::filesystem;
using namespace tranche;

namespace {

using test::Block;
using test::rules_blocks;
std::string read(const fs::path& p) { return test::read_file(p); }

// ---- schema tables ----------------------------------------------------------------------

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string enum_name(schema::EnumType t) { return std::string(schema::enum_info(t).name); }

std::string type_text(schema::Type type, schema::Unit unit, schema::EnumType e) {
  switch (type) {
    case schema::Type::Int: return "integer";
    case schema::Type::Bool: return "boolean";
    case schema::Type::Enum: return enum_name(e);
    case schema::Type::Text: return "name";
    case schema::Type::Number: break;
  }
  if (unit == schema::Unit::Ratio) return "ratio";
  if (unit == schema::Unit::None) return "number";
  return std::string(schema::unit_name(unit));
}

// A value as the documentation writes it: `0.4 mm`, `20%`, `210 °C`, `2`, `marlin`, `false`.
std::string value_text(double v, schema::Type type, schema::Unit unit, schema::EnumType e) {
  switch (type) {
    case schema::Type::Bool: return v != 0 ? "true" : "false";
    case schema::Type::Enum: return std::string(schema::enum_value_name(e, static_cast<int>(v)));
    case schema::Type::Int: return number(v);
    case schema::Type::Text: return "";
    case schema::Type::Number: break;
  }
  if (unit == schema::Unit::Ratio) return number(v * 100) + "%";
  if (unit == schema::Unit::None) return number(v);
  return number(v) + " " + std::string(schema::unit_name(unit));
}

std::string fields_table() {
  std::string t = "| field | type | known from | meaning |\n|---|---|---|---|\n";
  for (const auto& f : schema::fields())
    t += "| `" + std::string(f.name) + "` | " + type_text(f.type, f.unit, f.enum_type) + " | " +
         std::string(schema::stage_name(f.stage)) + " | " + std::string(f.doc) + " |\n";
  return t;
}

std::string properties_table() {
  std::string t =
      "| property | type | decided at | physical range | default | meaning |\n|---|---|---|---|---|---|\n";
  for (const auto& p : schema::properties()) {
    bool ranged = p.type == schema::Type::Number || p.type == schema::Type::Int;
    std::string range = ranged ? value_text(p.min, p.type, p.unit, p.enum_type) + " – " +
                                     value_text(p.max, p.type, p.unit, p.enum_type)
                               : "";
    t += "| `" + std::string(p.name) + "` | " + type_text(p.type, p.unit, p.enum_type) + " | " +
         std::string(schema::stage_name(p.stage)) + " | " + range + " | " +
         value_text(p.default_value, p.type, p.unit, p.enum_type) + " | " + std::string(p.doc) + " |\n";
  }
  return t;
}

std::string enums_table() {
  std::string t = "| enum | values |\n|---|---|\n";
  for (const auto& e : schema::enums()) {
    if (e.id == schema::EnumType::None) continue;
    std::vector<std::string> users;
    for (const auto& f : schema::fields())
      if (f.type == schema::Type::Enum && f.enum_type == e.id) users.push_back("`" + std::string(f.name) + "`");
    for (const auto& p : schema::properties())
      if (p.type == schema::Type::Enum && p.enum_type == e.id) users.push_back("`" + std::string(p.name) + "`");
    std::string row = "| `" + std::string(e.name) + "` (";
    for (size_t i = 0; i < users.size(); ++i) row += (i ? ", " : "") + users[i];
    row += ") | ";
    for (size_t i = 0; i < e.values.size(); ++i) row += (i ? ", `" : "`") + std::string(e.values[i]) + "`";
    t += row + " |\n";
  }
  return t;
}

// The first markdown table after the line `anchor` (a heading, or the table's header line).
std::string table_after(const std::string& md, const std::string& anchor) {
  size_t at = md.find(anchor);
  if (at == std::string::npos) return "";
  std::istringstream in(md.substr(at));
  std::string line, table;
  bool started = false;
  while (std::getline(in, line)) {
    bool row = line.rfind("|", 0) == 0;
    if (row) {
      started = true;
      table += line + "\n";
    } else if (started) {
      break;
    }
  }
  return table;
}

// ---- command-line help ------------------------------------------------------------------

std::string run(const std::string& cmd) {
  std::string out;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return out;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
  pclose(p);
  return out;
}

std::set<std::string> options_in(const std::string& text) {
  std::set<std::string> out;
  std::regex opt(R"((^|[\s`(,])(--?[a-zA-Z][a-zA-Z-]*))");
  for (std::sregex_iterator it(text.begin(), text.end(), opt), end; it != end; ++it) out.insert((*it)[2]);
  return out;
}

// The options a --help text lists: the first column of the lines after "options:".
std::set<std::string> help_options(const std::string& help) {
  std::istringstream in(help);
  std::string line, column;
  bool in_options = false;
  while (std::getline(in, line)) {
    if (line == "options:") in_options = true;
    size_t start = line.find_first_not_of(' ');
    if (!in_options || start == std::string::npos || line[start] != '-') continue;
    size_t gap = line.find("  ", start);
    column += line.substr(start, gap == std::string::npos ? std::string::npos : gap - start) + "\n";
  }
  return options_in(column);
}

// The options of the `| option | meaning |` tables of one section (from `heading` to the next `## `).
std::set<std::string> documented_options(const std::string& md, const std::string& heading) {
  size_t at = md.find("\n" + heading + "\n");
  REQUIRE_MESSAGE(at != std::string::npos, heading);
  size_t end = md.find("\n## ", at + 1);
  std::istringstream in(md.substr(at, end == std::string::npos ? std::string::npos : end - at));
  std::string line, cells;
  bool in_options = false;
  while (std::getline(in, line)) {
    if (line.rfind("| option |", 0) == 0) in_options = true;
    else if (line.rfind("|", 0) != 0) in_options = false;
    else if (in_options && line.rfind("|---", 0) != 0) cells += line.substr(0, line.find(" | ")) + "\n";
  }
  return options_in(cells);
}

}  // namespace

TEST_CASE("docs/guide.md: every rules block checks as documented") {
  fs::path root = test::source_dir();
  std::string md = read(root / "docs" / "guide.md");
  REQUIRE_FALSE(md.empty());
  auto blocks = rules_blocks(md);
  CHECK(blocks.size() >= 15);
  bool replacer = false;
  for (const auto& b : blocks) {
    replacer = replacer || b.text.find("replace path") != std::string::npos;
    std::string name = "guide.md-line" + std::to_string(b.line) + ".rules";
    std::string problems = test::run_case(root / "docs", name, b.text, root / "stdlib", /*default_ok=*/true);
    INFO("guide.md block at line " << b.line << "\n" << b.text << problems);
    CHECK(problems.empty());
  }
  CHECK(replacer);  // the tutorial goes as far as a replacer
}

namespace {
// The table of docs/language.md that follows `heading` reads `want`.
// With TRANCHE_WRITE_DOCS_TABLES=1 in the environment, a table that differs is rewritten in
// docs/language.md (after a schema change) instead of failing.
void check_table(const std::string& heading, const std::string& want, const std::string& what) {
  const fs::path path = test::source_dir() / "docs" / "language.md";
  std::string md = read(path);
  const std::string have = table_after(md, heading);
  if (have != want && std::getenv("TRANCHE_WRITE_DOCS_TABLES") && !have.empty()) {
    md.replace(md.find(have, md.find(heading)), have.size(), want);
    std::ofstream(path, std::ios::binary) << md;
    return;
  }
  CHECK_MESSAGE(have == want, "docs/language.md, " << what << ", should read:\n\n" << want
                                                   << "\n(TRANCHE_WRITE_DOCS_TABLES=1 rewrites it)");
}
}  // namespace

TEST_CASE("docs/language.md: the Fields table is the schema's") {
  check_table("\n## Fields\n", fields_table(), "## Fields");
}

TEST_CASE("docs/language.md: the Properties table is the schema's") {
  check_table("\n## Properties\n", properties_table(), "## Properties");
}

TEST_CASE("docs/language.md: the enum table is the schema's") {
  check_table("\n| enum | values |\n", enums_table(), "the enum table");
}

TEST_CASE("docs/language.md: every unit and context level of the schema is described") {
  std::string md = read(test::source_dir() / "docs" / "language.md");
  std::string units = table_after(md, "\n| quantity | written | example |\n");
  for (int u = 0; u <= static_cast<int>(schema::Unit::Celsius); ++u) {
    std::string name(schema::unit_name(static_cast<schema::Unit>(u)));
    if (name.empty()) continue;
    INFO(name);
    CHECK(units.find("`" + name) != std::string::npos);
  }
  for (int l = 0; l < schema::kLevelCount; ++l) {
    std::string level(schema::level_name(static_cast<schema::Level>(l)));
    INFO(level);
    CHECK(md.find("`" + level + ".") != std::string::npos);  // its fields
  }
}

namespace {

// Compiles `text` as docs/NAME; returns every diagnostic, rendered as text.
std::string diagnostics_of(const std::string& text) {
  compiler::FrontendOptions options;
  options.stdlib_dir = (test::source_dir() / "stdlib").string();
  diag::Sink sink;
  ast::Program program;
  compiler::load_source(program, (test::source_dir() / "docs" / "probe.rules").string(), text, options, sink);
  if (compiler::check(program, sink) && !sink.has_errors()) compiler::lint(program, sink);
  sink.finish({});
  std::string out;
  for (const auto& d : sink.all()) out += compiler::render_text(program.sources, d, false);
  return out;
}

}  // namespace

TEST_CASE("docs/language.md: the functions table lists every function the compiler knows") {
  std::string md = read(test::source_dir() / "docs" / "language.md");
  std::string table = table_after(md, "\n| function | arguments | result |\n");
  REQUIRE_FALSE(table.empty());
  // The compiler names its functions when it meets an unknown one.
  std::string d = diagnostics_of("rule { speed = nosuchfunction(1 mm/s) }\n");
  std::smatch m;
  REQUIRE_MESSAGE(std::regex_search(d, m, std::regex("functions are ([^\n]*)")), d);
  std::string list = m[1];
  std::regex name("`([a-z0-9_]+)`");
  int n = 0;
  for (std::sregex_iterator it(list.begin(), list.end(), name), end; it != end; ++it, ++n) {
    INFO((*it)[1]);
    CHECK(table.find("`" + std::string((*it)[1]) + "(") != std::string::npos);
  }
  CHECK(n >= 10);
}

TEST_CASE("docs/language.md: every event is described, and compiles") {
  std::string md = read(test::source_dir() / "docs" / "language.md");
  for (int l = 0; l < schema::kLevelCount; ++l) {
    auto level = static_cast<schema::Level>(l);
    if (level == schema::Level::Piece) continue;  // pieces are reached by looping over path.pieces
    std::string name(schema::level_name(level));
    INFO(name);
    CHECK(md.find("\"" + name + "\"") != std::string::npos);  // in the grammar's LEVEL
    for (const char* event : {"start", "end"})
      CHECK(diagnostics_of("on " + name + "." + event + " { comment \"x\" }\n").empty());
  }
  CHECK_FALSE(diagnostics_of("on piece.start { comment \"x\" }\n").empty());
}

TEST_CASE("docs/cli.md: documents exactly the options of tranche --help and rulec --help") {
  fs::path root = test::source_dir(), bin = test::binary_dir() / "apps";
  std::string md = read(root / "docs" / "cli.md");
  REQUIRE_FALSE(md.empty());
  struct Tool {
    std::string heading, help;
  };
  for (const Tool& t : {Tool{"## `tranche slice`", run("'" + (bin / "tranche").string() + "' --help")},
                        Tool{"## `rulec`", run("'" + (bin / "rulec").string() + "' --help")}}) {
    INFO(t.heading << "\n" << t.help);
    auto in_help = help_options(t.help);
    REQUIRE(in_help.size() >= 8);
    auto in_doc = documented_options(md, t.heading);
    for (const auto& o : in_help) CHECK_MESSAGE(in_doc.count(o) == 1, o << " is in --help but not in docs/cli.md");
    for (const auto& o : in_doc) CHECK_MESSAGE(in_help.count(o) == 1, o << " is in docs/cli.md but not in --help");
  }
}

TEST_CASE("docs: relative links in the user documentation point at existing files") {
  fs::path root = test::source_dir();
  std::vector<fs::path> pages = {root / "README.md", root / "stdlib" / "README.md", root / "examples" / "README.md",
                                 root / "editors" / "README.md"};
  for (const auto& e : fs::directory_iterator(root / "docs"))
    if (e.path().extension() == ".md") pages.push_back(e.path());
  for (const auto& e : fs::directory_iterator(root / "examples"))
    if (fs::exists(e.path() / "README.md")) pages.push_back(e.path() / "README.md");
  std::regex link(R"(\]\(([^)#\s]+)(#[^)]*)?\))");
  int links = 0;
  for (const auto& page : pages) {
    std::string md = read(page);
    REQUIRE_MESSAGE(!md.empty(), page);
    for (std::sregex_iterator it(md.begin(), md.end(), link), end; it != end; ++it) {
      std::string target = (*it)[1];
      if (target.find("://") != std::string::npos || target.rfind("mailto:", 0) == 0) continue;
      ++links;
      CHECK_MESSAGE(fs::exists(page.parent_path() / target), page.string() << " links to " << target);
    }
  }
  CHECK(links >= 20);
  // The README's promise: docs/cli.md exists and is linked.
  CHECK(read(root / "README.md").find("docs/cli.md") != std::string::npos);
}

namespace {

// The top-level folders of the checkout that belong to the tree: not hidden (.git, .ci), not
// ignored by a root-anchored folder pattern of .gitignore (/build*/, /out/), not a build tree.
std::set<std::string> top_level_folders(const fs::path& root) {
  std::vector<std::string> ignored;  // patterns such as "build*" or "out"
  std::istringstream gitignore(read(root / ".gitignore"));
  for (std::string line; std::getline(gitignore, line);)
    if (line.size() > 2 && line.front() == '/' && line.back() == '/')
      ignored.push_back(line.substr(1, line.size() - 2));
  auto is_ignored = [&](const std::string& name) {
    for (const auto& p : ignored) {
      const auto star = p.find('*');
      if (star == std::string::npos ? name == p : name.starts_with(p.substr(0, star))) return true;
    }
    return false;
  };
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(root)) {
    const std::string name = e.path().filename().string();
    if (!e.is_directory() || name.starts_with('.') || is_ignored(name)) continue;
    if (fs::exists(e.path() / "CMakeCache.txt")) continue;
    out.insert(name);
  }
  return out;
}

// The folders the README's layout table names in its first column (`name/`).
std::set<std::string> layout_folders(const std::string& layout) {
  std::set<std::string> out;
  std::istringstream rows(layout);
  const std::regex folder(R"(`([A-Za-z0-9_.-]+)/`)");
  for (std::string row; std::getline(rows, row);) {
    if (!row.starts_with("| `")) continue;
    const std::string first = row.substr(0, row.find('|', 1));
    for (std::sregex_iterator it(first.begin(), first.end(), folder), end; it != end; ++it)
      out.insert((*it)[1]);
  }
  return out;
}

}  // namespace

TEST_CASE("README.md: the layout table names every top-level folder and every geometry stage") {
  const fs::path root = test::source_dir();
  const std::string readme = read(root / "README.md");
  REQUIRE(readme.find("## Layout") != std::string::npos);
  std::string layout = readme.substr(readme.find("## Layout"));
  layout = layout.substr(0, layout.find("\n## ", 1));
  const auto real = top_level_folders(root);
  const auto named = layout_folders(layout);
  REQUIRE(real.size() >= 10);
  for (const auto& f : real)
    CHECK_MESSAGE(named.count(f) == 1, f << "/ is a top-level folder missing from README.md's layout table");
  for (const auto& f : named)
    CHECK_MESSAGE(real.count(f) == 1,
                  "README.md's layout table names " << f << "/, which is not a top-level folder");
  const std::string geometry_row = layout.substr(layout.find("| `geometry/` |"));
  const std::string row = geometry_row.substr(0, geometry_row.find('\n'));
  for (const auto& e : fs::directory_iterator(root / "geometry")) {
    if (!e.is_directory()) continue;
    INFO(e.path().filename().string());
    CHECK(row.find("`" + e.path().filename().string() + "`") != std::string::npos);
  }
}
