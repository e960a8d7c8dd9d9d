// Filters as unions of boxes, to prove facts about them for the lints: a filter that can never
// be true, one that is always true, a rule whose every slot is taken by later rules.
//
// A box is a conjunction of independent constraints, one per variable: a numeric field or
// property lies in an interval (integers in an integer interval), an enum field in a set of
// values, a boolean in a subset of {false, true}. Conditions the prover cannot model (other
// layers, arithmetic on fields, functions...) become opaque boolean variables, interned by
// their text, so `below.area < 4 mm2` in two rules is the same variable. A filter is a union
// of boxes (its disjunctive normal form, capped in size); fields are intersected with their
// natural domains (indices >= 0, areas >= 0, ratios in [0, 1]). Every answer is a proof: when a
// form grows past its cap the prover says "unknown" and nothing is reported.
#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "grammar/ast/ast.h"

namespace tranche::compiler::prover {

enum class VarKind : uint8_t { Real, Integer, Set };

struct Var {
  VarKind kind = VarKind::Set;
  double lo = -INFINITY, hi = INFINITY;  // domain (Real/Integer)
  uint64_t full = 0;                     // domain (Set): one bit per value
};

// One variable's constraint. Real: an interval with open/closed ends; Integer: closed integer
// bounds; Set: a bit mask of allowed values.
struct Cons {
  int var = 0;
  double lo = -INFINITY, hi = INFINITY;
  bool lo_open = false, hi_open = false;
  uint64_t mask = 0;
};

struct Box {
  std::vector<Cons> cons;  // sorted by var; a variable not listed is unconstrained
};
using Boxes = std::vector<Box>;

// The variables of one program.
class Space {
 public:
  int field(schema::FieldId f);
  int property(schema::PropId p);
  int atom(const std::string& key);  // an opaque condition: a Set var with values {false, true}
  const Var& var(int id) const { return vars_[static_cast<size_t>(id)]; }
  Cons full(int id) const;

 private:
  int add(const std::string& key, Var v);
  std::map<std::string, int> ids_;
  std::vector<Var> vars_;
};

inline constexpr size_t kMaxBoxes = 256;

// The filter (or its negation) as a union of non-empty boxes; nothing if it grows past
// kMaxBoxes. `rule` makes conditions on inherited property values private to that rule.
std::optional<Boxes> to_boxes(const ast::Expr& filter, Space& space, const ast::SourceMap& sources, int rule,
                              bool negate = false);

// a ∩ b, or nothing when empty.
std::optional<Box> intersect(const Box& a, const Box& b, const Space& space);
// a \ b as disjoint boxes.
Boxes subtract(const Box& a, const Box& b, const Space& space);

// Whether every point of `region` lies in the union of `cover` (tried in order). `used` gets
// the indices of the cover entries that took part. Nothing if the proof grows past `limit` boxes.
std::optional<bool> covered(const Boxes& region, std::span<const Boxes* const> cover, const Space& space,
                            std::vector<size_t>* used, size_t limit = 4096);

}  // namespace tranche::compiler::prover
