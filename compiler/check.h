// The checker: resolves names, types, units and stages of a loaded program and fills the
// checked fields of its AST (grammar/ast/ast.h); then the lints. Codes are listed in
// docs/diagnostics.md.
#pragma once

#include "grammar/ast/ast.h"
#include "grammar/ast/diagnostic.h"

namespace tranche::compiler {

// Checks every rule of `program.cascade` in place. Returns true (and sets program.checked)
// when no error was reported.
bool check(ast::Program& program, diag::Sink& sink);

// Warnings (W2xx) about a checked program: shadowed rules, unsatisfiable or constant filters,
// float equality on z, values out of physical range. Only rules in user files are reported.
void lint(const ast::Program& program, diag::Sink& sink);

}  // namespace tranche::compiler
