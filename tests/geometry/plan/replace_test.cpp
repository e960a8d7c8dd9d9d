// The replacer API on a path: offset and reverse alter it (and the context a replacer reads
// sees the new shape), text and moves become its ops.
#include <doctest/doctest.h>

#include "geometry/plan/replace.h"
#include "tests/support/print_fixture.h"

using namespace tranche;
using schema::FieldId;

TEST_CASE("replace path: offset moves the path sideways, reverse turns it; both re-enter the path") {
  test::PrintFixture f(test::prism_layers(2, {test::square_mm(0, 0, 10, 10)}));
  plan::Nest nest(*f.setup, *f.cascade);
  plan::PathPlan p;
  p.kind = schema::PathKind::Infill;
  p.pts = {geo::to_point(0, 0), geo::to_point(10, 0)};
  p.border = {schema::Border::None};
  nest.enter_path(nullptr, p);
  plan::PathReplace api(nest, p);
  REQUIRE(api.offset(1).ok());  // left of travel: +y
  CHECK(p.pts[0] == geo::to_point(0, 1));
  CHECK(p.pts[1] == geo::to_point(10, 1));
  CHECK(nest.ctx().points().size() == 2);  // path.points rebound to the new shape
  CHECK(nest.ctx().points()[0].y == doctest::Approx(1 + geo::to_mm(f.setup->shift.Y)));
  REQUIRE(api.reverse().ok());
  CHECK(p.pts[0] == geo::to_point(10, 1));
  CHECK(nest.ctx().get(FieldId::PathLength) == doctest::Approx(10));
  REQUIRE(api.offset(0).ok());  // nothing to do
  CHECK(p.pts[0] == geo::to_point(10, 1));
  api.gcode("M117 hi");
  api.comment("note");
  api.retract();
  REQUIRE(api.emit_default().ok());
  REQUIRE(p.ops.size() == 4);
  CHECK(p.ops[0].text == "M117 hi");
  CHECK(p.ops[1].text == "; note");
  CHECK(p.ops[2].kind == plan::Op::Kind::Retract);
  CHECK(p.ops[3].kind == plan::Op::Kind::Default);
  ctx::MoveOptions o;
  o.speed = 7;
  api.move_to(3, 4, o);
  CHECK(p.ops.back().speed == 7);
  CHECK(p.ops.back().flow < 0);  // the path's decided flow, filled in at the piece level
  CHECK(p.ops.back().to == plan::to_model(nest, 3, 4));
}

TEST_CASE("replace island: reverse is refused with a message") {
  struct Host final : plan::IslandHost {
    plan::Nest& n;
    explicit Host(plan::Nest& x) : n(x) {}
    plan::Nest& nest() override { return n; }
    Status redecide_island(plan::IslandPlan&) override { return ok_status(); }
    Status build_island(plan::IslandPlan&) override { return ok_status(); }
  };
  test::PrintFixture f(test::prism_layers(1, {test::square_mm(0, 0, 10, 10)}));
  plan::Nest nest(*f.setup, *f.cascade);
  Host host(nest);
  plan::IslandPlan ip;
  plan::IslandReplace api(host, ip);
  auto s = api.reverse();
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().message.find("paths, not islands") != std::string::npos);
}
