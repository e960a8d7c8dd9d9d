// Fill regions cut into cells: the zig-zags of region_shape() are the region's monotone pieces at
// the resolution of the lines. On regions that once broke the exact decomposition, the cells
// fill the region (their areas add up to it) and stay inside it.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "fixtures.h"
#include "geometry/toolpath/cells.h"
#include "geometry/toolpath/clip.h"
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
    FillShape shape = region_shape(r.rings, {&border}, 0.1);
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
  FillShape shape = region_shape({test::rect(0, 0, 5, 10)}, {&border}, 0.1);
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
  // With solid regions in the island, its border is also the fill region grown by a quarter
  // bead: a sparse region (not grown) still meets the perimeters on the fill region's edges.
  EdgeGrid wide(offset(geo::Rings{test::rect(0, 0, 10, 10)}, 0.1125));
  FillShape both = region_shape({test::rect(0, 0, 5, 10)}, {&border, &wide}, 0.1125);
  REQUIRE(both.rings.size() == 1);
  CHECK(both.kinds[0] == shape.kinds[0]);
}

TEST_CASE("cells: a solid region grown into the perimeters has its whole outer edge real") {
  // As the fill stage builds solid regions: from booleans with the neighbouring layers, grown by
  // a quarter bead, clipped to the fill region grown as much. Where the region meets the
  // island's fill border, its edges come from different polygons that agree to within a few
  // micrometres; labelled with a tolerance of nanometres, they alternated real and artificial,
  // and the zig-zag's connectors (artificial edges are inset) became a saw that laid 1.65 times
  // the plastic on a sphere's second layer.
  geo::Ring circle;
  for (int i = 0; i < 90; ++i)
    circle.push_back(geo::to_point(5 * std::cos(i * M_PI / 45), 5 * std::sin(i * M_PI / 45)));
  geo::Rings fill{circle};
  const double reach = 0.1;
  geo::Rings wide = offset(fill, reach);
  // The region: the left half, as the layer below (the same circle turned by 2°, its vertices
  // mid-edge of this one's, up to 3 µm further out) cuts it.
  geo::Ring below;
  for (int i = 0; i < 90; ++i) {
    double t = i * M_PI / 45 + M_PI / 90;
    below.push_back(geo::to_point(5 * std::cos(t), 5 * std::sin(t)));
  }
  geo::Rings left = intersection(intersection(fill, {below}), {test::rect(-6, -6, 0, 6)});
  geo::Rings region = intersection(offset(left, reach), wide);
  EdgeGrid fill_grid(fill), wide_grid(wide);
  FillShape shape = region_shape(region, {&fill_grid, &wide_grid}, 0.1);
  REQUIRE(shape.rings.size() == 1);
  const auto& ring = shape.rings[0];
  int on_border = 0, real = 0;
  for (size_t i = 0; i < ring.size(); ++i) {
    const auto &a = ring[i], &b = ring[(i + 1) % ring.size()];
    // Both ends on the grown circle (radius 5.1 mm, within a micrometre and its chords' sag).
    auto r = [](const geo::Point& p) { return std::hypot(geo::to_mm(p.X), geo::to_mm(p.Y)); };
    if (std::abs(r(a) - 5.1) > 0.01 || std::abs(r(b) - 5.1) > 0.01 || geo::to_mm(a.X) > -0.2) continue;
    ++on_border;
    real += shape.kinds[0][i] == geo::EdgeKind::Real;
  }
  CHECK(on_border > 20);
  CHECK(real == on_border);
}

TEST_CASE("cells: a cell's core is the part of the region its lines fill, in one piece") {
  // A 20 mm square with a 6 mm hole: at 30° its region is cut into several cells.
  geo::Rings region{test::rect(0, 0, 20, 20), test::rect(7, 7, 13, 13, false)};
  EdgeGrid border(region);
  FillSpec spec;
  spec.angle_deg = 30;
  spec.pitch_mm = 2;
  spec.artificial_inset_mm = 0.2;
  auto cells = zigzag(region_shape(region, {&border}, 0.1), spec);
  REQUIRE(cells.size() >= 2);
  geo::Rings all;
  for (const auto& c : cells) {
    geo::Rings core = cell_core(c, spec.angle_deg, spec.pitch_mm);
    // One piece without holes or slits (the lines of a zig-zag run both ways), about as large
    // as what its lines fill.
    CHECK(core.size() == 1);
    CHECK(area_mm2(core) == doctest::Approx(c.area_mm2).epsilon(0.1));
    all = union_of(all, core);
  }
  // Grown by half a bead and clipped, the cores cover the region, overlapping only at the cuts.
  CHECK(area_mm2(intersection(offset(all, 0.2), region)) == doctest::Approx(area_mm2(region)).epsilon(0.02));
}
