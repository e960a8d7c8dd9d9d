// The editor features, each a function of an open document and the request's parameters,
// returning the `result` of the LSP response (or the params of a notification).
#pragma once

#include "compiler/frontend.h"
#include "lsp/document.h"

namespace tranche::lsp {

// textDocument/publishDiagnostics params: the document's diagnostics as `rulec check` gives
// them (code, range, message with notes and helps, related locations, unused/deprecated tags,
// a link to docs/diagnostics.md); errors in used files are shown on the `use` that reads them.
json publish_diagnostics(const Document& doc);

// textDocument/hover: a field's or property's type, unit, stage, range, default and doc; a
// param's value and where it is set; a `use` target's path; an enum value, a function.
json hover(const Document& doc, const json& position);

// textDocument/completion: fields after `LEVEL.` (and after a loop variable: `p.`), events after
// `on LEVEL.`, enum values after `==`, `!=`, `in (` and `=` of an enum, units after a number (the
// unit of the property set or the field compared first), hook levels after `before`,
// `after`, `on` and `replace`, stdlib and relative paths in `use "..."`, else properties,
// params, functions, levels and keywords.
json completion(const Document& doc, const json& position, const compiler::FrontendOptions& options);

// textDocument/definition: a param's definitions, a `use`d file, the rules a W201/W213 names.
json definition(const Document& doc, const json& position);

// textDocument/documentSymbol: rules (and `on` events), params and `use`s.
json document_symbols(const Document& doc);

// textDocument/codeAction: a quick fix for every diagnostic in the range that suggests an edit.
json code_actions(const Document& doc, const json& params);

// textDocument/formatting: the canonical layout (grammar/format.h) as one edit; none when the
// document has syntax errors or is formatted.
json formatting(const Document& doc);

}  // namespace tranche::lsp
