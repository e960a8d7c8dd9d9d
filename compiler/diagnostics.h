// Rendering diagnostics (grammar/ast/diagnostic.h) for people and for tools.
//
// Text, in the rustc/clang style: header with the code, `-->` location, the source line with
// `^^^` under the primary span and `---` under secondary ones, then `= note:`, `= help:` and
// `= docs:` (the code's section of docs/diagnostics.md).
// JSON: one object per diagnostic, on one line:
//   {"code":"E0102","level":"error","message":"...","spans":[{"file":"a.rules","line":3,"col":18,
//    "end_line":3,"end_col":28,"label":"...","primary":true}],"notes":[...],"helps":[...],
//    "fixes":[{"file":"a.rules","byte_start":17,"byte_end":27,"replacement":"layer.index"}]}
// Lines and columns are 1-based; columns count characters; end_col is one past the last one.
#pragma once

#include <string>
#include <vector>

#include "grammar/ast/diagnostic.h"
#include "grammar/ast/source.h"

namespace tranche::compiler {

std::string render_text(const ast::SourceMap& sources, const diag::Diagnostic& d, bool color);
std::string render_json(const ast::SourceMap& sources, const diag::Diagnostic& d);
// Every diagnostic as one SARIF 2.1.0 log (for code-scanning tools), with a newline.
std::string render_sarif(const ast::SourceMap& sources, const std::vector<diag::Diagnostic>& all);
// Where a code is explained: "docs/diagnostics.md#e0102" (each code's section has that anchor).
std::string docs_link(std::string_view code);
// "2 errors, 1 warning"
std::string summary(size_t errors, size_t warnings);
// A JSON string literal (quotes included) for UTF-8 text.
std::string json_string(std::string_view s);

}  // namespace tranche::compiler
