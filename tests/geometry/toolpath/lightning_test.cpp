// Lightning infill's trees (geometry/toolpath/lightning.h): where they are needed, how far they
// reach, that they branch, stay inside the part and shrink away below the tops they hold.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <set>

#include "fixtures.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/edge_grid.h"
#include "geometry/toolpath/infill_patterns.h"
#include "geometry/toolpath/lightning.h"
#include "geometry/toolpath/zigzag.h"

using namespace tranche;
using namespace tranche::toolpath;

namespace {

constexpr double kH = 0.2, kSpacing = 0.45, kWidth = 0.45;

double length_mm(const geo::Rings& lines) {
  double l = 0;
  for (const auto& line : lines)
    for (size_t i = 1; i < line.size(); ++i)
      l += std::hypot(geo::to_mm(line[i].X - line[i - 1].X), geo::to_mm(line[i].Y - line[i - 1].Y));
  return l;
}

// A 40 mm square slab (layers 0-9) under a 6 mm square tower (layers 10-59): the tower's top,
// 50 layers above the slab's, is the small top far above.
std::vector<geo::Layer> slab_and_tower() {
  std::vector<geo::Layer> layers = test::stack(60, kH, geo::Polygon{test::rect(0, 0, 40, 40), {}});
  for (int i = 10; i < 60; ++i) layers[static_cast<size_t>(i)].islands[0].shape = geo::Polygon{test::rect(17, 17, 23, 23), {}};
  return layers;
}

// The slicer's spec (geometry/plan/island_content.cpp): PrusaSlicer's supporting radius, width /
// density, and its 45°.
LightningSpec spec_at(double density) {
  LightningSpec s;
  s.top_layers = 3;
  s.radius_mm = kWidth / density;
  s.inset_mm = 0.9;
  s.angle_deg = 45;
  return s;
}

// The distance from (x, y) to the nearest node (polyline point) of a layer's trees.
double nearest_node_mm(const geo::Rings& lines, double x, double y) {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& line : lines)
    for (const auto& p : line) d = std::min(d, std::hypot(geo::to_mm(p.X) - x, geo::to_mm(p.Y) - y));
  return d;
}

}  // namespace

TEST_CASE("lightning: the areas to hold up are the undersides of the tops") {
  const auto layers = slab_and_tower();
  const auto a = lightning_areas(layers, spec_at(0.2));
  // The tower's top layers 57-59 are solid: layer 56 holds them up, its whole sparse area less
  // the walls' band (0.2·tan 45° wide).
  const double wall = kH * std::tan(45 * M_PI / 180), side = 6 - 2 * 0.9 - 2 * wall;
  CHECK(area_mm2(a.need[56]) == doctest::Approx(side * side).epsilon(0.01));
  for (int i = 10; i < 56; ++i) CHECK(a.need[static_cast<size_t>(i)].empty());
  // The slab's top (layers 7-9, less the tower) over layer 6.
  CHECK(area_mm2(a.need[6]) == doctest::Approx((38.2 - 2 * wall) * (38.2 - 2 * wall) - 36).epsilon(0.01));
  CHECK(a.outline[57].empty());
  CHECK(area_mm2(a.outline[30]) == doctest::Approx(4.2 * 4.2).epsilon(1e-3));
}

// PrusaSlicer's meaning of the density: every point of a top's underside within width /
// density of a leaf (a node of the trees, not only a branch), less the sampling grid's margin
// (half its diagonal: the grid is a sixth of the radius).
TEST_CASE("lightning: every point under a top is within the radius of a node") {
  for (double density : {0.2, 0.3}) {
    CAPTURE(density);
    const auto layers = slab_and_tower();
    const LightningSpec spec = spec_at(density);
    const auto trees = lightning_trees(layers, spec);
    const auto a = lightning_areas(layers, spec);
    REQUIRE(!trees[56].empty());
    const double reach = spec.radius_mm * (1 + std::sqrt(0.5) / 6) + 1e-3;
    for (int layer : {56, 6}) {
      CAPTURE(layer);
      const EdgeGrid need(a.need[static_cast<size_t>(layer)]);
      const geo::BBox2 b = bbox(a.need[static_cast<size_t>(layer)]);
      double worst = 0;
      int samples = 0;
      for (double x = geo::to_mm(b.min_x); x <= geo::to_mm(b.max_x); x += 0.13)
        for (double y = geo::to_mm(b.min_y); y <= geo::to_mm(b.max_y); y += 0.13) {
          if (!need.inside(geo::to_point(x, y))) continue;
          ++samples;
          worst = std::max(worst, nearest_node_mm(trees[static_cast<size_t>(layer)], x, y));
        }
      CAPTURE(worst);
      CHECK(samples > 50);
      CHECK(worst <= reach);
      // Not much closer either: the leaves are spread a radius apart.
      CHECK(worst > 0.6 * spec.radius_mm);
    }
  }
}

// Plastic per area: under a large flat top (the slab's, 38 mm square, at 20 %) the leaves are
// laid one per disc of a radius (2.25 mm) left unheld, about one per 1.5–2 R² of top, each
// joined by a branch of one to two radii: 0.5–1.1 mm of branch per mm² of top divided by the
// radius (a grid at 20 % lays 0.2 / spacing = 0.44 mm/mm², 1 / R). Then the trees shrink by the
// pruning, 0.2 mm a layer from each tip (45°).
TEST_CASE("lightning: the branch length under a large top, and its shrinking below") {
  const auto layers = slab_and_tower();
  const LightningSpec spec = spec_at(0.2);
  const auto trees = lightning_trees(layers, spec);
  const auto a = lightning_areas(layers, spec);
  const double top_area = area_mm2(a.need[6]);
  const double per_area = length_mm(trees[6]) / top_area;
  CAPTURE(per_area);
  CHECK(per_area > 0.5 / spec.radius_mm);
  CHECK(per_area < 1.1 / spec.radius_mm);
  CHECK(length_mm(trees[5]) < length_mm(trees[6]));
  CHECK(length_mm(trees[2]) < 0.9 * length_mm(trees[6]));
  // Most leaves join a tree, not the walls: far fewer trees (roots: polylines starting on the
  // slab's sparse border, 0.9 mm inside its sides) than polylines.
  size_t roots = 0;
  for (const auto& line : trees[6]) {
    const double x = geo::to_mm(line[0].X), y = geo::to_mm(line[0].Y);
    if (std::min({x - 0.9, 39.1 - x, y - 0.9, 39.1 - y}) < 0.01) ++roots;
  }
  CAPTURE(roots);
  CAPTURE(trees[6].size());
  CHECK(roots > 0);
  CHECK(2 * roots < trees[6].size());
}

TEST_CASE("lightning: a small top far above gets a thin tree that shrinks away below it") {
  const auto layers = slab_and_tower();
  const LightningSpec spec = spec_at(0.2);
  const auto trees = lightning_trees(layers, spec);
  const auto a = lightning_areas(layers, spec);
  // Under the tower's top: a tree of about the grid's length at this density (area × d / s).
  const double grid_per_layer = area_mm2(a.outline[56]) * 0.2 / kSpacing;
  const double top = length_mm(trees[56]);
  CHECK(top > 0.5 * grid_per_layer);
  CHECK(top < 1.5 * grid_per_layer);
  // Going down the tower the branches are pruned by 0.2 mm a layer: shorter and shorter, and
  // gone well before the slab (every branch of a 4.2 mm wide tower is under 3 mm long).
  double last = top;
  for (int i = 55; i >= 10; --i) {
    const double l = length_mm(trees[static_cast<size_t>(i)]);
    CHECK(l <= last + 1e-6);
    last = l;
  }
  CHECK(length_mm(trees[40]) < 0.5 * top);
  CHECK(trees[20].empty());
  // The tower's plastic is far below the grid's over the same layers.
  double tower = 0;
  for (int i = 10; i <= 56; ++i) tower += length_mm(trees[static_cast<size_t>(i)]);
  CHECK(tower < 0.3 * 47 * grid_per_layer);
}

TEST_CASE("lightning: the trees branch, stay inside the sparse area and have no empty edges") {
  const auto layers = slab_and_tower();
  const LightningSpec spec = spec_at(0.2);
  const auto trees = lightning_trees(layers, spec);
  const auto a = lightning_areas(layers, spec);
  size_t branching = 0;
  for (size_t i = 0; i < trees.size(); ++i) {
    CAPTURE(i);
    if (trees[i].empty()) continue;
    const EdgeGrid outline(a.outline[i]);
    std::set<std::pair<geo::coord_t, geo::coord_t>> starts;
    for (const auto& line : trees[i]) {
      REQUIRE(line.size() >= 2);
      for (size_t k = 0; k < line.size(); ++k) {
        CHECK(outline.inside(line[k]));
        if (k == 0) continue;
        CHECK(line[k] != line[k - 1]);  // no zero-length move
        CHECK_FALSE(outline.crosses(line[k - 1], line[k]));
      }
      starts.insert({line[0].X, line[0].Y});
    }
    // Branches start from other branches: fewer distinct starts than polylines.
    if (starts.size() < trees[i].size()) ++branching;
  }
  CHECK(branching > 0);
  // The slab's top holds many trees at layer 6; they join the slab's border.
  CHECK(trees[6].size() > 10);
}

TEST_CASE("lightning: a plate with round holes keeps its trees out of the holes") {
  geo::Polygon plate{test::rect(0, 0, 40, 40), {}};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      geo::Ring hole;
      for (int k = 63; k >= 0; --k)  // clockwise
        hole.push_back(geo::to_point(5 + 10 * i + 2 * std::cos(k * M_PI / 32), 5 + 10 * j + 2 * std::sin(k * M_PI / 32)));
      plate.holes.push_back(hole);
    }
  const auto layers = test::stack(40, kH, plate);
  const auto trees = lightning_trees(layers, spec_at(0.2));
  REQUIRE(!trees[36].empty());
  for (const auto& line : trees[36])
    for (const auto& p : line)
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
          CHECK(std::hypot(geo::to_mm(p.X) - (5 + 10 * i), geo::to_mm(p.Y) - (5 + 10 * j)) > 2 + 0.9 - 0.01);
}

TEST_CASE("lightning: bad specs give no branches; the cache gives the layer tasks the same trees") {
  const auto layers = slab_and_tower();
  LightningSpec bad = spec_at(0.2);
  bad.radius_mm = 0;
  for (const auto& t : lightning_trees(layers, bad)) CHECK(t.empty());
  bad.radius_mm = std::numeric_limits<double>::quiet_NaN();
  for (const auto& t : lightning_trees(layers, bad)) CHECK(t.empty());
  bad = spec_at(0.2);
  bad.angle_deg = std::numeric_limits<double>::quiet_NaN();
  for (const auto& t : lightning_trees(layers, bad)) CHECK(t.empty());
  bad = spec_at(0.2);
  bad.inset_mm = std::numeric_limits<double>::infinity();  // taken as no walls
  CHECK(!lightning_trees(layers, bad)[56].empty());
  // A density near zero: one branch reaches everything, still no NaN.
  bad = spec_at(1e-6);
  for (const auto& t : lightning_trees(layers, bad))
    for (const auto& line : t) CHECK(line.size() >= 2);
  const LightningCache cache;
  const auto direct = lightning_trees(layers, spec_at(0.2));
  for (int i = 0; i < 60; ++i) CHECK(cache.lines(layers, i, spec_at(0.2)) == direct[static_cast<size_t>(i)]);
  CHECK(cache.lines(layers, 70, spec_at(0.2)).empty());  // past the top
  CHECK(cache.lines(layers, -1, spec_at(0.2)).empty());
}

TEST_CASE("lightning: branches clipped to a region become joined fill paths") {
  const auto layers = slab_and_tower();
  const auto trees = lightning_trees(layers, spec_at(0.2));
  PatternSpec ps;
  ps.pattern = schema::InfillPattern::Lightning;
  ps.spacing_mm = kSpacing;
  ps.density = 0.2;
  ps.link_max_mm = 5 * kSpacing / 0.2;
  // The sparse region a little inside the trees' outline: the roots are cut at its border.
  const geo::Rings region{test::rect(18, 18, 22, 22)};
  const auto fps = clip_fill_lines(trees[56], fill_shape(region, geo::EdgeKind::Real), ps);
  REQUIRE(!fps.empty());
  double l = 0;
  for (const auto& fp : fps) {
    CHECK(fp.area_mm2 > 0);
    for (size_t k = 0; k < fp.pts.size(); ++k) {
      CHECK(geo::to_mm(fp.pts[k].X) >= 18 - 1e-3);
      CHECK(geo::to_mm(fp.pts[k].X) <= 22 + 1e-3);
      if (k > 0) {
        CHECK(fp.pts[k] != fp.pts[k - 1]);
        l += std::hypot(geo::to_mm(fp.pts[k].X - fp.pts[k - 1].X), geo::to_mm(fp.pts[k].Y - fp.pts[k - 1].Y));
      }
    }
  }
  CHECK(l > 0.5 * length_mm(trees[56]));
  CHECK(clip_fill_lines({}, fill_shape(region, geo::EdgeKind::Real), ps).empty());
}

namespace {

// A dome: a hemisphere of radius `r` mm on the bed, layers of kH, each a 96-gon. Every layer's
// edge is a top (the layer above is smaller), so every layer grows leaves near its walls, and
// the trees carried down keep the ones from above: the rounded tops of the bench's sphere and
// bunny.
std::vector<geo::Layer> dome(double r) {
  const int n = static_cast<int>(r / kH);
  std::vector<geo::Layer> layers = test::stack(n, kH, geo::Polygon{test::rect(0, 0, 1, 1), {}});
  for (int i = 0; i < n; ++i) {
    const double z = (i + 0.5) * kH, rr = std::sqrt(r * r - z * z);
    geo::Ring ring;
    for (int k = 0; k < 96; ++k)
      ring.push_back(geo::to_point(r + rr * std::cos(k * M_PI / 48), r + rr * std::sin(k * M_PI / 48)));
    layers[static_cast<size_t>(i)].islands[0].shape = geo::Polygon{ring, {}};
  }
  return layers;
}

double total_mm(const std::vector<geo::Rings>& trees) {
  double l = 0;
  for (const auto& t : trees) l += length_mm(t);
  return l;
}

}  // namespace

// A denser lightning is more plastic: the total branch length over a dome's layers grows with
// the density all the way to 95 % (it used to peak near 65 % and fall, the bunny's infill with
// it: at high densities a leaf found the tree nodes only a radius beyond the border, so the
// join bonus of 4 radii never counted and the trees stayed short and died within a few layers).
TEST_CASE("lightning: a dome's branch length grows with the density up to 95 %") {
  const auto layers = dome(15);
  double last = 0;
  for (double density : {0.2, 0.35, 0.5, 0.65, 0.8, 0.95}) {
    CAPTURE(density);
    const double l = total_mm(lightning_trees(layers, spec_at(density)));
    CAPTURE(l);
    CAPTURE(last);
    CHECK(l > 1.02 * last);
    last = l;
  }
}

// The join bonus at every density: a leaf joins a tree node up to 4 radii further than the
// border (PrusaSlicer's valence boost), so under a large top the number of trees standing on
// the walls hardly changes with the density: more leaves, on the same trees (with nodes looked
// for only a radius beyond the border, the slab's top had 31 trees at 20 %, 67 at 50 % and 106
// at 95 %: the new leaves near the walls started trees of their own, short and soon pruned).
TEST_CASE("lightning: leaves join trees rather than the walls at high densities too") {
  const auto layers = slab_and_tower();
  size_t at20 = 0;
  for (double density : {0.2, 0.5, 0.8, 0.95}) {
    CAPTURE(density);
    const auto trees = lightning_trees(layers, spec_at(density));
    size_t roots = 0;  // polylines starting on the slab's sparse border, 0.9 mm inside its sides
    for (const auto& line : trees[6]) {
      const double x = geo::to_mm(line[0].X), y = geo::to_mm(line[0].Y);
      if (std::min({x - 0.9, 39.1 - x, y - 0.9, 39.1 - y}) < 0.01) ++roots;
    }
    CAPTURE(roots);
    CAPTURE(trees[6].size());
    if (at20 == 0) at20 = roots;
    CHECK(roots > 0);
    CHECK(roots < 1.5 * static_cast<double>(at20));
  }
}
