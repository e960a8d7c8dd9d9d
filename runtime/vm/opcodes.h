// The instruction set as C++ types, derived from opcodes.def (the one table where each opcode
// is written): the Op enum, the operand kinds and classes, and each opcode's metadata, which the
// disassembler, the verifier, the linker and the interpreter read.
#pragma once

#include <cstdint>

namespace tranche::vm {

enum class Op : uint8_t {
#define TRANCHE_OP(Name, mnemonic, A, B, C, D, Class) Name,
#include "runtime/vm/opcodes.def"
#undef TRANCHE_OP
  Count_
};
inline constexpr int kOpCount = static_cast<int>(Op::Count_);

// Operand kinds and opcode classes of opcodes.def.
enum class Operand : uint8_t { None, Reg, Const, Field, Prop, Jump, String, Rule, Enum, Coll, Member,
                               Decimals, LayerOffset, MoveFlags };
enum class OpClass : uint8_t { Expr, Stmt, Repl, Term };
struct OpInfo {
  const char* mnemonic;
  Operand a, b, c, d;
  OpClass cls;
};
const OpInfo& op_info(Op op);

}  // namespace tranche::vm
