// The rule-language parser: source text → AST (grammar/ast/ast.h). ANTLR stays behind this
// header. Lexical and syntax errors become diagnostics (E0001–E0007); a file with any of them
// yields no items, so the checker never sees a half-parsed file.
#pragma once

#include <cstdint>

#include "grammar/ast/ast.h"
#include "grammar/ast/diagnostic.h"

namespace tranche::grammar {

struct ParseOptions {
  int max_errors = 20;       // syntax errors reported per file before giving up
  int max_nesting = 100;     // brackets and prefix operators (`-`, `not`, `if`) open at once
  int max_expr_depth = 200;  // operators nested in one expression, `a + b + c` counting two
};

// Parses file `file_id` of `sources` (UTF-8; a leading BOM is skipped).
ast::File parse_file(const ast::SourceMap& sources, uint32_t file_id, diag::Sink& sink,
                     const ParseOptions& options = {});

// Parses bytes [begin, end) of file `file_id` as one expression: a `--set` value, a template's
// `{...}`. Returns null after reporting a diagnostic.
ast::ExprPtr parse_expression(const ast::SourceMap& sources, uint32_t file_id, uint32_t begin, uint32_t end,
                              diag::Sink& sink, const ParseOptions& options = {});

// How many parses needed the slow full-LL pass since the program started: SLL prediction
// handles every valid input of this grammar, so this only grows on syntax errors.
size_t ll_fallbacks();

// ANTLR keeps prediction caches across parses (shared, growing); long-running callers such as
// the fuzzer drop them from time to time. Not thread-safe, like the parser itself.
void clear_parser_caches();

}  // namespace tranche::grammar
