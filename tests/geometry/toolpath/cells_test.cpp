// Fill regions cut into cells: the zig-zags of region_shape() are the region's monotone pieces at
// the resolution of the lines. On regions that once broke the exact decomposition, the cells
// fill the region (their areas add up to it) and stay inside it.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "geometry/toolpath/cells.h"
#include "geometry/toolpath/clip.h"
#include "fixtures.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::toolpath;
namespace fs = std::filesystem;

namespace {
// tests/data/fill-regions/*.txt: "# angle A" then "loop" and one "x y" (nm) per line.
struct Region {
  double angle = 45;
  geo::Rings rings;
};
Region read_region(const fs::path& p) {
  Region r;
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("# angle ", 0) == 0) r.angle = std::stod(line.substr(8));
    if (line.empty() || line[0] == '#') continue;
    if (line == "loop") {
      r.rings.emplace_back();
      continue;
    }
    std::istringstream ss(line);
    long long x, y;
    ss >> x >> y;
    r.rings.back().push_back(geo::Point(x, y));
  }
  return r;
}
}  // namespace

TEST_CASE("cells: regions whose rings touch are filled whole, inside, in few zig-zags") {
  int files = 0;
  for (const auto& e : fs::directory_iterator(test::source_dir() / "tests" / "data" / "fill-regions")) {
    if (e.path().extension() != ".txt") continue;
    ++files;
    INFO(e.path().filename().string());
    Region r = read_region(e.path());
    REQUIRE_FALSE(r.rings.empty());
    EdgeGrid border(r.rings);
    FillShape shape = region_shape(r.rings, border);
    REQUIRE_FALSE(shape.rings.empty());
    for (const auto& k : shape.kinds)
      for (auto kind : k) CHECK(kind == geo::EdgeKind::Real);  // the whole border is the island's
    FillSpec spec;
    spec.angle_deg = r.angle;
    spec.pitch_mm = 0.4;
    auto cells = zigzag(shape, spec);
    double area = 0, want = 0;
    for (const auto& c : cells) {
      area += c.area_mm2;
      for (size_t i = 0; i + 1 < c.pts.size(); ++i) {
        geo::Point m((c.pts[i].X + c.pts[i + 1].X) / 2, (c.pts[i].Y + c.pts[i + 1].Y) / 2);
        CHECK((border.inside(m) || border.along(c.pts[i], c.pts[i + 1], 20)));
      }
    }
    for (const auto& ring : r.rings) want += geo::area_mm2(ring);
    CHECK(area == doctest::Approx(std::abs(want)).epsilon(0.05));
    // Linked along the border, the region needs no more zig-zags than before, and fewer.
    spec.link_max_mm = 3 * spec.pitch_mm;
    auto linked = zigzag(shape, spec);
    CHECK(linked.size() <= cells.size());
    double linked_area = 0;
    for (const auto& c : linked) linked_area += c.area_mm2;
    CHECK(linked_area == doctest::Approx(area));
  }
  CHECK(files >= 3);
}

TEST_CASE("cells: an edge is artificial where it is not on the island's fill border") {
  // The island's fill region is the 10 x 10 square; this region is its left half.
  EdgeGrid border(geo::Rings{test::rect(0, 0, 10, 10)});
  FillShape shape = region_shape({test::rect(0, 0, 5, 10)}, border);
  REQUIRE(shape.rings.size() == 1);
  int artificial = 0;
  const auto& ring = shape.rings[0];
  for (size_t i = 0; i < ring.size(); ++i) {
    const auto &a = ring[i], &b = ring[(i + 1) % ring.size()];
    bool inner = a.X == geo::to_units(5) && b.X == geo::to_units(5);
    CHECK((shape.kinds[0][i] == geo::EdgeKind::Artificial) == inner);
    artificial += inner;
  }
  CHECK(artificial == 1);
}
