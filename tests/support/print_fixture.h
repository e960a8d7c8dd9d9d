// A print set up from constructed layers, for the tests of the stages after the polygon stage
// (plan, gcode, export): the cascade (built-in defaults, optional rules from text, --set
// values), the print stage, and the print setup, exactly as the pipeline builds them.
#pragma once

#include <doctest/doctest.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "compiler/load_rules.h"
#include "geometry/plan/layer_loop.h"
#include "geometry/setup/print_setup.h"
#include "runtime/context/cascade.h"
#include "tests/support/fixtures.h"

namespace tranche::test {

// A square ring from (x0, y0) to (x1, y1), mm, counter-clockwise.
inline geo::Ring square_mm(double x0, double y0, double x1, double y1) {
  return {geo::to_point(x0, y0), geo::to_point(x1, y0), geo::to_point(x1, y1), geo::to_point(x0, y1)};
}

// `n` layers of 0.2 mm, each with the islands `outlines` (outer rings, no holes).
inline std::vector<geo::Layer> prism_layers(int n, const std::vector<geo::Ring>& outlines) {
  std::vector<geo::Layer> layers(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    auto& l = layers[static_cast<size_t>(i)];
    l.index = i;
    l.z_bottom = 0.2 * i;
    l.z_top = 0.2 * (i + 1);
    for (const auto& r : outlines) {
      geo::Island isl;
      isl.shape.outer = r;
      isl.area_mm2 = geo::area_mm2(r);
      l.islands.push_back(isl);
    }
  }
  return layers;
}

struct PrintFixture {
  std::shared_ptr<const vm::RuleSet> rules;
  std::unique_ptr<ctx::Cascade> cascade;
  std::unique_ptr<setup::PrintSetup> setup;
  Report report;

  // `rules_text`: a .rules source (empty: no rules, no profile); `sets`: plain --set values.
  PrintFixture(const std::vector<geo::Layer>& layers, const std::string& rules_text = {},
               const std::vector<std::pair<std::string, std::string>>& sets = {}) {
    if (!rules_text.empty()) {
      TempDir dir("print-fixture");
      std::string path = (dir / "r.rules").string();
      { std::ofstream(path) << rules_text; }
      compiler::RulesInput in;
      in.profile = false;
      in.files = {path};
      auto rs = compiler::load_rules(in, report);
      REQUIRE_MESSAGE(rs.ok(), (rs.ok() ? "" : rs.error().to_string()));
      rules = *rs;
    }
    auto c = ctx::Cascade::create(sets, rules.get(), rules.get(), rules.get());
    REQUIRE_MESSAGE(c.ok(), (c.ok() ? "" : c.error().to_string()));
    cascade = std::move(*c);
    setup::PrintFacts facts;
    facts.height = layers.empty() ? 0 : layers.back().z_top;
    ctx::Context print = setup::print_context(facts);
    auto props = cascade->print_props(print);
    REQUIRE(props.ok());
    auto s = setup::make_setup(layers, facts, print, *props, *cascade, "test", report);
    REQUIRE_MESSAGE(s.ok(), (s.ok() ? "" : s.error().to_string()));
    setup = std::move(*s);
  }

  plan::LayerPlan plan(int index) const {
    auto p = plan::plan_layer(*setup, *cascade, index);
    REQUIRE_MESSAGE(p.ok(), (p.ok() ? "" : p.error().to_string()));
    return std::move(*p);
  }
};

}  // namespace tranche::test
