// Diagnostics for the editor: the compiler's, in LSP's shape.
#include <algorithm>
#include <cctype>
#include <filesystem>

#include "lsp/features.h"

namespace tranche::lsp {

namespace {

// Diagnostics about code that does nothing: editors fade it (DiagnosticTag.Unnecessary).
bool unnecessary(const std::string& code) {
  return code == "W200" || code == "W201" || code == "W207" || code == "W209" || code == "W212" ||
         code == "W213";
}

// file:///.../docs/diagnostics.md#e0102 in the checkout the server was built from, if it is there.
std::string docs_href(const std::string& code) {
#ifdef TRANCHE_DOCS_DIR
  static const std::string page = [] {
    std::error_code ec;
    std::filesystem::path p = std::filesystem::path(TRANCHE_DOCS_DIR) / "diagnostics.md";
    return std::filesystem::exists(p, ec) ? path_to_uri(p.string()) : std::string();
  }();
  if (page.empty()) return {};
  std::string anchor = code;
  std::transform(anchor.begin(), anchor.end(), anchor.begin(), [](unsigned char c) { return std::tolower(c); });
  return page + "#" + anchor;
#else
  (void)code;
  return {};
#endif
}

json one(const Document& doc, const diag::Diagnostic& d, const ast::Span& at, const std::string& prefix) {
  std::string message = prefix + d.message;
  for (const auto& n : d.notes) message += "\nnote: " + n;
  for (const auto& h : d.helps) message += "\nhelp: " + h;
  json out = {{"range", doc.range(at)},
              {"severity", d.severity == diag::Severity::Error ? 1 : 2},
              {"code", d.code},
              {"source", "rulec"},
              {"message", message}};
  if (std::string href = docs_href(d.code); !href.empty()) out["codeDescription"] = {{"href", href}};
  json related = json::array();
  for (const auto& l : d.labels) {
    if (l.primary || !doc.analysis.program || l.span.file >= doc.analysis.program->sources.size()) continue;
    related.push_back({{"location", doc.location(l.span)}, {"message", l.text.empty() ? d.message : l.text}});
  }
  if (!related.empty()) out["relatedInformation"] = related;
  if (unnecessary(d.code)) out["tags"] = json::array({1});
  return out;
}

}  // namespace

json publish_diagnostics(const Document& doc) {
  json list = json::array();
  const Analysis& a = doc.analysis;
  bool shown_elsewhere = false;
  for (const auto& d : a.diagnostics) {
    ast::Span at = d.span();
    if (at.file == a.file) {
      list.push_back(one(doc, d, at, ""));
      continue;
    }
    // In a used file: on the `use` that reads it (or the first one), errors only, once per file.
    if (d.severity != diag::Severity::Error || shown_elsewhere || !a.parsed || !a.program) continue;
    const ast::Use* use = nullptr;
    for (const auto& item : a.parsed->items)
      if (item.use && (!use || item.use->file == static_cast<int>(at.file))) use = item.use.get();
    if (!use) continue;
    shown_elsewhere = true;
    std::string where = at.file < a.program->sources.size() ? a.program->sources.file(at.file).path : "?";
    json d_json = one(doc, d, use->target_span, "in " + where + ":" + std::to_string(at.line) + ": ");
    d_json["relatedInformation"] = json::array({{{"location", doc.location(at)}, {"message", d.message}}});
    list.push_back(d_json);
  }
  return {{"uri", doc.uri}, {"version", doc.version}, {"diagnostics", list}};
}

}  // namespace tranche::lsp
