// The rule VM: a verified Program run inside the slicing loop. One RuleSet is the user's rules
// (every `--rules` file, linked in cascade order, and `--set` expressions); the loop consults it
// through the three interfaces of runtime/context/hooks.h:
//   Decider    for each property of a stage, the first candidate (last rule) whose filter holds
//              decides its value; a property read inside its own rule is resolved from the
//              candidates below that rule, down to the value the cascade gives below the rules
//   Executors  for a hook, the last matching executor, then every matching `append` one after it
//   Replacers  for an island or a path, the last matching replacer runs instead of the default
//
// Hoisting: each property's candidates are split, for the level the property is decided at, into
// the conjuncts that read only fields of outer levels and the others. For each element of the
// level just outside (each path, for a per-piece `speed`) the outer conjuncts are evaluated once
// and the candidates whose outer conjuncts hold are kept ("live"); each decision then tests only
// the inner conjuncts of the live candidates, in order, and stops at the first match. The kept
// list stays valid while Context::generation of that outer level stays the same. A conjunct that
// compares a field with a constant is evaluated in place, without entering the interpreter.
//
// Thread safety: a RuleSet is immutable once created; every call keeps its state on the
// calling thread (registers, text buffer, the live candidate lists), so layers run in parallel.
//
// Run-time errors (division by zero, a square root of a negative number, a value that is not a
// number or outside the property's physical range, a template or output too long, too many loop
// steps) stop the slice: the Error names the rule and, with debug information, file:line:col.
#pragma once

#include <array>
#include <bitset>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/result.h"
#include "runtime/context/hooks.h"
#include "runtime/vm/program.h"

namespace tranche::vm {

// Bounds on what one call may do (each is a run-time error when exceeded).
inline constexpr uint64_t kMaxLoopSteps = 20'000'000;  // loop iterations per hook or replacer run
inline constexpr size_t kMaxTextBytes = 64 * 1024;     // one `gcode`/`comment` template's text
inline constexpr size_t kMaxOutputBytes = 64u << 20;   // everything one hook or replacer run emits
inline constexpr int kMaxInheritDepth = 1000;          // nested "value of the rules before"

class RuleSet final : public ctx::Decider, public ctx::Executors, public ctx::Replacers {
 public:
  // Verifies the program (see verify.h) and prepares it to run.
  static Result<std::shared_ptr<const RuleSet>> create(Program program);

  const Program& program() const { return program_; }
  // The value a name field (object.name) takes for `name`: the index of the same text in the
  // program's strings, which holds every quoted text the rules compare names with; -1 when no
  // rule names it (then `object.name == "..."` is false and `!=` true for every text).
  int text_index(std::string_view name) const;
  // Every quoted text the rules compare a name with, in the order of the strings, with where it
  // is first written ("file:line:col"; empty without debug information).
  std::vector<std::pair<std::string, std::string>> compared_texts() const;

  // ctx::Decider
  Status decide(schema::Stage stage, const ctx::Context& ctx, ctx::PropertyValues& props) const override;
  schema::Level varies_at(schema::Stage stage) const override { return varies_[static_cast<size_t>(stage)]; }
  // Decider, Executors and Replacers: whether any code reads the field.
  bool reads(schema::FieldId field) const override { return reads_[static_cast<size_t>(field)]; }
  // Decider: over the candidates whose conjuncts on outer fields hold for the element (the live
  // candidates of hoisting, kept for the decisions that follow).
  Result<Dependence> depends(schema::Stage stage, const ctx::Context& ctx) const override;
  bool reads_beyond(schema::Stage stage, schema::FieldId field) const override {
    return beyond_[static_cast<size_t>(stage)][static_cast<size_t>(field)];
  }
  // ctx::Executors
  bool has(schema::Level level, ctx::When when) const override;
  Status run(schema::Level level, ctx::When when, const ctx::Context& ctx, ctx::LineSink& out) const override;
  // ctx::Replacers
  bool has(schema::Level level) const override;
  Result<bool> replace(schema::Level level, const ctx::Context& ctx, ctx::ReplaceApi& api) const override;

  // For `rulec explain` and tests.
  // Runs a Test or Value chunk in the context (props: the element's properties).
  Result<double> evaluate(uint32_t chunk, const ctx::Context& ctx, const ctx::PropertyValues& props) const;
  // Whether the slot `cands` has a property candidate, hook or replacer matching in ctx: the
  // index in `cands` of the deciding candidate, or -1.
  Result<int> first_match(const Candidates& cands, const ctx::Context& ctx, const ctx::PropertyValues& props) const;
  // "rule \"name\"" (or "rule 3" without debug information) and "file:line:col" ("" without).
  std::string rule_name(uint32_t rule) const;
  std::string rule_where(uint32_t rule) const;
  // The rule's name without quotes ("bridges"), or its position ("the rule at f.rules:3").
  std::string rule_label(uint32_t rule) const;
  // The file (as given) and line where the code of `chunk` (a value, a hook's or a replacer's
  // body) starts; line 0 without debug information.
  std::pair<std::string, uint32_t> chunk_source(uint32_t chunk) const;

  // Every property's value check: a finite number within the physical range (angles are
  // brought into [0, 360)). Returns the value to store, or an explanation of what is wrong.
  static Result<double> check_value(schema::PropId prop, double value);

 private:
  explicit RuleSet(Program p);
  // Done once by create() (ruleset.cpp), in this order.
  void analyse();
  using FieldSet = std::bitset<schema::kFieldCount>;
  struct ChunkFacts {
    std::vector<schema::Level> level;  // per chunk: the innermost level it reads
    std::vector<uint8_t> pure;         // per chunk: 1 when it reads only fields
    std::vector<schema::Level> own;    // per chunk: the innermost level of what it reads but properties
    std::vector<uint32_t> stages;      // per chunk: a bit per stage whose properties it reads
    std::vector<FieldSet> fields;      // per chunk: the fields it reads (also through collections)
  };
  ChunkFacts analyse_chunks();
  void analyse_simple();
  void analyse_constants();
  void analyse_splits(const ChunkFacts& facts);
  void analyse_dependence(const ChunkFacts& facts);
  uint32_t cand_rule(schema::PropId q, int i) const { return program_.props[static_cast<size_t>(q)][static_cast<size_t>(i)].rule; }
  uint32_t cand_chunk(schema::PropId q, int i) const { return program_.props[static_cast<size_t>(q)][static_cast<size_t>(i)].chunk; }
  friend class Machine;

  Program program_;
  uint32_t uid_ = 0;
  std::array<bool, schema::kFieldCount> reads_{};
  std::array<schema::Level, schema::kStageCount> varies_{};
  std::array<std::vector<schema::PropId>, schema::kStageCount> stage_props_;  // with candidates, in order
  // A conjunct `field CMP constant` (most of them), evaluated without the interpreter.
  struct Simple {
    bool on = false;
    bool negate = false;
    uint8_t cmp = 0;  // 0 ==, 1 !=, 2 <, 3 <=, 4 >, 5 >=
    uint16_t field = 0;
    double k = 0;
  };
  std::vector<Simple> simple_;        // per conjunct
  std::vector<uint8_t> is_const_;     // per chunk: a Value chunk that is one `retk`
  std::vector<double> const_value_;   // its value
  // Per property and candidate: its conjuncts, outer ones first (indices into split_list_).
  struct Split {
    uint32_t first = 0, outer = 0, inner = 0;
  };
  std::array<std::vector<Split>, schema::kPropCount> split_;
  std::vector<uint32_t> split_list_;
  std::array<schema::Level, schema::kPropCount> decided_at_{};  // the level each property is decided at
  // Per property and candidate: the deepest level its rule and value read. A property decided
  // again at a finer stage (schema::finest_stage: fill_angle per cell) leaves the candidates
  // reading that finer level out of its own stage's decision.
  std::array<std::vector<schema::Level>, schema::kPropCount> cand_level_;
  // Per property and candidate (analyse_dependence): the deepest level and the fields its rule
  // and value read, reads of the property's own stage left out; per stage, the fields read by
  // code other than that stage's candidates.
  std::array<std::vector<schema::Level>, schema::kPropCount> dep_level_;
  std::array<std::vector<FieldSet>, schema::kPropCount> dep_fields_;
  std::array<FieldSet, schema::kStageCount> beyond_{};
  struct Range {
    bool plain = false;  // a number without unit conversion: in range means stored as is
    double min = 0, max = 0;
  };
  std::array<Range, schema::kPropCount> ranges_{};
};

// Counters of the calling thread, for tests of hoisting (never reset by the VM).
struct Counters {
  uint64_t conjuncts_run = 0;   // conjuncts evaluated
  uint64_t live_rebuilds = 0;   // live candidate lists built (once per outer element and property)
};
Counters& thread_counters();

}  // namespace tranche::vm
