#include "runtime/context/defaults.h"

#include <algorithm>
#include <cmath>

namespace tranche::ctx {
namespace {

using schema::PathKind;
using T = BuiltinRule::Test;

constexpr double kind(PathKind k) { return static_cast<double>(k); }

// What stdlib/defaults.rules will say, rule for rule. Units: mm/s, ratio, deg.
constexpr BuiltinRule kRules[] = {
    // rule "speed by kind" when path.kind == K { speed = V }
    {PropId::Speed, FieldId::PathKind, T::Equals, kind(PathKind::OuterPerimeter), 25},
    {PropId::Speed, FieldId::PathKind, T::Equals, kind(PathKind::InnerPerimeter), 45},
    {PropId::Speed, FieldId::PathKind, T::Equals, kind(PathKind::Infill), 80},
    {PropId::Speed, FieldId::PathKind, T::Equals, kind(PathKind::SolidInfill), 60},
    {PropId::Speed, FieldId::PathKind, T::Equals, kind(PathKind::TopSolid), 40},
    {PropId::Speed, FieldId::PathKind, T::Equals, kind(PathKind::BottomSolid), 40},
    {PropId::Speed, FieldId::PathKind, T::Equals, kind(PathKind::Bridge), 25},
    {PropId::Speed, FieldId::PathKind, T::Equals, kind(PathKind::Skirt), 30},
    {PropId::Speed, FieldId::PathKind, T::Equals, kind(PathKind::Ironing), 15},
    // rule "ironing flow" when path.kind == ironing { flow = 15% }
    {PropId::Flow, FieldId::PathKind, T::Equals, kind(PathKind::Ironing), 0.15},
    {PropId::Speed, FieldId::PathKind, T::Equals, kind(PathKind::Support), 50},
    {PropId::Speed, FieldId::PathKind, T::Equals, kind(PathKind::SupportInterface), 40},
    {PropId::Speed, FieldId::PathKind, T::Equals, kind(PathKind::Brim), 30},
    {PropId::Speed, FieldId::PathKind, T::Equals, kind(PathKind::GapFill), 30},
    // rule "first layer" when layer.index == 0 { speed = 20 mm/s; fan = 0% }
    {PropId::Speed, FieldId::LayerIndex, T::Equals, 0, 20},
    {PropId::Fan, FieldId::LayerIndex, T::Equals, 0, 0},
    // rule "cross hatch" when layer.index mod 2 == 1 { fill_angle = 135 deg }  (45 deg otherwise)
    {PropId::FillAngle, FieldId::LayerIndex, T::Odd, 0, 135},
};

bool matches(const BuiltinRule& r, const Context& ctx) {
  switch (r.test) {
    case T::Always:
      return true;
    case T::Equals:
      return ctx.get(r.field) == r.operand;
    case T::Odd:
      return std::fmod(std::abs(ctx.get(r.field)), 2.0) == 1.0;
  }
  return false;
}

}  // namespace

std::span<const BuiltinRule> builtin_rules() { return kRules; }

BuiltinDefaults::BuiltinDefaults() {
  std::fill(std::begin(varies_), std::end(varies_), schema::Level::Print);
  for (const auto& r : kRules) {
    auto stage = static_cast<size_t>(schema::property(r.prop).stage);
    if (r.test != T::Always) varies_[stage] = std::max(varies_[stage], schema::field(r.field).level);
  }
}

Status BuiltinDefaults::decide(schema::Stage stage, const Context& ctx, PropertyValues& props) const {
  for (uint32_t i = 0; i < std::size(kRules); ++i) {
    const BuiltinRule& r = kRules[i];
    if (schema::property(r.prop).stage != stage || !matches(r, ctx)) continue;
    props[r.prop] = r.result;
    if (Trace* t = ctx.trace()) t->step({r.prop, TraceStep::Source::BuiltinDefault, i, UINT32_MAX, r.result, 0});
  }
  return ok_status();
}

schema::Level BuiltinDefaults::varies_at(schema::Stage stage) const {
  return varies_[static_cast<size_t>(stage)];
}

bool BuiltinDefaults::reads(schema::FieldId field) const {
  for (const auto& r : kRules)
    if (r.test != T::Always && r.field == field) return true;
  return false;
}

}  // namespace tranche::ctx
