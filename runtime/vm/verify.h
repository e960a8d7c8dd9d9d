// The loader's verifier and the disassembler. A program is verified before anything runs:
// every operand in range for its kind, every jump inside its chunk, every chunk ending with a
// terminator of its kind, every table consistent. After verification the interpreter needs
// no bounds checks on operands (it still bounds loops, recursion and output at run time).
#pragma once

#include <string>

#include "base/result.h"
#include "runtime/vm/program.h"

namespace tranche::vm {

// Limits a verified program stays within (bundles over them are refused).
inline constexpr size_t kMaxCode = 1u << 24;        // instructions
inline constexpr size_t kMaxConsts = 1u << 16;      // operands are 16-bit
inline constexpr size_t kMaxStrings = 1u << 16;
inline constexpr size_t kMaxRules = 65535;
inline constexpr size_t kMaxChunkSize = 65535;
inline constexpr size_t kMaxStringBytes = 1u << 20;  // one template piece

// Errors name what is wrong ("chunk 4, instruction 7: register 9 out of range (chunk has 3)").
Status verify(const Program& program);

// A listing of the whole program: tables, then each chunk's instructions with operands decoded
// (field and property names, constants, strings) and, with debug information, `file:line:col`.
std::string disassemble(const Program& program);
// One chunk only (tests compare codegen against golden listings).
std::string disassemble_chunk(const Program& program, uint32_t chunk);

// "file:line:col" of instruction `instr` (an index in Program::code) from the debug section;
// empty without one, or when the instruction has no position.
std::string instruction_location(const Program& program, uint32_t instr);

}  // namespace tranche::vm
