// Replays tests/data/polygons/*.txt: polygons that once broke resolution or decomposition.
#include <doctest/doctest.h>

#include <fmt/format.h>

#include <filesystem>

#include "geometry/polygon/corpus.h"
#include "geometry/polygon/decompose.h"
#include "polygon_checks.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::geo;

TEST_CASE("corpus: every stored polygon resolves and decomposes with all properties") {
  const auto dir = test::source_dir() / "tests" / "data" / "polygons";
  REQUIRE(std::filesystem::is_directory(dir));
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".txt") continue;
    ++files;
    const std::string name = entry.path().filename().string();
    CAPTURE(name);
    auto c = load_polygon_case(entry.path().string());
    REQUIRE_MESSAGE(c.ok(), (c.ok() ? "" : c.error().to_string()));
    Report rep;
    ResolveOptions o;
    o.overlap = c->mode;
    auto islands = resolve_islands(c->loops, o, rep);
    REQUIRE_MESSAGE(islands.ok(), (islands.ok() ? "" : islands.error().to_string()));
    int holes = 0;
    for (const auto& is : *islands) {
      CHECK_MESSAGE(test::island_problem(is).empty(), test::island_problem(is));
      holes += static_cast<int>(is.shape.holes.size());
    }
    std::mt19937_64 rng(7);
    CHECK(test::coverage_problem(c->loops, c->mode == OverlapMode::Boolean, *islands, rng, 256) == "");
    if (c->expect_islands >= 0) CHECK(static_cast<int>(islands->size()) == c->expect_islands);
    if (c->expect_holes >= 0) CHECK(holes == c->expect_holes);
    std::vector<double> angles = c->angles;
    for (const auto& [a, n] : c->expect_cells) angles.push_back(a);
    for (double a : angles) {
      int total = 0;
      for (const auto& is : *islands) {
        auto cells = decompose(is.shape, a);
        REQUIRE_MESSAGE(cells.ok(), (cells.ok() ? "" : cells.error().to_string()));
        CHECK_MESSAGE(test::cells_problem(is, *cells, a, true, &rng) == "", fmt::format("at {}°", a));
        total += static_cast<int>(cells->size());
      }
      for (const auto& [ea, n] : c->expect_cells) {
        if (ea == a) CHECK_MESSAGE(total == n, fmt::format("cells at {}°", a));
      }
    }
  }
  CHECK(files >= 10);
}

TEST_CASE("corpus: the format round-trips and bad lines name the file and line") {
  PolygonCase c;
  c.mode = OverlapMode::Boolean;
  c.angles = {10, 20.5};
  c.expect_islands = 2;
  c.expect_cells = {{20.5, 3}};
  c.loops = {test::rect(0, 0, 5, 5), test::rect(-3, -4, 7, 9)};
  auto back = parse_polygon_case(format_polygon_case(c), "x.txt");
  REQUIRE(back.ok());
  CHECK(back->mode == OverlapMode::Boolean);
  CHECK(back->angles == c.angles);
  CHECK(back->expect_islands == 2);
  CHECK(back->expect_cells == c.expect_cells);
  CHECK(back->loops == c.loops);
  auto bad = parse_polygon_case("loop\n1 2\n3 x\n", "bad.txt");
  REQUIRE_FALSE(bad.ok());
  CHECK(bad.error().where == "bad.txt:3");
  CHECK_FALSE(parse_polygon_case("1 2\n", "b.txt").ok());
  CHECK_FALSE(parse_polygon_case("mode sideways\n", "b.txt").ok());
  CHECK_FALSE(load_polygon_case("/nonexistent/file.txt").ok());
}

TEST_CASE("corpus: decompose_region splits a pinched region into islands first") {
  // Two squares touching at a corner, given as one region.
  auto cells = decompose_region({test::rect(0, 0, 10, 10), test::rect(10, 10, 20, 20)}, 45);
  REQUIRE(cells.ok());
  CHECK(cells->size() == 2);
}
