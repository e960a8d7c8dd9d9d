#include <doctest/doctest.h>

#include "compiler/prover.h"
#include "tests/compiler/helpers.h"

using namespace tranche;
using compiler::prover::Box;
using compiler::prover::Boxes;
using compiler::prover::Cons;
using compiler::prover::Space;
using Cover = std::vector<const Boxes*>;

namespace {

// The filter of rule `i` of `text`, as boxes.
std::optional<Boxes> boxes_of(test::Compiled& c, Space& space, size_t i, bool negate = false) {
  const ast::Rule& r = c.rule(i);
  REQUIRE(r.filter);
  return compiler::prover::to_boxes(*r.filter, space, c.program.sources, r.index, negate);
}

Cons interval(int var, double lo, double hi, bool lo_open = false, bool hi_open = false) {
  Cons k;
  k.var = var;
  k.lo = lo;
  k.hi = hi;
  k.lo_open = lo_open;
  k.hi_open = hi_open;
  return k;
}

Box box(std::vector<Cons> cons) { return Box{std::move(cons)}; }

}  // namespace

TEST_CASE("prover: comparisons become intervals clipped to the field's domain") {
  test::Compiled c;
  test::compile_text(c, "rule when layer.index < 2 { speed = 20 mm/s }\n", false);
  REQUIRE_FALSE(c.sink.has_errors());
  Space space;
  auto b = boxes_of(c, space, 0);
  REQUIRE(b.has_value());
  REQUIRE(b->size() == 1);
  REQUIRE((*b)[0].cons.size() == 1);
  const Cons& k = (*b)[0].cons[0];
  CHECK(k.lo == 0);  // indices are >= 0
  CHECK(k.hi == 1);  // integers: `< 2` is `<= 1`
  CHECK_FALSE(k.lo_open);
  CHECK_FALSE(k.hi_open);
}

TEST_CASE("prover: subtracting real intervals keeps open and closed ends exact") {
  Space space;
  int z = space.field(schema::FieldId::LayerZ);
  Boxes d =
      compiler::prover::subtract(box({interval(z, 0, 10, false, true)}), box({interval(z, 2, 3)}), space);
  REQUIRE(d.size() == 2);
  CHECK(d[0].cons[0].lo == 0);
  CHECK(d[0].cons[0].hi == 2);
  CHECK(d[0].cons[0].hi_open);  // [0, 2)
  CHECK(d[1].cons[0].lo == 3);
  CHECK(d[1].cons[0].lo_open);  // (3, 10)
  CHECK(d[1].cons[0].hi == 10);
  CHECK(d[1].cons[0].hi_open);
  // Disjoint: nothing removed.
  Boxes same =
      compiler::prover::subtract(box({interval(z, 0, 1)}), box({interval(z, 1, 2, true, false)}), space);
  REQUIRE(same.size() == 1);
  CHECK(same[0].cons[0].hi == 1);
  // Covering: nothing left.
  CHECK(compiler::prover::subtract(box({interval(z, 1, 2)}), box({interval(z, 0, 5)}), space).empty());
}

TEST_CASE("prover: integer intervals subtract without gaps") {
  Space space;
  int i = space.field(schema::FieldId::LayerIndex);
  Boxes d = compiler::prover::subtract(box({interval(i, 0, 9)}), box({interval(i, 0, 4)}), space);
  REQUIRE(d.size() == 1);
  CHECK(d[0].cons[0].lo == 5);
  CHECK(d[0].cons[0].hi == 9);
  CHECK(compiler::prover::subtract(box({interval(i, 5, 9)}), box({interval(i, 5, 9)}), space).empty());
}

TEST_CASE("prover: enum sets subtract as masks, other variables stay") {
  Space space;
  int kind = space.field(schema::FieldId::PathKind);
  int i = space.field(schema::FieldId::LayerIndex);
  Cons infill_or_bridge;
  infill_or_bridge.var = kind;
  infill_or_bridge.mask =
      (1u << static_cast<int>(schema::PathKind::Infill)) | (1u << static_cast<int>(schema::PathKind::Bridge));
  Cons infill = infill_or_bridge;
  infill.mask = 1u << static_cast<int>(schema::PathKind::Infill);
  Box a = box({interval(i, 0, 3)});
  a.cons.insert(a.cons.begin(), infill_or_bridge);  // sorted by var: kind was created first
  Boxes d = compiler::prover::subtract(a, box({infill}), space);
  REQUIRE(d.size() == 1);
  CHECK(d[0].cons[0].mask == (1u << static_cast<int>(schema::PathKind::Bridge)));
  CHECK(d[0].cons[1].lo == 0);
  CHECK(d[0].cons[1].hi == 3);
}

TEST_CASE("prover: a region is covered by a union, and the cover that took part is named") {
  test::Compiled c;
  test::compile_text(c,
                     "rule when layer.index in 0..9 { fan = 50% }\n"
                     "rule when layer.index < 5 { fan = 0% }\n"
                     "rule when layer.index >= 5 { fan = 100% }\n"
                     "rule when layer.index > 100 { fan = 20% }\n",
                     false);
  REQUIRE_FALSE(c.sink.has_errors());
  Space space;
  auto region = boxes_of(c, space, 0);
  auto low = boxes_of(c, space, 1), high = boxes_of(c, space, 2), far = boxes_of(c, space, 3);
  std::vector<size_t> used;
  CHECK(compiler::prover::covered(*region, Cover{&*far, &*low, &*high}, space, &used) == true);
  CHECK(used == std::vector<size_t>{1, 2});
  CHECK(compiler::prover::covered(*region, Cover{&*low}, space, nullptr) == false);
  CHECK(compiler::prover::covered(*region, Cover{&*far}, space, nullptr) == false);
}

TEST_CASE("prover: contradictions are empty, tautologies have an empty negation") {
  test::Compiled c;
  test::compile_text(c,
                     "rule when layer.index < 2 and layer.index > 5 { flow = 1 }\n"
                     "rule when path.kind == infill and path.kind == bridge { flow = 1 }\n"
                     "rule when layer.index >= 0 { flow = 1 }\n"
                     "rule when island.supported <= 1 or cell.solid { flow = 1 }\n"
                     "rule when not (cell.solid and not cell.solid) { flow = 1 }\n",
                     false);
  REQUIRE_FALSE(c.sink.has_errors());
  Space space;
  CHECK(boxes_of(c, space, 0)->empty());
  CHECK(boxes_of(c, space, 1)->empty());
  CHECK_FALSE(boxes_of(c, space, 2)->empty());
  CHECK(boxes_of(c, space, 2, true)->empty());  // indices are never negative
  CHECK(boxes_of(c, space, 3, true)->empty());  // ratios are at most 1
  CHECK(boxes_of(c, space, 4, true)->empty());
}

TEST_CASE("prover: conditions it cannot model are opaque, shared by text, private when inherited") {
  test::Compiled c;
  test::compile_text(c,
                     "rule when below.area < 4 mm2 { speed = 20 mm/s }\n"
                     "rule when below.area  <  4 mm2 { speed = 30 mm/s }\n"
                     "rule when speed > 50 mm/s { speed = 50 mm/s }\n"
                     "rule when speed > 50 mm/s { speed = 40 mm/s }\n",
                     false);
  REQUIRE_FALSE(c.sink.has_errors());
  Space space;
  auto a = boxes_of(c, space, 0), b = boxes_of(c, space, 1);
  CHECK(compiler::prover::covered(*a, Cover{&*b}, space, nullptr) == true);
  // `speed` read in a rule that sets it is the value before that rule: not the same condition.
  auto p = boxes_of(c, space, 2), q = boxes_of(c, space, 3);
  CHECK(compiler::prover::covered(*p, Cover{&*q}, space, nullptr) == false);
}

TEST_CASE("prover: a normal form past its cap is unknown, never a proof") {
  std::string filter;
  for (int k = 0; k < 5; ++k) {
    if (k) filter += " and ";
    filter += "(layer.index == " + std::to_string(k) + " or island.holes == " + std::to_string(k) +
              " or cell.index == 1 or path.index == 2)";
  }
  test::Compiled c;
  test::compile_text(c, "rule when " + filter + " { flow = 1 }\n", false);
  REQUIRE_FALSE(c.sink.has_errors());
  Space space;
  CHECK_FALSE(boxes_of(c, space, 0).has_value());  // 4^5 = 1024 boxes > 256
}
