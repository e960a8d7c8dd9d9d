// Definition, document symbols, quick fixes and formatting.
#include <fmt/format.h>

#include <filesystem>

#include "grammar/format.h"
#include "lsp/features.h"

namespace tranche::lsp {

namespace {

// A rule's whole extent: its header and every action.
ast::Span extent(const ast::Rule& r) {
  ast::Span s = r.span;
  for (const auto& a : r.actions) {
    s = join(s, a->span);
    for (const auto& b : a->body) s = join(s, b->span);
  }
  return s;
}

}  // namespace

json definition(const Document& doc, const json& position) {
  const Analysis& a = doc.analysis;
  if (!a.program) return nullptr;
  uint32_t at = doc.offset(position);
  Found f = find_at(a, at);
  json out = json::array();
  if (f.use && f.use->file >= 0) {
    std::string path = std::filesystem::absolute(a.program->sources.file(f.use->file).path).string();
    json zero = {{"line", 0}, {"character", 0}};
    out.push_back({{"uri", path_to_uri(path)}, {"range", {{"start", zero}, {"end", zero}}}});
    return out;
  }
  std::string name;
  if (f.expr && f.expr->kind == ast::ExprKind::Name && f.expr->from_param) name = f.expr->text;
  if (f.param && f.param->name_span.offset <= at && at <= f.param->name_span.end()) name = f.param->name;
  if (!name.empty()) {
    for (const ast::Param* p : param_definitions(*a.program, name))
      if (!p->from_set) out.push_back(doc.location(p->name_span));
    return out;
  }
  // On a rule's header: the later rules that override it (the ones its W201/W213 names).
  if (f.rule && !f.expr && f.rule->span.offset <= at && at <= f.rule->span.end()) {
    for (const auto& d : a.diagnostics) {
      if ((d.code != "W201" && d.code != "W213") || d.span().file != a.file) continue;
      ast::Span s = d.span();
      ast::Span whole = extent(*f.rule);
      if (s.offset < whole.offset || s.offset > whole.end()) continue;
      for (const auto& l : d.labels)
        if (!l.primary) out.push_back(doc.location(l.span));
    }
  }
  return out.empty() ? json(nullptr) : out;
}

json document_symbols(const Document& doc) {
  json out = json::array();
  const Analysis& a = doc.analysis;
  if (!a.parsed || !a.program) return out;
  const ast::SourceMap& sources = a.program->sources;
  for (const auto& item : a.parsed->items) {
    if (item.rule) {
      const ast::Rule& r = *item.rule;
      std::string name = r.has_name ? r.name : std::string(sources.text(r.span));
      if (name.size() > 60) name = name.substr(0, 57) + "...";
      json children = json::array();
      for (const auto& s : r.actions) {
        if (s->kind != ast::StmtKind::Assign) continue;
        children.push_back({{"name", s->name}, {"kind", 7}, {"range", doc.range(s->span)},
                            {"selectionRange", doc.range(s->name_span)}});
      }
      json sym = {{"name", name}, {"kind", r.from_on ? 24 : 12}, {"range", doc.range(extent(r))},
                  {"selectionRange", doc.range(r.span)}, {"children", children}};
      if (r.filter) sym["detail"] = "when " + std::string(sources.text(r.filter->span));
      out.push_back(std::move(sym));
    } else if (item.param) {
      const ast::Param& p = *item.param;
      out.push_back({{"name", p.name}, {"kind", 14}, {"detail", std::string(sources.text(p.value->span))},
                     {"range", doc.range(p.span)}, {"selectionRange", doc.range(p.name_span)}});
    } else if (item.use) {
      out.push_back({{"name", "use \"" + item.use->target + "\""}, {"kind", 2}, {"range", doc.range(item.use->span)},
                     {"selectionRange", doc.range(item.use->target_span)}});
    }
  }
  return out;
}

json code_actions(const Document& doc, const json& params) {
  json out = json::array();
  const Analysis& a = doc.analysis;
  if (!a.program) return out;
  uint32_t from = doc.offset(params["range"]["start"]), to = doc.offset(params["range"]["end"]);
  json context = params.value("context", json::object());
  for (const auto& d : a.diagnostics) {
    ast::Span s = d.span();
    if (s.file != a.file || d.fixes.empty() || s.end() < from || s.offset > to) continue;
    json edits = json::array();
    std::string title;
    for (const auto& fix : d.fixes) {
      if (fix.span.file != a.file) continue;
      edits.push_back({{"range", doc.range(fix.span)}, {"newText", fix.replacement}});
      if (title.empty())
        title = fmt::format("{}: write `{}` instead of `{}`", d.code, fix.replacement, a.program->sources.text(fix.span));
    }
    if (edits.empty()) continue;
    // The diagnostic as the client knows it, when it sent it back.
    json diag = nullptr;
    for (const auto& c : context.value("diagnostics", json::array()))
      if (c.value("code", json()) == d.code && c.value("range", json()) == doc.range(s)) diag = c;
    json action = {{"title", title}, {"kind", "quickfix"}, {"isPreferred", d.fixes.size() == 1},
                   {"edit", {{"changes", {{doc.uri, edits}}}}}};
    if (!diag.is_null()) action["diagnostics"] = json::array({diag});
    out.push_back(std::move(action));
  }
  return out;
}

json formatting(const Document& doc) {
  ast::SourceMap sources;
  uint32_t id = sources.add(doc.path, doc.text);
  diag::Sink sink;
  auto out = grammar::format_file(sources, id, sink);
  if (!out || *out == doc.text) return json::array();
  Position end = doc.index->position(static_cast<uint32_t>(doc.text.size()));
  return json::array({{{"range", {{"start", {{"line", 0}, {"character", 0}}},
                                  {"end", {{"line", end.line}, {"character", end.character}}}}},
                       {"newText", *out}}});
}

}  // namespace tranche::lsp
