// A compiled rule set: the code the VM runs and the tables that say which code decides which
// slot. compiler/codegen.cpp builds it from a checked AST; bundle.h writes and reads it; the
// loader verifies it (verify.h) before anything runs.
//
// Instructions are 64 bits. A is a register; B, C and D are registers, constants, fields,
// properties, strings, rules or jump targets, as opcodes.def says for each opcode:
//
//    63           48 47           32 31           16 15        8 7         0
//   +---------------+---------------+---------------+-----------+-----------+
//   |       D       |       C       |       B       |     A     |    op     |
//   +---------------+---------------+---------------+-----------+-----------+
//
// Code is grouped in chunks, each a self-contained routine with its own registers (at most
// 256) whose jumps stay inside it and whose last instruction ends it:
//   Test     one conjunct of a rule's filter; returns 1 or 0
//   Value    a modifier's value; returns the number
//   Hook     an executor's body (`before path { ... }`); emits text
//   Replace  a replacer's body; emits text and moves, may alter the element
//
// A rule is the list of its filter's conjuncts (all must hold). Every slot of the cascade
// (each property, each hook, each replacement) has its candidates: (rule, chunk) pairs in
// *descending* rule order, so that the first candidate whose rule matches decides the slot
// (last match wins). A property's candidates are evaluated in `property_order`.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "runtime/schema/schema.h"
#include "runtime/vm/opcodes.h"

namespace tranche::vm {

struct Instr {
  uint8_t op = 0;
  uint8_t a = 0;
  uint16_t b = 0, c = 0, d = 0;

  Op code() const { return static_cast<Op>(op); }
  uint64_t pack() const {
    return uint64_t(op) | uint64_t(a) << 8 | uint64_t(b) << 16 | uint64_t(c) << 32 | uint64_t(d) << 48;
  }
  static Instr unpack(uint64_t w) {
    return Instr{uint8_t(w), uint8_t(w >> 8), uint16_t(w >> 16), uint16_t(w >> 32), uint16_t(w >> 48)};
  }
};
static_assert(sizeof(Instr) == 8);


// Collections a `for` loop walks (operand C).
enum class Coll : uint8_t { Points, Pieces, Islands };
inline constexpr uint16_t kPointX = 0, kPointY = 1, kPointIndex = 2;
inline constexpr uint16_t kDefaultDecimals = 0xFFFF;
inline constexpr uint16_t kMoveTravel = 1, kMoveSpeed = 2, kMoveFlow = 4, kMoveWidth = 8;

enum class ChunkKind : uint8_t { Test, Value, Hook, Replace };

struct Chunk {
  uint32_t start = 0;  // index of the first instruction in Program::code
  uint32_t size = 0;
  uint16_t regs = 0;   // registers used (1..256)
  ChunkKind kind = ChunkKind::Test;
};

struct Conjunct {
  uint32_t chunk = 0;
  schema::Level level = schema::Level::Print;  // the innermost level it reads
};

struct Rule {
  uint32_t first = 0, count = 0;  // its conjuncts: Program::conjuncts[first, first + count)
};

struct Candidate {
  uint32_t rule = 0;
  uint32_t chunk = 0;   // Value chunk (properties), Hook or Replace chunk
  bool append = false;  // hooks: `append` adds to the hook instead of replacing it
};
using Candidates = std::vector<Candidate>;

// File, line and column of a piece of rule source (1-based line and column).
struct Loc {
  uint32_t file = 0, line = 0, col = 0;
};

// Optional: maps code back to the source, for runtime errors, `rulec disasm` and `explain`.
struct Debug {
  std::vector<std::string> files;       // file names as given
  std::vector<Loc> locs;                // distinct locations
  std::vector<uint32_t> instr_loc;      // per instruction of Program::code: index in locs
  std::vector<std::string> rule_names;  // per rule: `"first layers slow"` or "the rule at f:3"
  std::vector<uint32_t> rule_loc;       // per rule: index in locs
  std::vector<std::string> conj_text;   // per conjunct: its source text
  std::vector<uint32_t> conj_loc;       // per conjunct: index in locs
  bool empty() const { return files.empty() && locs.empty() && rule_names.empty(); }
};

struct Program {
  std::vector<double> consts;
  std::vector<std::string> strings;
  std::vector<Instr> code;
  std::vector<Chunk> chunks;
  std::vector<Conjunct> conjuncts;
  std::vector<Rule> rules;  // in cascade order
  std::array<Candidates, schema::kPropCount> props;
  std::array<std::array<Candidates, 2>, schema::kLevelCount> hooks;  // [level][0 before, 1 after]
  std::array<Candidates, schema::kLevelCount> replace;               // island and path only
  std::vector<schema::PropId> property_order;  // every property, stage-major, dependencies first
  Debug debug;
};

}  // namespace tranche::vm
