#include "runtime/vm/opcodes.h"

#include <cstddef>

namespace tranche::vm {
namespace {

constexpr Operand kind_of(char c) {
  switch (c) {
    case 'R': return Operand::Reg;
    case 'K': return Operand::Const;
    case 'F': return Operand::Field;
    case 'P': return Operand::Prop;
    case 'J': return Operand::Jump;
    case 'S': return Operand::String;
    case 'N': return Operand::Rule;
    case 'E': return Operand::Enum;
    case 'C': return Operand::Coll;
    case 'M': return Operand::Member;
    case 'D': return Operand::Decimals;
    case 'O': return Operand::LayerOffset;
    case 'X': return Operand::MoveFlags;
    default: return Operand::None;
  }
}

#define TRANCHE_OP(Name, mnemonic, A, B, C, D, Class) \
  OpInfo{mnemonic, kind_of(#A[0]), kind_of(#B[0]), kind_of(#C[0]), kind_of(#D[0]), OpClass::Class},
const OpInfo kOps[] = {
#include "runtime/vm/opcodes.def"
};
#undef TRANCHE_OP
static_assert(sizeof(kOps) / sizeof(kOps[0]) == kOpCount);

}  // namespace

const OpInfo& op_info(Op op) { return kOps[static_cast<size_t>(op)]; }

}  // namespace tranche::vm
