// Cooling: the fan decided once per layer, or per path when a rule reads the path.
#include <doctest/doctest.h>

#include "geometry/plan/cooling.h"
#include "tests/support/print_fixture.h"

using namespace tranche;
using schema::PathKind;
using schema::PropId;

TEST_CASE("cooling: the fan once per layer, or per path when a rule reads the path") {
  {
    test::PrintFixture f(test::prism_layers(4, {test::square_mm(0, 0, 10, 10)}), {}, {{"skirt_loops", "0"}});
    auto l0 = f.plan(0), l2 = f.plan(2);
    for (const auto& p : l0.islands[0].paths) CHECK(p.fan == 0);  // the built-in first layer
    for (const auto& p : l2.islands[0].paths) CHECK(p.fan == 1);
  }
  {
    test::PrintFixture f(test::prism_layers(4, {test::square_mm(0, 0, 10, 10)}),
                         "rule when path.kind == infill and layer.time > 0 s { fan = 30% }\n",
                         {{"skirt_loops", "0"}});
    auto l2 = f.plan(2);
    for (const auto& p : l2.islands[0].paths)
      CHECK(p.fan == doctest::Approx(p.kind == PathKind::Infill ? 0.3 : 1.0));
    CHECK(l2.props[PropId::Fan] == 1);  // per path: the layer's own fan is left as decided
  }
}
