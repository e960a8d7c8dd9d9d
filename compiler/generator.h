// Internal to compiler/: the code generator's state (class Generator) while it turns a checked
// program into VM code. codegen.cpp drives it rule by rule and builds the chunks,
// codegen_expr.cpp compiles expressions and conditions (fused compare-and-jump), codegen_stmt.cpp
// the statements of hook and replacer bodies.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "compiler/codegen.h"
#include "runtime/vm/verify.h"

namespace tranche::compiler::gen {

using ast::Expr;
using ast::ExprKind;
using ast::Op;
using ast::RefKind;
using ast::Stmt;
using ast::StmtKind;
using vm::Instr;
using VOp = vm::Op;

// Thrown inside the generator when a VM limit is exceeded; caught at its boundary.
struct CodegenLimit {
  std::string message;
};

// The six comparisons as they appear in fused opcodes, and their mirror (operands swapped).
enum class Cmp { Eq, Ne, Lt, Le, Gt, Ge };

inline Cmp mirror(Cmp c) {
  switch (c) {
    case Cmp::Lt: return Cmp::Gt;
    case Cmp::Le: return Cmp::Ge;
    case Cmp::Gt: return Cmp::Lt;
    case Cmp::Ge: return Cmp::Le;
    default: return c;
  }
}

inline std::optional<Cmp> cmp_of(Op op) {
  switch (op) {
    case Op::Eq: return Cmp::Eq;
    case Op::Ne: return Cmp::Ne;
    case Op::Lt: return Cmp::Lt;
    case Op::Le: return Cmp::Le;
    case Op::Gt: return Cmp::Gt;
    case Op::Ge: return Cmp::Ge;
    default: return std::nullopt;
  }
}

// Fused opcode for (comparison, operand form, polarity). Form: 0 FK, 1 RK, 2 RR.
inline VOp fused(Cmp c, int form, bool when_true) {
  static constexpr VOp table[6][3][2] = {
      {{VOp::JnEqFK, VOp::JEqFK}, {VOp::JnEqRK, VOp::JEqRK}, {VOp::JnEqRR, VOp::JEqRR}},
      {{VOp::JnNeFK, VOp::JNeFK}, {VOp::JnNeRK, VOp::JNeRK}, {VOp::JnNeRR, VOp::JNeRR}},
      {{VOp::JnLtFK, VOp::JLtFK}, {VOp::JnLtRK, VOp::JLtRK}, {VOp::JnLtRR, VOp::JLtRR}},
      {{VOp::JnLeFK, VOp::JLeFK}, {VOp::JnLeRK, VOp::JLeRK}, {VOp::JnLeRR, VOp::JLeRR}},
      {{VOp::JnGtFK, VOp::JGtFK}, {VOp::JnGtRK, VOp::JGtRK}, {VOp::JnGtRR, VOp::JGtRR}},
      {{VOp::JnGeFK, VOp::JGeFK}, {VOp::JnGeRK, VOp::JGeRK}, {VOp::JnGeRR, VOp::JGeRR}},
  };
  return table[static_cast<int>(c)][form][when_true ? 1 : 0];
}

inline bool plain_field(const Expr& e) { return e.ref == RefKind::Field && !e.constant; }

class Generator {
 public:
  Generator(const ast::Program& ast, const CodegenOptions& options) : ast_(ast), options_(options) {}

  vm::Program run();

 private:
  // ---- chunks ---------------------------------------------------------------------------
  struct ChunkState {
    uint32_t start = 0;
    int next = 0;   // first free register
    int max = 0;    // registers used
    int base = 0;   // locals occupy [0, base)
  };

  void begin(int locals) {
    cs_ = ChunkState{};
    cs_.start = static_cast<uint32_t>(p_.code.size());
    cs_.next = cs_.max = cs_.base = locals;
    if (locals > 256)
      throw CodegenLimit{fmt::format("{} uses more than 256 names", rule_->display(ast_.sources))};
  }
  uint32_t end(vm::ChunkKind kind) {
    uint32_t size = static_cast<uint32_t>(p_.code.size()) - cs_.start;
    if (size > vm::kMaxChunkSize)
      throw CodegenLimit{fmt::format("{} compiles to more than {} instructions in one action",
                                     rule_->display(ast_.sources), vm::kMaxChunkSize)};
    p_.chunks.push_back({cs_.start, size, static_cast<uint16_t>(std::max(cs_.max, 1)), kind});
    return static_cast<uint32_t>(p_.chunks.size() - 1);
  }
  int alloc() {
    int r = cs_.next++;
    if (r >= 256)
      throw CodegenLimit{
          fmt::format("{} needs more than 256 registers in one action", rule_->display(ast_.sources))};
    cs_.max = std::max(cs_.max, cs_.next);
    return r;
  }
  // Registers allocated after `mark` are free again.
  int mark() const { return cs_.next; }
  void release(int m) { cs_.next = m; }

  uint32_t test_chunk(const Expr& e);

  uint32_t value_chunk(const Expr& e);

  uint32_t body_chunk(const Stmt& action, vm::ChunkKind kind);

  // ---- emission, labels ---------------------------------------------------------------
  struct Label {
    int target = -1;               // chunk-relative, once placed
    std::vector<uint32_t> fixups;  // absolute indices of jumps to patch
  };

  uint32_t emit(VOp op, uint8_t a = 0, uint16_t b = 0, uint16_t c = 0, uint16_t d = 0) {
    p_.code.push_back(Instr{static_cast<uint8_t>(op), a, b, c, d});
    if (options_.debug) p_.debug.instr_loc.push_back(loc(span_));
    return static_cast<uint32_t>(p_.code.size() - 1);
  }
  void jump_to(uint32_t at, Label& l) {
    if (l.target >= 0) set_target(at, static_cast<uint16_t>(l.target));
    else l.fixups.push_back(at);
  }
  void place(Label& l) {
    l.target = static_cast<int>(p_.code.size() - cs_.start);
    if (l.target > static_cast<int>(vm::kMaxChunkSize))
      throw CodegenLimit{
          fmt::format("{} compiles to too much code in one action", rule_->display(ast_.sources))};
    for (uint32_t at : l.fixups) set_target(at, static_cast<uint16_t>(l.target));
    l.fixups.clear();
  }
  void set_target(uint32_t at, uint16_t target) {
    Instr& in = p_.code[at];
    const vm::OpInfo& info = vm::op_info(in.code());
    if (info.b == vm::Operand::Jump) in.b = target;
    else if (info.c == vm::Operand::Jump) in.c = target;
    else in.d = target;
  }
  void jmp(Label& l) { jump_to(emit(VOp::Jmp), l); }

  uint16_t konst(double v) {
    if (v == 0) v = 0;  // one entry for -0 and 0
    uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    auto [it, fresh] = konst_.try_emplace(bits, static_cast<uint16_t>(p_.consts.size()));
    if (fresh) {
      if (p_.consts.size() >= vm::kMaxConsts) throw CodegenLimit{"more than 65536 distinct constants"};
      p_.consts.push_back(v);
    }
    return it->second;
  }
  uint16_t string(const std::string& s) {
    auto [it, fresh] = strings_.try_emplace(s, static_cast<uint16_t>(p_.strings.size()));
    if (fresh) {
      if (p_.strings.size() >= vm::kMaxStrings) throw CodegenLimit{"more than 65536 distinct texts (templates and names)"};
      p_.strings.push_back(s);
    }
    return it->second;
  }
  uint32_t loc(const ast::Span& s) {
    if (!s.valid()) return 0;
    uint64_t key = uint64_t(s.file) << 48 ^ uint64_t(s.line) << 20 ^ s.col;
    auto [it, fresh] = locs_.try_emplace(key, static_cast<uint32_t>(p_.debug.locs.size()));
    if (fresh) p_.debug.locs.push_back({s.file, s.line, s.col});
    return it->second;
  }

  // ---- expressions --------------------------------------------------------------------
  // The register holding e's value: a local's own register, or a new one.
  int value(const Expr& e);

  // Computes e into register dst.
  void into(const Expr& e, int dst);
  bool reference(const Expr& e, int dst);

  // `any(i in lo..hi: c)` (`all`) into dst: i counts up from lo, and the loop stops at the first
  // step that decides (c true for `any`, false for `all`). The VM bounds backward jumps.
  void quantifier(const Expr& e, int dst);

  // A boolean expression into a register: 1 or 0.
  void boolean(const Expr& e, int dst);

  void call(const Expr& e, int dst);

  // ---- conditions -------------------------------------------------------------------------
  // Jumps to `target` when e is `when`; falls through otherwise.
  void cond(const Expr& e, bool when, Label& target);

  // An operand compared several times (`x in a..b`, `x in (a, b)`): a field is read in place,
  // anything else is computed once into a register.
  struct Shared {
    const Expr* e;
    int reg = -1;  // -1: a plain field or a constant
  };
  Shared share(const Expr& x);

  void compare(const Expr& a, Cmp c, const Expr& b, bool when, Label& target);

  void compare_shared(const Shared& sa, Cmp c, const Expr& b, bool when, Label& target);

  void compare_operands(const Shared& sa, Cmp c, const Expr& b, bool when, Label& target);

  // ---- statements -------------------------------------------------------------------------
  void statements(const std::vector<ast::StmtPtr>& body);

  void statement(const Stmt& s);

  void text(const ast::Template& t);

  void loop(const Stmt& s);

  const ast::Program& ast_;
  const CodegenOptions& options_;
  vm::Program p_;
  ChunkState cs_;
  const ast::Rule* rule_ = nullptr;
  const Stmt* action_ = nullptr;
  ast::Span span_;
  std::unordered_map<uint64_t, uint16_t> konst_;
  std::map<std::string, uint16_t> strings_;
  std::unordered_map<uint64_t, uint32_t> locs_;
  std::vector<int> bound_;  // registers of the quantifier variables around the expression
};

}  // namespace tranche::compiler::gen
