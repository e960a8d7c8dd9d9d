#include "compiler/diagnostics.h"

#include <fmt/format.h>

#include <cctype>
#include <set>

#include <algorithm>
#include <map>

namespace tranche::compiler {

namespace {

struct Style {
  bool on;
  std::string paint(std::string_view s, const char* code) const {
    return on ? fmt::format("\x1b[{}m{}\x1b[0m", code, s) : std::string(s);
  }
};
constexpr const char* kRed = "1;31";
constexpr const char* kYellow = "1;33";
constexpr const char* kBlue = "1;34";
constexpr const char* kBold = "1";

// A source line as shown: tabs become four spaces. `col` (1-based) maps to a display column.
struct ShownLine {
  std::string text;
  std::vector<uint32_t> display_col;  // per character of the original line, + end
};

ShownLine show(std::string_view line) {
  ShownLine s;
  uint32_t col = 0;
  for (size_t i = 0; i < line.size();) {
    unsigned char c = static_cast<unsigned char>(line[i]);
    size_t n = c < 0x80 ? 1 : c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC0 ? 2 : 1;
    n = std::min(n, line.size() - i);
    s.display_col.push_back(col);
    if (c == '\t') {
      s.text += "    ";
      col += 4;
    } else {
      s.text += line.substr(i, n);
      col += 1;
    }
    i += n;
  }
  s.display_col.push_back(col);
  return s;
}

std::string location(const ast::SourceMap& sources, const ast::Span& span) {
  const auto& path = sources.file(span.file).path;
  if (!span.valid()) return path;
  return fmt::format("{}:{}:{}", path, span.line, span.col);
}

}  // namespace

std::string render_text(const ast::SourceMap& sources, const diag::Diagnostic& d, bool color) {
  Style st{color};
  bool error = d.severity == diag::Severity::Error;
  const char* tone = error ? kRed : kYellow;
  std::string out = st.paint(fmt::format("{}[{}]", error ? "error" : "warning", d.code), tone) +
                    st.paint(fmt::format(": {}", d.message), kBold) + "\n";

  // Labels grouped by file and line, in order; the primary label's file comes first.
  std::vector<const diag::Label*> labels;
  for (const auto& l : d.labels)
    if (l.span.file < sources.size()) labels.push_back(&l);
  uint32_t width = 1;
  for (const auto* l : labels)
    width = std::max<uint32_t>(width, static_cast<uint32_t>(std::to_string(l->span.line).size()));
  std::string pad(width, ' ');

  const ast::Span primary = d.span();
  if (primary.file < sources.size()) {
    out += fmt::format("{}{} {}\n", pad, st.paint("-->", kBlue), location(sources, primary));
  }
  std::map<std::pair<uint32_t, uint32_t>, std::vector<const diag::Label*>> by_line;
  for (const auto* l : labels)
    if (l->span.valid()) by_line[{l->span.file, l->span.line}].push_back(l);
  if (!by_line.empty()) {
    uint32_t current_file = primary.file;
    out += fmt::format("{} {}\n", pad, st.paint("|", kBlue));
    // The primary file first, then the others.
    std::vector<std::pair<uint32_t, uint32_t>> order;
    for (const auto& [key, _] : by_line)
      if (key.first == primary.file) order.push_back(key);
    for (const auto& [key, _] : by_line)
      if (key.first != primary.file) order.push_back(key);
    for (const auto& key : order) {
      auto& line_labels = by_line[key];
      if (key.first != current_file) {
        current_file = key.first;
        out += fmt::format("{}{} {}\n", pad, st.paint(":::", kBlue), location(sources, line_labels[0]->span));
        out += fmt::format("{} {}\n", pad, st.paint("|", kBlue));
      }
      ShownLine shown = show(sources.line_text(key.first, key.second));
      out += st.paint(fmt::format("{:>{}} |", key.second, width), kBlue) + " " + shown.text + "\n";
      std::sort(line_labels.begin(), line_labels.end(), [](auto* a, auto* b) {
        return a->primary != b->primary ? a->primary : a->span.col < b->span.col;
      });
      for (const auto* l : line_labels) {
        size_t first = std::min<size_t>(l->span.col - 1, shown.display_col.size() - 1);
        auto [end_line, end_col] = sources.line_col(l->span.file, l->span.end());
        size_t last = end_line == l->span.line ? std::min<size_t>(end_col - 1, shown.display_col.size() - 1)
                                               : shown.display_col.size() - 1;
        uint32_t from = shown.display_col[first];
        uint32_t to = std::max(shown.display_col[last], from + 1);
        std::string marks(to - from, l->primary ? '^' : '-');
        std::string text = l->text.empty() ? marks : marks + " " + l->text;
        out += st.paint(fmt::format("{} |", pad), kBlue) + " " + std::string(from, ' ') +
               st.paint(text, l->primary ? tone : kBlue) + "\n";
      }
    }
  }
  if (!by_line.empty()) out += fmt::format("{} {}\n", pad, st.paint("|", kBlue));
  for (const auto& n : d.notes)
    out += fmt::format("{} {} {}\n", pad, st.paint("=", kBlue), st.paint("note", kBold) + ": " + n);
  for (const auto& h : d.helps)
    out += fmt::format("{} {} {}\n", pad, st.paint("=", kBlue), st.paint("help", kBold) + ": " + h);
  out += fmt::format("{} {} {}\n", pad, st.paint("=", kBlue), st.paint("docs", kBold) + ": " + docs_link(d.code));
  return out;
}

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (c < 0x20 || c == 0x7F) {
          out += fmt::format("\\u{:04x}", c);
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  return out + "\"";
}

std::string render_json(const ast::SourceMap& sources, const diag::Diagnostic& d) {
  std::string out =
      fmt::format("{{\"code\":{},\"level\":\"{}\",\"message\":{},\"spans\":[", json_string(d.code),
                  d.severity == diag::Severity::Error ? "error" : "warning", json_string(d.message));
  bool first = true;
  for (const auto& l : d.labels) {
    if (l.span.file >= sources.size()) continue;
    if (!first) out += ",";
    first = false;
    auto [end_line, end_col] =
        l.span.valid() ? sources.line_col(l.span.file, l.span.end()) : std::pair<uint32_t, uint32_t>{0, 0};
    out += fmt::format(
        "{{\"file\":{},\"line\":{},\"col\":{},\"end_line\":{},\"end_col\":{},\"byte_start\":{},\"byte_end\":{"
        "},"
        "\"label\":{},\"primary\":{}}}",
        json_string(sources.file(l.span.file).path), l.span.line, l.span.col, end_line, end_col,
        l.span.offset, l.span.end(), json_string(l.text), l.primary ? "true" : "false");
  }
  out += "],\"notes\":[";
  for (size_t i = 0; i < d.notes.size(); ++i) {
    if (i) out += ',';
    out += json_string(d.notes[i]);
  }
  out += "],\"helps\":[";
  for (size_t i = 0; i < d.helps.size(); ++i) {
    if (i) out += ',';
    out += json_string(d.helps[i]);
  }
  out += "],\"fixes\":[";
  for (size_t i = 0; i < d.fixes.size(); ++i) {
    const diag::Fix& f = d.fixes[i];
    if (f.span.file >= sources.size()) continue;
    out += fmt::format("{}{{\"file\":{},\"byte_start\":{},\"byte_end\":{},\"replacement\":{}}}", i ? "," : "",
                       json_string(sources.file(f.span.file).path), f.span.offset, f.span.end(),
                       json_string(f.replacement));
  }
  return out + "]}";
}

std::string render_sarif(const ast::SourceMap& sources, const std::vector<diag::Diagnostic>& all) {
  // SARIF 2.1.0: one run of rulec, one result per diagnostic, its primary span as the location
  // and the secondary ones as related locations; notes and helps are appended to the message.
  std::set<std::string> codes;
  for (const auto& d : all) codes.insert(d.code);
  std::string out =
      "{\"$schema\":\"https://json.schemastore.org/sarif-2.1.0.json\",\"version\":\"2.1.0\",\"runs\":[{"
      "\"tool\":{\"driver\":{\"name\":\"rulec\",\"informationUri\":\"docs/diagnostics.md\",\"rules\":[";
  bool first = true;
  for (const auto& c : codes) {
    out += fmt::format("{}{{\"id\":{},\"helpUri\":{}}}", first ? "" : ",", json_string(c),
                       json_string(docs_link(c)));
    first = false;
  }
  out += "]}},\"results\":[";
  auto location = [&](const diag::Label& l) {
    auto [end_line, end_col] =
        l.span.valid() ? sources.line_col(l.span.file, l.span.end()) : std::pair<uint32_t, uint32_t>{0, 0};
    std::string region = l.span.valid() ? fmt::format(",\"region\":{{\"startLine\":{},\"startColumn\":{},"
                                                      "\"endLine\":{},\"endColumn\":{}}}",
                                                      l.span.line, l.span.col, end_line, end_col)
                                        : std::string();
    std::string msg = l.text.empty() ? std::string() : fmt::format(",\"message\":{{\"text\":{}}}", json_string(l.text));
    return fmt::format("{{\"physicalLocation\":{{\"artifactLocation\":{{\"uri\":{}}}{}}}{}}}",
                       json_string(sources.file(l.span.file).path), region, msg);
  };
  first = true;
  for (const auto& d : all) {
    std::string text = d.message;
    for (const auto& n : d.notes) text.append("\nnote: ").append(n);
    for (const auto& h : d.helps) text.append("\nhelp: ").append(h);
    out += fmt::format("{}{{\"ruleId\":{},\"level\":\"{}\",\"message\":{{\"text\":{}}}", first ? "" : ",",
                       json_string(d.code), d.severity == diag::Severity::Error ? "error" : "warning",
                       json_string(text));
    first = false;
    std::string primary, related;
    for (const auto& l : d.labels) {
      if (l.span.file >= sources.size()) continue;
      if (primary.empty())
        primary = location(l);
      else
        related.append(related.empty() ? "" : ",").append(location(l));
    }
    if (!primary.empty()) out.append(",\"locations\":[").append(primary).append("]");
    if (!related.empty()) out.append(",\"relatedLocations\":[").append(related).append("]");
    // The suggested edits, as SARIF fixes (one fix: all of them together).
    std::string changes;
    for (const auto& f : d.fixes) {
      if (f.span.file >= sources.size() || !f.span.valid()) continue;
      auto [end_line, end_col] = sources.line_col(f.span.file, f.span.end());
      changes += fmt::format(
          "{}{{\"artifactLocation\":{{\"uri\":{}}},\"replacements\":[{{\"deletedRegion\":{{\"startLine\":{},"
          "\"startColumn\":{},\"endLine\":{},\"endColumn\":{}}},\"insertedContent\":{{\"text\":{}}}}}]}}",
          changes.empty() ? "" : ",", json_string(sources.file(f.span.file).path), f.span.line, f.span.col, end_line,
          end_col, json_string(f.replacement));
    }
    if (!changes.empty())
      out += fmt::format(",\"fixes\":[{{\"description\":{{\"text\":{}}},\"artifactChanges\":[{}]}}]",
                         json_string(d.helps.empty() ? d.message : d.helps[0]), changes);
    out += "}";
  }
  return out + "]}]}\n";
}

std::string docs_link(std::string_view code) {
  std::string anchor(code);
  for (char& c : anchor) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return "docs/diagnostics.md#" + anchor;
}

std::string summary(size_t errors, size_t warnings) {
  auto plural = [](size_t n, const char* word) { return fmt::format("{} {}{}", n, word, n == 1 ? "" : "s"); };
  return plural(errors, "error") + ", " + plural(warnings, "warning");
}

}  // namespace tranche::compiler
