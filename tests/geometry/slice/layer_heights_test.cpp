#include "geometry/slice/layer_heights.h"

#include <doctest/doctest.h>

#include <cmath>

using namespace tranche::geo;

namespace {

void check_contiguous(const std::vector<Layer>& layers) {
  REQUIRE(!layers.empty());
  CHECK(layers.front().z_bottom == 0);
  for (size_t i = 0; i < layers.size(); ++i) {
    CHECK(layers[i].index == static_cast<int>(i));
    CHECK(layers[i].z_top > layers[i].z_bottom);
    if (i) CHECK(layers[i].z_bottom == layers[i - 1].z_top);
  }
}

}  // namespace

SCENARIO("layer plan with constant heights") {
  GIVEN("a 10 mm model and 0.2 mm layers") {
    auto plan = plan_layer_heights(10.0, {});
    REQUIRE(plan.ok());
    THEN("there are 50 layers ending exactly on multiples of 0.2 mm") {
      CHECK(plan->size() == 50);
      check_contiguous(*plan);
      for (const auto& l : *plan) CHECK(l.z_top == (l.index + 1) * 200000 / 1e6);
      CHECK(plan->back().z_top == 10.0);
      CHECK((*plan)[3].z_slice() == doctest::Approx(0.7));
    }
  }
  GIVEN("a first layer of 0.3 mm") {
    LayerHeightParams p;
    p.first_layer_height = 0.3;
    auto plan = plan_layer_heights(10.0, p);
    REQUIRE(plan.ok());
    THEN("the rest follows at 0.2 mm and the last one is shortened to the model's top") {
      check_contiguous(*plan);
      CHECK((*plan)[0].z_top == 0.3);
      CHECK((*plan)[1].z_top == 0.5);
      CHECK(plan->size() == 50);  // 0.3 + 48 × 0.2 = 9.9, then 0.1
      CHECK(plan->back().z_bottom == 9.9);
      CHECK(plan->back().z_top == 10.0);
    }
  }
}

SCENARIO("the last partial layer") {
  GIVEN("a model 10.1 mm tall: the remainder (0.1) is at least a quarter layer") {
    auto plan = plan_layer_heights(10.1, {});
    REQUIRE(plan.ok());
    THEN("a shortened last layer ends at the top") {
      CHECK(plan->size() == 51);
      CHECK(plan->back().z_bottom == 10.0);
      CHECK(plan->back().z_top == 10.1);
      CHECK(plan->back().z_slice() == doctest::Approx(10.05));
    }
  }
  GIVEN("a model 10.03 mm tall: the remainder (0.03) is a sliver") {
    auto plan = plan_layer_heights(10.03, {});
    REQUIRE(plan.ok());
    THEN("it is merged into the layer below") {
      CHECK(plan->size() == 50);
      CHECK(plan->back().z_bottom == doctest::Approx(9.8));
      CHECK(plan->back().z_top == 10.03);
      check_contiguous(*plan);
    }
  }
  GIVEN("a model thinner than the first layer") {
    auto plan = plan_layer_heights(0.03, {});
    REQUIRE(plan.ok());
    THEN("it is one layer of its own height") {
      REQUIRE(plan->size() == 1);
      CHECK(plan->front().z_top == 0.03);
    }
  }
}

SCENARIO("variable layer height from a callback") {
  LayerHeightParams p;
  std::vector<std::pair<int, double>> calls;
  p.height = [&](int index, double z_bottom) {
    calls.emplace_back(index, z_bottom);
    return z_bottom < 1.0 ? 0.1 : 0.25;
  };
  auto plan = plan_layer_heights(3.0, p);
  REQUIRE(plan.ok());
  check_contiguous(*plan);
  THEN("the callback sees each layer's index and bottom z and decides its height") {
    CHECK(plan->size() == 10 + 8);
    CHECK(calls.size() == plan->size());
    for (size_t i = 0; i < plan->size(); ++i) {
      CHECK(calls[i].first == static_cast<int>(i));
      CHECK(calls[i].second == (*plan)[i].z_bottom);
    }
    CHECK((*plan)[9].height() == doctest::Approx(0.1));
    CHECK((*plan)[10].height() == doctest::Approx(0.25));
    CHECK(plan->back().z_top == 3.0);
  }
}

TEST_CASE("layer plan errors") {
  CHECK(!plan_layer_heights(0.0, {}).ok());
  CHECK(!plan_layer_heights(-1.0, {}).ok());
  CHECK(!plan_layer_heights(std::nan(""), {}).ok());
  LayerHeightParams zero;
  zero.layer_height = 0;
  auto r = plan_layer_heights(1.0, zero);
  REQUIRE(!r.ok());
  CHECK(r.error().where == "layer 1");
  CHECK(r.error().message.find("at least 0.001 mm") != std::string::npos);
  LayerHeightParams nan_cb;
  nan_cb.height = [](int, double) { return std::nan(""); };
  CHECK(!plan_layer_heights(1.0, nan_cb).ok());
  LayerHeightParams tiny;
  tiny.layer_height = 0.001;
  auto many = plan_layer_heights(2000.0, tiny);
  REQUIRE(!many.ok());
  CHECK(many.error().message.find("too small") != std::string::npos);
}
