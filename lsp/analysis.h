// One document checked as `rulec check` checks a file (load, `use`s, check, lint), and what the
// editor features need from the result: the node under the cursor.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "compiler/frontend.h"
#include "grammar/ast/ast.h"
#include "grammar/ast/diagnostic.h"

namespace tranche::lsp {

struct Analysis {
  std::unique_ptr<ast::Program> program;
  std::vector<diag::Diagnostic> diagnostics;  // sorted, every file's
  uint32_t file = 0;                          // the document in program->sources
  const ast::File* parsed = nullptr;          // its items (empty after a syntax error)
};

// Checks `text` as the file at `path` (its `./` uses resolve from there).
Analysis analyze(const std::string& path, std::string text, const compiler::FrontendOptions& options);

// The innermost nodes of the document at a byte offset (any may be null).
struct Found {
  const ast::Expr* expr = nullptr;  // the innermost expression
  const ast::Stmt* stmt = nullptr;  // the innermost statement
  const ast::Rule* rule = nullptr;
  const ast::Param* param = nullptr;
  const ast::Use* use = nullptr;
};
Found find_at(const Analysis& a, uint32_t offset);

// Every definition of param `name` in cascade order (`--set` ones are not in a file).
std::vector<const ast::Param*> param_definitions(const ast::Program& program, const std::string& name);

}  // namespace tranche::lsp
