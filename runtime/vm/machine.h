// Internal to runtime/vm: the interpreter (class Machine) that vm.cpp implements and the
// RuleSet's entry points (vm.cpp, hooks.cpp) drive, and the per-thread state it runs on.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "runtime/vm/vm.h"

namespace tranche::vm {

// Registers of every frame of the calling thread: frames nest (a value that reads its own
// property's earlier value runs another candidate's chunk), so they are carved from one block
// that never moves.
constexpr size_t kStackRegs = 1u << 17;

struct ThreadState {
  std::unique_ptr<double[]> regs{new double[kStackRegs]()};
  size_t top = 0;
  // Per property: the candidates live for the current outer element (see vm.h, hoisting).
  struct Live {
    uint64_t key = 0;  // Context::generation of the level outside the decision; 0: none
    uint32_t owner = 0;
    struct Entry {
      uint32_t candidate;       // index into the property's candidates
      uint32_t first, count;    // its inner conjuncts in RuleSet::split_list_
    };
    std::vector<Entry> entries;  // in candidate order
  };
  std::array<Live, schema::kPropCount> live;
  std::string text;  // the template being built
  Counters counters;
};

// The calling thread's state (registers, live candidates, the template being built).
ThreadState& state();

enum class Fault : uint8_t { None, DivZero, ModZero, SqrtNeg, NotFinite, TextTooLong, OutputTooLong, Steps,
                             Depth, Api };

// Runs chunks for one call into the RuleSet (one decision, one hook, one replacement).
class Machine {
 public:
  Machine(const RuleSet& rs, const ctx::Context& c, const ctx::PropertyValues* props)
      : rs_(rs), p_(rs.program_), ctx_(c), props_(props), st_(state()) {}

  ctx::LineSink* out = nullptr;
  ctx::ReplaceApi* api = nullptr;

  ~Machine() {
    st_.counters.conjuncts_run += run_;
    st_.counters.live_rebuilds += rebuilds_;
  }

  // Runs chunk `ci`; false on a fault (see error()).
  bool exec(uint32_t ci, double& result);
  // Whether conjunct k holds (for rule r, named in errors).
  bool conj(uint32_t k, uint32_t r, bool& ok);
  // Whether every conjunct of rule r holds.
  bool test(uint32_t r, bool& result);
  // The candidates of property q whose outer conjuncts hold for the element outside q's level
  // (built once per such element and kept in the thread's state); null when q is not hoisted.
  bool live_list(schema::PropId q, const ThreadState::Live*& found);
  // The candidate of property q that decides it, among those of rules before `below` (all when
  // UINT32_MAX): its index, or -1 when none matches.
  bool winner(schema::PropId q, uint32_t below, int& index);
  // The value of property q as the rules before `below` decide it (else its base).
  bool resolve(schema::PropId q, uint32_t below, double& result);
  // The value of candidate i of property q.
  bool value(schema::PropId q, int i, double& result);

  Error error() const;
  bool faulted() const { return fault_ != Fault::None; }
  void fail_api(Error e) {
    fault_ = Fault::Api;
    api_error_ = std::make_unique<Error>(std::move(e));
  }

 private:
  bool fault(Fault f, uint32_t ci, uint32_t pc) {
    fault_ = f;
    fault_chunk_ = ci;
    fault_pc_ = pc;
    return false;
  }
  double elem(Coll c, size_t index, uint16_t member) const;
  size_t count(Coll c) const;
  bool emit(bool comment, uint32_t ci, uint32_t pc);

  const RuleSet& rs_;
  const Program& p_;
  const ctx::Context& ctx_;
  const ctx::PropertyValues* props_;
  ThreadState& st_;
  uint64_t steps_ = 0;
  size_t emitted_ = 0;
  int depth_ = 0;
  Fault fault_ = Fault::None;
  uint32_t fault_chunk_ = 0, fault_pc_ = 0;
  std::unique_ptr<Error> api_error_;  // set with Fault::Api
  uint32_t rule_ = UINT32_MAX;  // the rule whose code runs (for messages)
  uint16_t depth_read_ = 0;     // values read as "the rules before" being computed (for traces)
  uint64_t run_ = 0, rebuilds_ = 0;
  schema::Level limit_ = schema::Level::Piece;  // candidates reading a deeper level are left out (see cand_level_)

  friend class RuleSet;
};

}  // namespace tranche::vm
