#include <doctest/doctest.h>

#include "geometry/mesh/primitives.h"
#include "geometry/polygon/layers.h"
#include "geometry/slice/layer_heights.h"
#include "geometry/slice/slicer.h"
#include "polygon_checks.h"

using namespace tranche;
using namespace tranche::geo;

namespace {

std::vector<Layer> slice(const Mesh& mesh) {
  Report rep;
  auto layers = plan_layer_heights(mesh.bbox().max.z, {});
  REQUIRE(layers.ok());
  auto st = slice_mesh(mesh, *layers, {}, rep);
  REQUIRE(st.ok());
  return std::move(*layers);
}

}  // namespace

// 45° on even layers, 135° on odd ones, as the cascade's built-in default.
const IslandAngle alternate = [](const Layer& l, size_t) { return l.index % 2 == 0 ? 45.0 : 135.0; };

TEST_CASE("layers: two cubes touching along an edge slice into two islands per layer") {
  // Cube A [0,10]^3 and cube B [10,20]x[10,20]x[0,10] share the vertical edge x = y = 10.
  Mesh cubes = box({10, 10, 10});
  append(cubes, box({10, 10, 10}, {10, 10, 0}));
  std::vector<Layer> layers = slice(cubes);
  REQUIRE(layers.size() > 10);
  Report rep;
  REQUIRE(resolve_layers(layers, {}, rep).ok());
  for (const Layer& l : layers) {
    CHECK(l.islands.size() == 2);
    for (const auto& is : l.islands) CHECK(is.area_mm2 == doctest::Approx(100).epsilon(1e-6));
  }
  auto cells = decompose_layers(layers, alternate);
  REQUIRE(cells.ok());
  for (size_t l = 0; l < layers.size(); ++l) {
    REQUIRE((*cells)[l].size() == 2);
    for (const auto& c : (*cells)[l]) {
      REQUIRE(c.size() == 1);
      CHECK(c[0].fill_angle_deg == alternate(layers[l], 0));
    }
  }
}

TEST_CASE("layers: a plate with holes, resolved and decomposed layer by layer") {
  std::vector<Layer> layers = slice(plate_with_holes(60, 40, 3, 4, 3, 4, 32));
  Report rep;
  REQUIRE(resolve_layers(layers, {}, rep).ok());
  CHECK(rep.empty());
  DecomposeStats total;
  auto cells = decompose_layers(layers, alternate, &total);
  REQUIRE(cells.ok());
  for (size_t i = 0; i < layers.size(); ++i) {
    const Layer& l = layers[i];
    REQUIRE(l.islands.size() == 1);
    CHECK(l.islands[0].shape.holes.size() == 12);
    CHECK(test::cells_problem(l.islands[0], (*cells)[i][0], alternate(l, 0)) == "");
  }
  CHECK(total.cells >= static_cast<int>(layers.size()) * 2);
}

TEST_CASE("layers: errors name the layer, warnings come in layer order") {
  std::vector<Layer> layers(3);
  for (int i = 0; i < 3; ++i) {
    layers[i].index = i;
    layers[i].loops = {test::mm_ring({{0, 0}, {20, 20}, {20, 0}, {0, 20}})};  // a figure 8
  }
  Report rep;
  REQUIRE(resolve_layers(layers, {}, rep).ok());
  const auto w = rep.warnings();
  REQUIRE(w.size() == 3);
  CHECK(w[0].where.rfind("layer 0 ", 0) == 0);
  CHECK(w[2].where.rfind("layer 2 ", 0) == 0);
  ResolveOptions strict;
  strict.strict = true;
  Report rep2;
  auto st = resolve_layers(layers, strict, rep2);
  REQUIRE_FALSE(st.ok());
  CHECK(st.error().where.rfind("layer 0 ", 0) == 0);
}

TEST_CASE("layers: an island that cannot be decomposed is a warning when a report is given") {
  std::vector<Layer> layers(2);
  layers[0].index = 0;
  layers[1].index = 1;
  const coord_t far = coord_t{1} << 40;  // beyond the sweep's range
  Island bad;
  bad.shape.outer = test::rect(0, 0, far, far);
  layers[1].islands.push_back(bad);
  Island good;
  good.shape.outer = test::rect(0, 0, 10, 10);
  layers[1].islands.push_back(good);
  CHECK_FALSE(decompose_layers(layers, alternate).ok());
  Report rep;
  size_t calls = 0;
  auto cells = decompose_layers(layers, alternate, nullptr, &rep, [&](size_t) { ++calls; });
  REQUIRE(cells.ok());
  CHECK(rep.count("decompose-failed") == 1);
  CHECK(rep.warnings()[0].where == "layer 1 island 0");
  CHECK((*cells)[1][0].empty());
  CHECK((*cells)[1][1].size() == 1);
  CHECK(calls == 2);
}
