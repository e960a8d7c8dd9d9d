#include <doctest/doctest.h>

#include <string>

#include "runtime/context/cascade.h"
#include "runtime/context/context.h"
#include "runtime/context/defaults.h"
#include "runtime/context/overrides.h"

using namespace tranche;
using namespace tranche::ctx;
using schema::Level;
using schema::PathKind;
using schema::Stage;

namespace {
double decided(const Decider& d, Stage stage, const Context& c, PropId id) {
  PropertyValues p = PropertyValues::schema_defaults();
  REQUIRE(d.decide(stage, c, p).ok());
  return p[id];
}
}  // namespace

TEST_CASE("context: layer table reads other layers, empty outside the print") {
  LayerTable t(3);
  t.set(1, FieldId::LayerArea, 12.5);
  t.set(2, FieldId::LayerZ, 0.6);
  t.set(0, FieldId::IslandArea, 99);  // not a layer field: ignored
  Context c;
  c.set_layers(&t);
  c.set(FieldId::LayerIndex, 2);
  CHECK(c.below(FieldId::LayerArea) == 12.5);
  CHECK(c.layer(2, FieldId::LayerZ) == 0.6);
  CHECK(c.above(FieldId::LayerZ) == 0);
  CHECK(c.layer(-1, FieldId::LayerArea) == 0);
  CHECK(c.layer(0, FieldId::IslandArea) == 0);
  CHECK(LayerTable::holds(FieldId::LayerTime));
  CHECK_FALSE(LayerTable::holds(FieldId::PathLength));
}

TEST_CASE("context: entering a level clears it and every deeper level") {
  Context c;
  c.set(FieldId::LayerIndex, 4);
  c.set(FieldId::IslandArea, 3);
  c.set(FieldId::PieceLength, 1);
  c.clear_from(Level::Island);
  CHECK(c.get(FieldId::LayerIndex) == 4);
  CHECK(c.get(FieldId::IslandArea) == 0);
  CHECK(c.get(FieldId::PieceLength) == 0);
}

TEST_CASE("built-in defaults: speed by path kind, first layer, fan and fill angle alternation") {
  BuiltinDefaults d;
  Context c;
  c.set(FieldId::LayerIndex, 3);
  auto speed_of = [&](PathKind k) {
    c.set(FieldId::PathKind, static_cast<double>(k));
    return decided(d, Stage::Piece, c, PropId::Speed);
  };
  CHECK(speed_of(PathKind::OuterPerimeter) == 25);
  CHECK(speed_of(PathKind::InnerPerimeter) == 45);
  CHECK(speed_of(PathKind::Infill) == 80);
  CHECK(speed_of(PathKind::SolidInfill) == 60);
  CHECK(speed_of(PathKind::TopSolid) == 40);
  CHECK(speed_of(PathKind::BottomSolid) == 40);
  CHECK(speed_of(PathKind::Bridge) == 25);
  CHECK(speed_of(PathKind::Skirt) == 30);
  CHECK(decided(d, Stage::Cooling, c, PropId::Fan) == 1.0);
  CHECK(decided(d, Stage::Island, c, PropId::FillAngle) == 135);
  c.set(FieldId::LayerIndex, 0);
  CHECK(speed_of(PathKind::Infill) == 20);
  CHECK(speed_of(PathKind::OuterPerimeter) == 20);
  CHECK(decided(d, Stage::Cooling, c, PropId::Fan) == 0.0);
  CHECK(decided(d, Stage::Island, c, PropId::FillAngle) == 45);
  // Decisions at a stage only touch that stage's properties.
  CHECK(decided(d, Stage::Piece, c, PropId::Fan) == schema::property(PropId::Fan).default_value);
}

TEST_CASE("built-in defaults: hoisting levels follow the fields the table reads") {
  BuiltinDefaults d;
  CHECK(d.varies_at(Stage::Piece) == Level::Path);  // speed reads path.kind, not piece fields
  CHECK(d.varies_at(Stage::Cooling) == Level::Layer);
  CHECK(d.varies_at(Stage::Island) == Level::Layer);
  CHECK(d.varies_at(Stage::Print) == Level::Print);
}

TEST_CASE("--set: numbers with optional units, enums, booleans") {
  auto v = [](const char* k, const char* val) {
    auto r = parse_override(k, val);
    REQUIRE_MESSAGE(r.ok(), (r.ok() ? "" : r.error().to_string()));
    return r->value;
  };
  CHECK(v("layer_height", "0.15") == doctest::Approx(0.15));
  CHECK(v("layer_height", "0.15mm") == doctest::Approx(0.15));
  CHECK(v("layer_height", " 0.15 mm") == doctest::Approx(0.15));
  CHECK(v("infill_density", "35%") == doctest::Approx(0.35));
  CHECK(v("infill_density", "0.35") == doctest::Approx(0.35));
  CHECK(v("nozzle_temp", "215C") == 215);
  CHECK(v("nozzle_temp", "215°C") == 215);
  CHECK(v("fill_angle", "30deg") == 30);
  CHECK(v("speed", "50mm/s") == 50);
  CHECK(v("perimeters", "3") == 3);
  CHECK(v("seam", "rear") == static_cast<double>(schema::Seam::Rear));
  CHECK(v("gcode_flavor", "klipper") == static_cast<double>(schema::Flavor::Klipper));
  CHECK(v("relative_e", "true") == 1);
  CHECK(v("outer_first", "false") == 0);
}

TEST_CASE("--set: clear errors for unknown keys, bad units and out-of-range values") {
  auto err = [](const char* k, const char* val) {
    auto r = parse_override(k, val);
    REQUIRE_FALSE(r.ok());
    return r.error().to_string();
  };
  std::string e = err("layer_hieght", "0.2");
  CHECK(e.find("unknown property 'layer_hieght'") != std::string::npos);
  CHECK(e.find("layer_height") != std::string::npos);
  CHECK(err("sped", "20").find("speed") != std::string::npos);
  CHECK(err("layer.index", "2").find("context field") != std::string::npos);
  CHECK(err("layer_height", "0.2 mm/s").find("not a unit") != std::string::npos);
  CHECK(err("layer_height", "5").find("outside the range") != std::string::npos);
  CHECK(err("infill_density", "20").find("20%") != std::string::npos);
  CHECK(err("perimeters", "2.5").find("whole number") != std::string::npos);
  CHECK(err("seam", "sharpest").find("aligned, nearest, rear, random, sharpest_corner, point") != std::string::npos);
  CHECK(err("relative_e", "yes").find("true or false") != std::string::npos);
  CHECK(err("speed", "fast").find("needs a number") != std::string::npos);
  CHECK(err("speed", "").find("missing value") != std::string::npos);
}

TEST_CASE("the cascade: --set overrides win over the built-in defaults at the property's stage") {
  auto cascade = Cascade::create({{"speed", "33"}, {"fan", "50%"}});
  REQUIRE(cascade.ok());
  Context c;
  c.set(FieldId::LayerIndex, 0);
  c.set(FieldId::PathKind, static_cast<double>(PathKind::Infill));
  auto decide = [&](Stage st, PropId id) {
    PropertyValues p = PropertyValues::schema_defaults();
    REQUIRE((*cascade)->decide(st, c, p).ok());
    CHECK(&c.props() == &p);  // rules read the values being decided
    return p[id];
  };
  CHECK(decide(Stage::Piece, PropId::Speed) == 33);
  CHECK(decide(Stage::Cooling, PropId::Fan) == 0.5);
  CHECK(decide(Stage::Island, PropId::FillAngle) == 45);
  c.set(FieldId::LayerIndex, 1);
  CHECK(decide(Stage::Island, PropId::FillAngle) == 135);  // the built-in alternation, written once
  CHECK((*cascade)->varies_at(Stage::Piece) == Level::Path);
}

// A decider that sets one property to a constant at one stage, reading one field.
struct Fixed final : Decider {
  Stage stage;
  PropId prop;
  double value;
  FieldId field;
  Fixed(Stage s, PropId p, double v, FieldId f) : stage(s), prop(p), value(v), field(f) {}
  Status decide(Stage st, const Context&, PropertyValues& props) const override {
    if (st == stage) props[prop] = value;
    return ok_status();
  }
  Level varies_at(Stage st) const override { return st == stage ? schema::field(field).level : Level::Print; }
  bool reads(FieldId f) const override { return f == field; }
};

TEST_CASE("the cascade's order: defaults < middle (the script) < rules < --set") {
  Fixed script(Stage::Island, PropId::FillAngle, 30, FieldId::IslandIndex);
  Fixed rules(Stage::Island, PropId::Perimeters, 4, FieldId::IslandArea);
  auto cascade = Cascade::create({{"perimeters", "3"}}, &rules);
  REQUIRE(cascade.ok());
  Context c;
  c.set(FieldId::LayerIndex, 1);
  PropertyValues p = PropertyValues::schema_defaults();
  REQUIRE((*cascade)->decide(Stage::Island, c, p).ok());
  CHECK(p[PropId::FillAngle] == 135);  // no middle layer yet: the built-in default
  CHECK(p[PropId::Perimeters] == 3);   // --set above the rules
  (*cascade)->set_middle(&script);
  p = PropertyValues::schema_defaults();
  REQUIRE((*cascade)->decide(Stage::Island, c, p).ok());
  CHECK(p[PropId::FillAngle] == 30);
  CHECK((*cascade)->varies_at(Stage::Island) == Level::Island);
  CHECK((*cascade)->reads(FieldId::IslandIndex));
  CHECK((*cascade)->reads(FieldId::IslandArea));
  p = PropertyValues::schema_defaults();
  REQUIRE((*cascade)->decide_defaults(Stage::Island, c, p).ok());
  CHECK(p[PropId::FillAngle] == 135);  // what the script sees as its default
  CHECK(p[PropId::Perimeters] == 2);
}

TEST_CASE("deciders say which fields they read, so costly unread fields are skipped") {
  BuiltinDefaults b;
  CHECK(b.reads(FieldId::PathKind));
  CHECK(b.reads(FieldId::LayerIndex));
  CHECK_FALSE(b.reads(FieldId::IslandSupported));
  CHECK_FALSE(b.reads(FieldId::PieceOverhang));
  auto o = Overrides::parse({{"speed", "33"}});
  REQUIRE(o.ok());
  CHECK_FALSE(o->reads(FieldId::LayerIndex));
  auto cascade = Cascade::create({{"speed", "33"}});
  REQUIRE(cascade.ok());
  CHECK((*cascade)->reads(FieldId::PathKind));  // the built-in speed by kind
  CHECK_FALSE((*cascade)->reads(FieldId::IslandSupported));
}

TEST_CASE("cascade: layer heights follow first_layer_height, layer_height and --set") {
  Context print;
  {
    auto c = Cascade::create({});
    REQUIRE(c.ok());
    auto p = (*c)->print_props(print);
    REQUIRE(p.ok());
    CHECK(*(*c)->layer_height(print, *p, 0, 0.0) == doctest::Approx(0.2));
    CHECK(*(*c)->layer_height(print, *p, 5, 1.0) == doctest::Approx(0.2));
  }
  {
    auto c = Cascade::create({{"first_layer_height", "0.3"}, {"layer_height", "0.15mm"}});
    REQUIRE(c.ok());
    auto p = (*c)->print_props(print);
    REQUIRE(p.ok());
    CHECK((*p)[PropId::FirstLayerHeight] == doctest::Approx(0.3));
    // --set layer_height is a rule without a filter: it wins on layer 0 too.
    CHECK(*(*c)->layer_height(print, *p, 0, 0.0) == doctest::Approx(0.15));
    CHECK(*(*c)->layer_height(print, *p, 3, 0.6) == doctest::Approx(0.15));
  }
  {
    auto c = Cascade::create({{"first_layer_height", "0.3"}});
    REQUIRE(c.ok());
    auto p = (*c)->print_props(print);
    CHECK(*(*c)->layer_height(print, *p, 0, 0.0) == doctest::Approx(0.3));
    CHECK(*(*c)->layer_height(print, *p, 1, 0.3) == doctest::Approx(0.2));
  }
  CHECK_FALSE(Cascade::create({{"layer_hieght", "0.1"}}).ok());
}

TEST_CASE("the cascade records each layer's decision in a trace, lowest first, and nothing without one") {
  struct Recorder final : Trace {
    std::vector<TraceStep> steps;
    void step(const TraceStep& s) override { steps.push_back(s); }
  } r;
  struct Traced final : Decider {  // a middle layer that records, as ScriptAngles does
    Status decide(Stage st, const Context& ctx, PropertyValues& props) const override {
      if (st != Stage::Island) return ok_status();
      props[PropId::FillAngle] = 30;
      if (ctx.trace()) ctx.trace()->step({PropId::FillAngle, TraceStep::Source::Middle, UINT32_MAX, UINT32_MAX, 30, 0});
      return ok_status();
    }
    Level varies_at(Stage) const override { return Level::Print; }
  } middle;
  auto cascade = Cascade::create({{"fill_angle", "10"}});
  REQUIRE(cascade.ok());
  (*cascade)->set_middle(&middle);
  Context c;
  c.set(FieldId::LayerIndex, 1);
  c.set_trace(&r);
  PropertyValues p = PropertyValues::schema_defaults();
  REQUIRE((*cascade)->decide(Stage::Island, c, p).ok());
  std::vector<std::pair<TraceStep::Source, double>> angle;
  for (const auto& s : r.steps)
    if (s.prop == PropId::FillAngle) angle.emplace_back(s.source, s.value);
  using S = TraceStep::Source;
  CHECK(angle == std::vector<std::pair<S, double>>{{S::Start, 45}, {S::BuiltinDefault, 135}, {S::Middle, 30}, {S::Set, 10}});
  const size_t n = r.steps.size();
  c.set_trace(nullptr);
  p = PropertyValues::schema_defaults();
  REQUIRE((*cascade)->decide(Stage::Island, c, p).ok());
  CHECK(r.steps.size() == n);
  CHECK(p[PropId::FillAngle] == 10);
}
