// The shape of the checked AST that codegen reads: ids, types, units, slots, stages, frames.
#include <doctest/doctest.h>

#include "tests/compiler/helpers.h"

using namespace tranche;
using ast::ExprKind;
using ast::RefKind;
using ast::Unit;
using schema::FieldId;
using schema::PropId;
using schema::Stage;

TEST_CASE("checked AST: a modifier rule carries field ids, enum values, units, slot and conjunct stages") {
  test::Compiled c;
  test::compile_text(
      c, "rule \"r\" when layer.index < 2 and path.kind == infill { speed = 20 mm/s; flow = 105% }\n");
  REQUIRE(c.sink.all().empty());
  REQUIRE(c.program.checked);
  const ast::Rule& r = c.rule(0);
  CHECK(r.index == 0);
  CHECK(r.name == "r");

  REQUIRE(r.conjuncts.size() == 2);
  const ast::Expr& lt = *r.conjuncts[0].expr;
  CHECK(r.conjuncts[0].stage == Stage::LayerPlan);
  CHECK(r.conjuncts[0].level == schema::Level::Layer);
  CHECK(lt.op == ast::Op::Lt);
  CHECK(lt.args[0]->ref == RefKind::Field);
  CHECK(lt.args[0]->field == FieldId::LayerIndex);
  CHECK(lt.args[0]->type == ast::Type::integer());
  CHECK(lt.args[1]->constant == 2.0);
  const ast::Expr& eq = *r.conjuncts[1].expr;
  CHECK(r.conjuncts[1].stage == Stage::PathPlan);
  CHECK(eq.args[0]->field == FieldId::PathKind);
  CHECK(eq.args[1]->ref == RefKind::EnumValue);
  CHECK(eq.args[1]->enum_value == static_cast<int>(schema::PathKind::Infill));
  CHECK(eq.args[1]->type == ast::Type::enumeration(schema::EnumType::PathKind));
  CHECK(r.filter->stage == Stage::PathPlan);

  REQUIRE(r.slots.size() == 2);
  CHECK(r.slots[0].kind == ast::SlotKind::Property);
  CHECK(r.slots[0].prop == PropId::Speed);
  CHECK(r.slots[0].stage == Stage::Piece);
  const ast::Expr& v = *r.slots[0].action->value;
  CHECK(v.type == ast::Type::number(Unit{1, -1, 0, 0}));
  CHECK(v.constant == 20.0);
  CHECK(r.slots[0].action->prop == PropId::Speed);
  CHECK(r.slots[1].prop == PropId::Flow);
  CHECK(r.slots[1].action->value->constant == doctest::Approx(1.05));
  CHECK(r.slots[1].action->value->type == ast::Type::number());
}

TEST_CASE("checked AST: own property is inherited, others are decided values, same-stage order is kept") {
  test::Compiled c;
  test::compile_text(c,
                     "rule { speed = speed * 50% }\n"
                     "rule { flow = speed / 100 mm/s }\n"
                     "rule { width = 0.5 mm }\n");
  REQUIRE(c.sink.all().empty());
  const ast::Expr& half = *c.rule(0).slots[0].action->value;
  CHECK(half.args[0]->ref == RefKind::Inherited);
  CHECK(half.args[0]->prop == PropId::Speed);
  const ast::Expr& ratio = *c.rule(1).slots[0].action->value;
  CHECK(ratio.args[0]->ref == RefKind::Property);
  CHECK(ratio.args[0]->prop == PropId::Speed);
  CHECK(ratio.type == ast::Type::number());
  const auto& order = c.program.property_order;
  REQUIRE(order.size() == static_cast<size_t>(schema::kPropCount));
  auto pos = [&](PropId p) { return std::find(order.begin(), order.end(), p) - order.begin(); };
  CHECK(pos(PropId::Speed) < pos(PropId::Flow));
  CHECK(pos(PropId::Width) < pos(PropId::Speed));  // stage-major
  CHECK(pos(PropId::LayerHeight) < pos(PropId::FillAngle));
}

TEST_CASE("checked AST: hooks have frames, locals have slots, loops have kinds and element fields") {
  test::Compiled c;
  test::compile_text(c,
                     "rule \"h\" {\n"
                     "  before layer append {\n"
                     "    let a = 2\n"
                     "    for isl in layer.islands { comment \"{isl.area:.1} {a}\" }\n"
                     "    for i in 1..3 { gcode \"G4 P{i}\" }\n"
                     "  }\n"
                     "}\n");
  REQUIRE(c.sink.all().empty());
  const ast::Rule& r = c.rule(0);
  REQUIRE(r.slots.size() == 1);
  CHECK(r.slots[0].kind == ast::SlotKind::Hook);
  CHECK(r.slots[0].level == schema::Level::Layer);
  CHECK(r.slots[0].when == ast::When::Before);
  CHECK(r.slots[0].append);
  const ast::Stmt& hook = *r.slots[0].action;
  CHECK(hook.frame_size == 3);
  CHECK(hook.body[0]->kind == ast::StmtKind::Let);
  CHECK(hook.body[0]->local == 0);
  const ast::Stmt& loop = *hook.body[1];
  CHECK(loop.loop == ast::LoopKind::Islands);
  CHECK(loop.local == 1);
  const ast::Template& t = loop.body[0]->text;
  REQUIRE(t.parts.size() == 3);
  CHECK(t.parts[0].expr->ref == RefKind::ElementField);
  CHECK(t.parts[0].expr->local == 1);
  CHECK(t.parts[0].expr->element == ast::Element::Island);
  CHECK(t.parts[0].expr->field == FieldId::IslandArea);
  CHECK(t.parts[0].decimals == 1);
  CHECK(t.parts[1].text == " ");
  CHECK(t.parts[2].expr->ref == RefKind::Local);
  CHECK(t.parts[2].expr->local == 0);
  const ast::Stmt& range = *hook.body[2];
  CHECK(range.loop == ast::LoopKind::Range);
  CHECK(range.range_lo == 1);
  CHECK(range.range_hi == 3);
  CHECK(range.local == 2);
}

TEST_CASE("checked AST: other layers, replacers and `on` events") {
  test::Compiled c;
  test::compile_text(c,
                     "rule when below.area < 1 mm2 and layers[layer.index - 2].z > 1 mm { fan = 1 }\n"
                     "rule when island.area < 4 mm2 { replace island { offset -0.1 mm; default } }\n"
                     "on path.end when path.kind == skirt append { comment \"skirt\" }\n");
  REQUIRE(c.sink.all().empty());
  const ast::Expr& below = *c.rule(0).conjuncts[0].expr->args[0];
  CHECK(below.ref == RefKind::OtherLayer);
  CHECK(below.other == ast::OtherLayer::Below);
  CHECK(below.field == FieldId::LayerArea);
  CHECK(below.stage == Stage::Layer);
  const ast::Expr& indexed = *c.rule(0).conjuncts[1].expr->args[0];
  CHECK(indexed.ref == RefKind::OtherLayer);
  CHECK(indexed.other == ast::OtherLayer::Indexed);
  CHECK(indexed.field == FieldId::LayerZ);
  REQUIRE(indexed.args.size() == 1);
  CHECK(indexed.args[0]->type == ast::Type::integer());

  const ast::Slot& replace = c.rule(1).slots.at(0);
  CHECK(replace.kind == ast::SlotKind::Replace);
  CHECK(replace.level == schema::Level::Island);
  CHECK(replace.stage == Stage::Island);
  CHECK(replace.action->body[0]->kind == ast::StmtKind::Offset);
  CHECK(replace.action->body[0]->value->constant == -0.1);

  const ast::Rule& on = c.rule(2);
  CHECK(on.from_on);
  CHECK(on.slots.at(0).kind == ast::SlotKind::Hook);
  CHECK(on.slots[0].level == schema::Level::Path);
  CHECK(on.slots[0].when == ast::When::After);
  CHECK(on.slots[0].append);
  CHECK_FALSE(ast::dump(c.program).empty());
}

TEST_CASE("checked AST: constants fold, percent scales, degrees feed trigonometry") {
  test::Compiled c;
  test::compile_text(
      c,
      "rule { fill_angle = 15 deg * 3 + atan2(1 mm, 1 mm); fan = 50%; perimeters = round(2.5) + 1 mod 2 }\n"
      "rule when sin(30 deg) > 0.49 and sin(30 deg) < 0.51 { flow = 1 }\n");
  REQUIRE_FALSE(c.sink.has_errors());
  CHECK(c.rule(0).slots[0].action->value->constant == doctest::Approx(90));
  CHECK(c.rule(0).slots[1].action->value->constant == doctest::Approx(0.5));
  CHECK(c.rule(0).slots[2].action->value->constant == 4.0);
  CHECK(c.rule(0).slots[2].action->value->type == ast::Type::integer());
  CHECK(c.rule(1).filter->constant == 1.0);
  CHECK(c.has("W203") == true);  // and the lint says the filter is constant
}
