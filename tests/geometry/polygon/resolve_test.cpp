#include <doctest/doctest.h>

#include "geometry/polygon/resolve.h"
#include "polygon_checks.h"

using namespace tranche;
using namespace tranche::geo;
using test::mm_ring;
using test::rect;
using test::reversed;

namespace {

std::vector<Island> resolve_ok(const Rings& loops, OverlapMode mode = OverlapMode::Additive,
                               Report* rep = nullptr) {
  Report local;
  ResolveOptions o;
  o.overlap = mode;
  o.layer_index = 3;
  auto r = resolve_islands(loops, o, rep ? *rep : local);
  REQUIRE_MESSAGE(r.ok(), (r.ok() ? "" : r.error().to_string()));
  for (const auto& is : *r) CHECK_MESSAGE(test::island_problem(is).empty(), test::island_problem(is));
  return std::move(*r);
}

size_t total_holes(const std::vector<Island>& v) {
  size_t n = 0;
  for (const auto& is : v) n += is.shape.holes.size();
  return n;
}

}  // namespace

TEST_CASE("resolve: two squares touching at a corner are two islands") {
  const auto v = resolve_ok(
      {mm_ring({{0, 0}, {10, 0}, {10, 10}, {0, 10}}), mm_ring({{10, 10}, {20, 10}, {20, 20}, {10, 20}})});
  REQUIRE(v.size() == 2);
  CHECK(v[0].area_mm2 == doctest::Approx(100));
  CHECK(v[1].area_mm2 == doctest::Approx(100));
}

TEST_CASE("resolve: a figure-8 loop splits at its crossing, with a warning") {
  Report rep;
  const auto v = resolve_ok({mm_ring({{0, 0}, {20, 20}, {20, 0}, {0, 20}})}, OverlapMode::Additive, &rep);
  CHECK(v.size() == 2);
  CHECK(rep.count("intersecting-loops") == 1);
  const auto w = rep.warnings();
  REQUIRE(!w.empty());
  CHECK(w[0].where == "layer 3 at (10.000, 10.000) mm");
}

TEST_CASE("resolve: a hole touching the outline at a point stays one island") {
  const auto v =
      resolve_ok({mm_ring({{0, 0}, {10, 0}, {10, 10}, {0, 10}}), mm_ring({{5, 10}, {6, 8}, {5, 6}, {4, 8}})});
  REQUIRE(v.size() == 1);
  CHECK(v[0].shape.holes.size() == 1);
  CHECK(v[0].area_mm2 == doctest::Approx(96));
}

TEST_CASE("resolve: holes touching each other and an island touching its hole") {
  const auto v =
      resolve_ok({mm_ring({{0, 0}, {30, 0}, {30, 30}, {0, 30}}), mm_ring({{10, 10}, {10, 20}, {15, 15}}),
                  mm_ring({{15, 15}, {20, 20}, {20, 10}})});
  REQUIRE(v.size() == 1);
  CHECK(v[0].shape.holes.size() == 2);
  const auto w =
      resolve_ok({mm_ring({{0, 0}, {30, 0}, {30, 30}, {0, 30}}),
                  mm_ring({{5, 5}, {5, 25}, {25, 25}, {25, 5}}), mm_ring({{5, 5}, {15, 10}, {10, 15}})});
  REQUIRE(w.size() == 2);
  CHECK(total_holes(w) == 1);
}

TEST_CASE("resolve: an island inside a hole is its own island") {
  const auto v = resolve_ok({mm_ring({{0, 0}, {30, 0}, {30, 30}, {0, 30}}),
                             reversed(mm_ring({{5, 5}, {25, 5}, {25, 25}, {5, 25}})),
                             mm_ring({{10, 10}, {20, 10}, {20, 20}, {10, 20}}),
                             reversed(mm_ring({{12, 12}, {18, 12}, {18, 18}, {12, 18}}))});
  REQUIRE(v.size() == 2);
  CHECK(v[0].shape.holes.size() == 1);
  CHECK(v[1].shape.holes.size() == 1);
  CHECK(v[0].area_mm2 + v[1].area_mm2 == doctest::Approx(900 - 400 + 100 - 36));
}

TEST_CASE("resolve: zero-width spikes and zero-area loops vanish, with warnings") {
  Report rep;
  const auto v = resolve_ok({mm_ring({{0, 0}, {10, 0}, {10, 5}, {20, 5}, {10, 5}, {10, 10}, {0, 10}}),
                             mm_ring({{30, 0}, {40, 0}, {50, 0}}), mm_ring({{60, 0}, {60, 0}, {61, 0}})},
                            OverlapMode::Additive, &rep);
  REQUIRE(v.size() == 1);
  CHECK(v[0].shape.outer.size() == 4);
  CHECK(rep.count("loop-spike") == 1);
  CHECK(rep.count("degenerate-loop") == 2);
}

TEST_CASE("resolve: additive unites overlaps, boolean cancels them") {
  const Rings two{rect(0, 0, 20, 20), rect(10, 10, 30, 30)};
  const auto add = resolve_ok(two, OverlapMode::Additive);
  REQUIRE(add.size() == 1);
  CHECK(test::island_area2(add[0]) == 2 * (400 + 400 - 100));
  const auto xo = resolve_ok(two, OverlapMode::Boolean);
  REQUIRE(xo.size() == 2);  // the overlap is removed and the rest touches only at two corners
  CHECK(test::island_area2(xo[0]) + test::island_area2(xo[1]) == 2 * (400 + 400 - 200));
  // A loop inside another, both counter-clockwise: additive keeps it filled, boolean makes a hole.
  const Rings nested{rect(0, 0, 30, 30), rect(10, 10, 20, 20)};
  CHECK(total_holes(resolve_ok(nested, OverlapMode::Additive)) == 0);
  CHECK(total_holes(resolve_ok(nested, OverlapMode::Boolean)) == 1);
}

TEST_CASE("resolve: two cubes touching along an edge, sliced by hand") {
  // Cube A [0,10]^3 and cube B [10,20]x[10,20]x[0,10]: every layer is two squares meeting at (10, 10).
  for (int layer = 0; layer < 5; ++layer) {
    const auto v = resolve_ok({rect(0, 0, 10000000, 10000000), rect(10000000, 10000000, 20000000, 20000000)});
    CHECK(v.size() == 2);
  }
  // Sharing a face instead: one island.
  CHECK(resolve_ok({rect(0, 0, 10, 10), rect(10, 0, 20, 10)}).size() == 1);
}

TEST_CASE("resolve: strict mode turns the first coherence problem into an error") {
  Report rep;
  ResolveOptions o;
  o.strict = true;
  o.layer_index = 12;
  auto r = resolve_islands({mm_ring({{0, 0}, {20, 20}, {20, 0}, {0, 20}})}, o, rep);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().where == "layer 12 at (10.000, 10.000) mm");
  CHECK(r.error().message.find("intersecting-loops") != std::string::npos);
  CHECK(rep.empty());
  // Clean input passes in strict mode.
  CHECK(resolve_islands({rect(0, 0, 10, 10)}, o, rep).ok());
}

TEST_CASE("resolve: loops closed by gap repair are reported") {
  Report rep;
  const std::vector<uint8_t> repaired{0, 1};
  ResolveOptions o;
  o.layer_index = 0;
  auto r = resolve_islands({rect(0, 0, 10, 10), rect(20, 0, 30, 10)}, o, rep, repaired);
  REQUIRE(r.ok());
  CHECK(rep.count("repaired-loop") == 1);
}

TEST_CASE("resolve: coordinates beyond the sweep range are an error, not a crash") {
  Report rep;
  const coord_t far = coord_t{1} << 40;
  auto r = resolve_islands({rect(0, 0, far, far)}, {}, rep);
  CHECK_FALSE(r.ok());
}

TEST_CASE("resolve: a vertex touching another loop's edge splits there") {
  // Triangle touching the square's right edge at its middle: two islands; a hole touching an
  // edge inside: the rings get a shared vertex.
  CHECK(resolve_ok({rect(0, 0, 10, 10), Ring{{10, 5}, {20, 0}, {20, 10}}}).size() == 2);
  const auto v = resolve_ok({rect(0, 0, 10, 10), Ring{{5, 10}, {6, 8}, {5, 6}, {4, 8}}});
  REQUIRE(v.size() == 1);
  bool shared = false;
  for (const auto& p : v[0].shape.outer) shared |= p == Point(5, 10);
  CHECK(shared);
}

TEST_CASE("resolve: subtractive painting erases what is below") {
  std::vector<PaintedShape> shapes(3);
  shapes[0].loops = {rect(0, 0, 30, 30)};
  shapes[1].loops = {rect(10, 10, 20, 20)};
  shapes[1].erase = true;
  shapes[2].loops = {rect(12, 12, 18, 18)};
  auto painted = paint(shapes);
  REQUIRE(painted.ok());
  const auto v = resolve_ok(*painted);
  CHECK(v.size() == 2);
  CHECK(total_holes(v) == 1);
}

TEST_CASE("resolve: layer wrapper fills islands") {
  Report rep;
  Layer layer;
  layer.index = 4;
  layer.loops = {rect(0, 0, 10, 10), rect(20, 0, 30, 10)};
  REQUIRE(resolve_layer(layer, {}, rep).ok());
  CHECK(layer.islands.size() == 2);
}
