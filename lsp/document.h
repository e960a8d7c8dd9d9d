// An open document: its text as the editor has it, and the analysis of that text.
#pragma once

#include <nlohmann/json.hpp>

#include <memory>
#include <optional>
#include <string>

#include "grammar/ast/source.h"
#include "lsp/analysis.h"
#include "lsp/protocol.h"

namespace tranche::lsp {

using json = nlohmann::json;

struct Document {
  std::string uri, path, text;
  int64_t version = 0;
  Analysis analysis;
  std::unique_ptr<LineIndex> index;  // over `text`, rebuilt with it

  // Applies one `contentChanges` entry (a range and its new text, or the whole text).
  void apply(const json& change);
  void reindex() { index = std::make_unique<LineIndex>(text); }
  uint32_t offset(const json& position) const;
  // An LSP range for a span of any file of the analysis (the document's own, or a used file's).
  json range(const ast::Span& span) const;
  // The location of a span: its file's URI and range.
  json location(const ast::Span& span) const;
};

}  // namespace tranche::lsp
