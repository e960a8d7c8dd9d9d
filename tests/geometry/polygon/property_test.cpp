// Randomised properties over thousands of generated polygons (fixed seeds): whatever the input,
// resolution gives valid strict islands covering the same area as a plain union, and every
// decomposition tiles its island with monotone cells whose real edges are exactly the boundary.
#include <doctest/doctest.h>

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "generators.h"
#include "geometry/polygon/corpus.h"
#include "geometry/polygon/decompose.h"
#include "geometry/polygon/resolve.h"
#include "polygon_checks.h"

using namespace tranche;
using namespace tranche::geo;

namespace {

using test::i128;
using namespace tranche::test::gen;

double random_angle(Rng& rng) {
  switch (pick(rng, 0, 3)) {
    case 0:
      return 45.0 * pick(rng, 0, 7);  // exactly parallel to many generated edges
    case 1:
      return pick(rng, 0, 179);
    default:
      return uniform(rng, -180, 360);
  }
}

// Writes a failing case where it can be turned into a corpus entry.
std::string dump(const Rings& loops, OverlapMode mode, double angle, const std::string& tag) {
  PolygonCase c;
  c.mode = mode;
  c.angles = {angle};
  c.loops = loops;
  const auto path = std::filesystem::temp_directory_path() / fmt::format("tranche-polygon-{}.txt", tag);
  std::ofstream(path) << format_polygon_case(c);
  return path.string();
}

struct Totals {
  int cases = 0, islands = 0, cells = 0, failures = 0;
};

void run_case(const Rings& loops, OverlapMode mode, Rng& rng, const std::string& tag, Totals& t) {
  ++t.cases;
  Report rep;
  ResolveOptions o;
  o.overlap = mode;
  auto islands = resolve_islands(loops, o, rep);
  if (!islands) {
    FAIL_CHECK(fmt::format("{}: resolve failed: {} (case in {})", tag, islands.error().to_string(),
                           dump(loops, mode, 0, tag)));
    ++t.failures;
    return;
  }
  for (const auto& is : *islands) {
    const std::string p = test::island_problem(is);
    if (!p.empty()) {
      FAIL_CHECK(fmt::format("{}: bad island: {} (case in {})", tag, p, dump(loops, mode, 0, tag)));
      ++t.failures;
      return;
    }
  }
  if (const std::string p = test::coverage_problem(loops, mode == OverlapMode::Boolean, *islands, rng, 64);
      !p.empty()) {
    FAIL_CHECK(fmt::format("{}: {} (case in {})", tag, p, dump(loops, mode, 0, tag)));
    ++t.failures;
    return;
  }
  for (const auto& is : *islands) {
    ++t.islands;
    for (int k = 0; k < 2; ++k) {
      const double angle = random_angle(rng);
      auto cells = decompose(is.shape, angle);
      std::string p = cells ? test::cells_problem(is, *cells, angle, true, &rng) : cells.error().to_string();
      if (!p.empty()) {
        FAIL_CHECK(fmt::format("{}: decomposition at {}°: {} (case in {})", tag, angle, p,
                               dump(loops, mode, angle, tag)));
        ++t.failures;
        return;
      }
      t.cells += static_cast<int>(cells->size());
    }
  }
}

// TRANCHE_PROPERTY_SCALE=N runs N times as many cases, with other seeds (for stress runs).
int scale() {
  const char* s = std::getenv("TRANCHE_PROPERTY_SCALE");
  return s ? std::max(1, std::atoi(s)) : 1;
}

void run_family(const char* name, int count, uint64_t seed, const std::function<Rings(Rng&)>& make,
                OverlapMode mode = OverlapMode::Additive) {
  count *= scale();
  Rng rng(seed * static_cast<uint64_t>(scale()));
  Totals t;
  for (int i = 0; i < count && t.failures < 3; ++i) {
    run_case(make(rng), mode, rng, fmt::format("{}-{}", name, i), t);
  }
  MESSAGE(fmt::format("{}: {} cases, {} islands, {} cells", name, t.cases, t.islands, t.cells));
  CHECK(t.failures == 0);
  CHECK(t.islands > 0);
}

}  // namespace

TEST_CASE("property: stars with holes, fine and coarse grids") {
  run_family("stars", 600, 11, [](Rng& rng) { return stars_with_holes(rng, 1); });
  run_family("stars-grid", 600, 12, [](Rng& rng) { return stars_with_holes(rng, 1000000); });
}

TEST_CASE("property: unions of rectangles") {
  run_family("rects", 800, 21, rectangles);
  run_family("rects-xor", 400, 22, rectangles, OverlapMode::Boolean);
}

TEST_CASE("property: unions of circles") {
  run_family("circles", 500, 31, [](Rng& rng) { return circles(rng, 1); });
  run_family("circles-grid", 300, 32, [](Rng& rng) { return circles(rng, 500000); });
  run_family(
      "circles-xor", 300, 33, [](Rng& rng) { return circles(rng, 1); }, OverlapMode::Boolean);
}

TEST_CASE("property: nested disjoint loops, fast path against the union path") {
  run_family("nested", 400, 51, nested);
  run_family("nested-xor", 400, 52, nested, OverlapMode::Boolean);
  Rng rng(53);
  for (int i = 0; i < 400; ++i) {
    const Rings loops = nested(rng);
    for (OverlapMode mode : {OverlapMode::Additive, OverlapMode::Boolean}) {
      Report rep;
      ResolveOptions o;
      o.overlap = mode;
      auto fast = resolve_islands(loops, o, rep);  // no contacts: decided without Clipper
      auto slow = strict_islands(loops, mode);
      REQUIRE(fast.ok());
      REQUIRE(slow.ok());
      REQUIRE(fast->size() == slow->size());
      for (size_t k = 0; k < fast->size(); ++k) {
        CHECK(test::island_area2((*fast)[k]) == test::island_area2((*slow)[k]));
        CHECK((*fast)[k].shape.holes.size() == (*slow)[k].shape.holes.size());
      }
    }
  }
}

TEST_CASE("property: self-intersecting scribbles") {
  run_family("scribbles", 600, 41, [](Rng& rng) { return scribbles(rng, 1000000); });
  run_family(
      "scribbles-xor", 600, 42, [](Rng& rng) { return scribbles(rng, 1000000); }, OverlapMode::Boolean);
  run_family("scribbles-fine", 300, 43, [](Rng& rng) { return scribbles(rng, 1237); });
}
