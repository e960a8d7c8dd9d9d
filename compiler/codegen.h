// Code generation: a checked AST (compiler/check.h) to a VM program (runtime/vm/program.h).
//
// The work is done once, here: each rule's filter is split into its conjuncts (one Test chunk
// each, tagged with the level it reads, so the VM can keep a layer-level result for the whole
// layer); comparisons of a field or a value with a constant become one fused compare-and-branch
// instruction; constants are folded by the checker and pooled here; every slot gets its
// candidates in descending rule order, so the VM stops at the first (last written) match.
#pragma once

#include "grammar/ast/ast.h"
#include "base/result.h"
#include "runtime/vm/program.h"

namespace tranche::compiler {

struct CodegenOptions {
  bool debug = true;  // keep the debug section (file:line:col of code, rule names, filter texts)
};

// `program` must be checked without errors. Errors: limits of the VM (more than 65535 rules,
// constants or strings; a chunk of more than 65535 instructions or 256 registers), naming the rule.
Result<vm::Program> generate(const ast::Program& program, const CodegenOptions& options = {});

}  // namespace tranche::compiler
