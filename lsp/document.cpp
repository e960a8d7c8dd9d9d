#include "lsp/document.h"

namespace tranche::lsp {

void Document::apply(const json& change) {
  if (!change.contains("range")) {
    text = change.value("text", std::string());
    reindex();
    return;
  }
  uint32_t from = offset(change["range"]["start"]);
  uint32_t to = std::max(from, offset(change["range"]["end"]));
  text.replace(from, to - from, change.value("text", std::string()));
  reindex();
}

uint32_t Document::offset(const json& position) const {
  Position p{position.value("line", 0u), position.value("character", 0u)};
  return index->offset(p);
}

json Document::range(const ast::Span& span) const {
  const ast::SourceMap* sources = analysis.program ? &analysis.program->sources : nullptr;
  Position a, b;
  if (span.file == analysis.file || !sources || span.file >= sources->size()) {
    a = index->position(span.offset);
    b = index->position(span.end());
  } else {
    LineIndex other(sources->file(span.file).text);
    a = other.position(span.offset);
    b = other.position(span.end());
  }
  if (!span.valid()) a = b = Position{};
  return {{"start", {{"line", a.line}, {"character", a.character}}},
          {"end", {{"line", b.line}, {"character", b.character}}}};
}

json Document::location(const ast::Span& span) const {
  std::string target = uri;
  if (span.file != analysis.file && analysis.program && span.file < analysis.program->sources.size())
    target = path_to_uri(std::filesystem::absolute(analysis.program->sources.file(span.file).path).string());
  return {{"uri", target}, {"range", range(span)}};
}

}  // namespace tranche::lsp
