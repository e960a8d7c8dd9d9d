// Inline expectations for .rules cases (tests/language/*.rules and the examples in docs/):
//   # expect ok                             no diagnostic at all
//   # expect error[E0102] at 3:21           an error with this code, primary span at line 3, column 21
//   # expect warning[W201] at 5:1           a warning
//   # expect error[E0010] at lib/a.rules:2:5   in another file (path relative to the case's folder)
//   # expect error[E0100] at 2:15: `layer_nr` is Cura's    ... whose text (message, labels, notes,
//                                                          helps) contains this
// Cases named `mistake_*.rules` (typical mistakes of users) must also give a help with every
// diagnostic.
//   # set speed=40                          also check `--set speed=40`
// The run fails on any missing or unexpected diagnostic.
#pragma once

#include <doctest/doctest.h>

#include <filesystem>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "compiler/check.h"
#include "compiler/diagnostics.h"
#include "compiler/frontend.h"

namespace tranche::test {

// The ```rules blocks of a markdown file, with the line of each block's first line.
struct Block {
  int line;
  std::string text;
};
inline std::vector<Block> rules_blocks(const std::string& md) {
  std::vector<Block> out;
  std::istringstream in(md);
  std::string line;
  int n = 0;
  bool open = false;
  while (std::getline(in, line)) {
    ++n;
    if (!open && line == "```rules") {
      out.push_back(Block{n + 1, ""});
      open = true;
    } else if (open && line == "```") {
      open = false;
    } else if (open) {
      out.back().text += line + "\n";
    }
  }
  return out;
}

struct Expected {
  std::string level, code, file;
  uint32_t line = 0, col = 0;
  std::string text;  // not part of the key: checked against the diagnostic's rendering
  auto key() const { return std::tie(level, code, file, line, col); }
  bool operator<(const Expected& o) const { return key() < o.key(); }
  std::string str() const {
    return level + "[" + code + "] at " + file + ":" + std::to_string(line) + ":" + std::to_string(col);
  }
};

struct Case {
  std::multiset<Expected> expected;
  bool expect_ok = false;
  std::vector<std::pair<std::string, std::string>> sets;
};

inline Case parse_expectations(const std::string& text, const std::string& file) {
  Case c;
  static const std::regex expect(
      R"(#\s*expect\s+(ok|(error|warning)\[([EW][0-9]+)\]\s+at\s+(?:(\S+):)?([0-9]+):([0-9]+)(?::\s*(.*\S))?))");
  static const std::regex set(R"(#\s*set\s+([A-Za-z_0-9]+)=(.*))");
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find('\n', start);
    std::string line = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::smatch m;
    if (std::regex_search(line, m, expect)) {
      if (m[1] == "ok") {
        c.expect_ok = true;
      } else {
        Expected e;
        e.level = m[2];
        e.code = m[3];
        e.file = m[4].matched ? std::string(m[4]) : file;
        e.line = static_cast<uint32_t>(std::stoul(m[5]));
        e.col = static_cast<uint32_t>(std::stoul(m[6]));
        if (m[7].matched) e.text = m[7];
        c.expected.insert(e);
      }
    } else if (std::regex_search(line, m, set)) {
      c.sets.emplace_back(m[1], m[2]);
    }
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return c;
}

// Checks `text` as the file `dir/name` (uses resolve from `dir`, stdlib names from `stdlib`).
// Returns a description of every mismatch; empty when the case passes.
// With `default_ok`, a case without `# expect` lines must give no diagnostic (documentation
// examples); otherwise it is an error to have none.
inline std::string run_case(const std::filesystem::path& dir, const std::string& name,
                            const std::string& text, const std::filesystem::path& stdlib,
                            bool default_ok = false) {
  Case c = parse_expectations(text, name);
  if (!c.expect_ok && c.expected.empty()) {
    if (!default_ok) return "no `# expect` line";
    c.expect_ok = true;
  }
  compiler::FrontendOptions options;
  options.stdlib_dir = stdlib.string();
  diag::Sink sink;
  ast::Program program;
  compiler::load_source(program, (dir / name).string(), text, options, sink);
  for (const auto& [k, v] : c.sets) compiler::add_set(program, k, v, sink);
  if (compiler::check(program, sink) && !sink.has_errors()) compiler::lint(program, sink);
  sink.finish({});

  std::multiset<Expected> got;
  std::string rendered, problems;
  std::vector<std::pair<Expected, std::string>> texts;  // each diagnostic and its rendering
  bool mistake = name.starts_with("mistake_");
  for (const auto& d : sink.all()) {
    Expected e;
    e.level = d.severity == diag::Severity::Error ? "error" : "warning";
    e.code = d.code;
    ast::Span s = d.span();
    std::filesystem::path p = program.sources.file(s.file).path;
    e.file = p.is_absolute() ? p.lexically_relative(dir).string() : p.string();
    e.line = s.line;
    e.col = s.col;
    got.insert(e);
    std::string shown = compiler::render_text(program.sources, d, false);
    rendered += shown;
    texts.emplace_back(e, shown);
    if (mistake && d.helps.empty()) problems += "  no help:    " + e.str() + "\n";
    std::string json = compiler::render_json(program.sources, d);
    if (json.empty() || json.front() != '{' || json.back() != '}' || json.find('\n') != std::string::npos)
      return "bad JSON for " + e.str() + ": " + json;
  }
  for (const auto& e : c.expected) {
    if (e.text.empty()) continue;
    bool found = false;
    for (const auto& [g, shown] : texts) found = found || (g.key() == e.key() && shown.find(e.text) != std::string::npos);
    if (!found) problems += "  not said:   " + e.str() + ": " + e.text + "\n";
  }
  std::multiset<Expected> missing, unexpected;
  for (const auto& e : c.expected)
    if (got.count(e) < c.expected.count(e) && !missing.count(e)) missing.insert(e);
  for (const auto& e : got)
    if (c.expected.count(e) < got.count(e) && !unexpected.count(e)) unexpected.insert(e);
  for (const auto& e : missing) problems += "  missing:    " + e.str() + "\n";
  for (const auto& e : unexpected) problems += "  unexpected: " + e.str() + "\n";
  if (!problems.empty()) problems += "diagnostics:\n" + rendered;
  return problems;
}

}  // namespace tranche::test
