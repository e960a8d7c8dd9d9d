#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <set>

#include "fixtures.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/edge_grid.h"
#include "geometry/toolpath/flow.h"
#include "geometry/toolpath/motion.h"
#include "geometry/toolpath/order.h"

using namespace tranche;
using namespace tranche::toolpath;
using doctest::Approx;

TEST_CASE("flow: the stadium cross-section and bead spacing of Slic3r/PrusaSlicer") {
  const double w = 0.45, h = 0.2;
  CHECK(bead_area_mm2(w, h) == Approx((w - h) * h + std::numbers::pi * 0.01));
  CHECK(bead_spacing_mm(w, h) == Approx(w - h * (1 - std::numbers::pi / 4)));
  CHECK(bead_spacing_mm(w, w, h) == Approx(bead_spacing_mm(w, h)));
  // E per mm: bead area over the filament's cross-section.
  CHECK(e_per_mm(w, h, 1.0, 1.75) == Approx(bead_area_mm2(w, h) / (std::numbers::pi * 1.75 * 1.75 / 4)));
  CHECK(e_per_mm(w, h, 0.5, 1.75) == Approx(0.5 * e_per_mm(w, h, 1.0, 1.75)));
}

TEST_CASE("edge grid: crossing, inside and covered fraction against a square with a hole") {
  geo::Rings rings{test::rect(0, 0, 10, 10), test::rect(4, 4, 6, 6, false)};
  EdgeGrid g(rings);
  CHECK(g.inside(geo::to_point(1, 1)));
  CHECK_FALSE(g.inside(geo::to_point(5, 5)));
  CHECK_FALSE(g.inside(geo::to_point(11, 5)));
  CHECK_FALSE(g.inside(geo::to_point(-1, 5)));
  CHECK(g.crosses(geo::to_point(1, 5), geo::to_point(9, 5)));  // through the hole
  CHECK_FALSE(g.crosses(geo::to_point(1, 1), geo::to_point(9, 2)));
  CHECK(g.crosses(geo::to_point(5, -1), geo::to_point(5, 1)));
  CHECK(g.inside_fraction(geo::to_point(-2, 1), geo::to_point(2, 1)) == Approx(0.5));
  CHECK(g.inside_fraction(geo::to_point(1, 5), geo::to_point(9, 5)) == Approx(0.75));
  CHECK(g.along(geo::to_point(2, 0), geo::to_point(3, 0), 10));
  CHECK_FALSE(g.along(geo::to_point(2, 1), geo::to_point(3, 1), 10));
}

TEST_CASE("clip: offsets are exact erosions; simplify keeps corners") {
  geo::Rings sq{test::rect(0, 0, 10, 10)};
  CHECK(area_mm2(offset(sq, -1)) == Approx(64).epsilon(1e-6));
  CHECK(offset(sq, -5.01).empty());
  CHECK(offset_open(geo::Rings{test::rect(0, 0, 10, 0.5)}, 0, 0.3).empty());  // thinner than 0.6: gone
  geo::Ring dense;
  for (int i = 0; i < 100; ++i) dense.push_back(geo::to_point(i * 0.1, 0));
  dense.push_back(geo::to_point(10, 10));
  dense.push_back(geo::to_point(0, 10));
  CHECK(simplify(dense, 1000).size() == 4);
}

TEST_CASE("seams: rear picks the largest y, nearest the closest vertex, aligned prefers corners") {
  geo::Ring r{geo::to_point(0, 0), geo::to_point(10, 0), geo::to_point(10, 10), geo::to_point(5, 11),
              geo::to_point(0, 10)};
  CHECK(choose_seam(r, schema::Seam::Rear, {}) == 3);
  CHECK(choose_seam(r, schema::Seam::Nearest, geo::to_point(9, 1)) == 1);
  // An L-shape's concave corner wins over a slightly more rearward convex one.
  geo::Ring l{geo::to_point(0, 0), geo::to_point(10, 0), geo::to_point(10, 5),
              geo::to_point(5, 5), geo::to_point(5, 6),  geo::to_point(0, 6)};
  CHECK(choose_seam(l, schema::Seam::Aligned, {}) == 3);
  auto open = open_loop_at(r, 2);
  CHECK(open.size() == 6);
  CHECK(open.front() == open.back());
  CHECK(open.front() == r[2]);
}

namespace {
geo::Ring circle_mm(double cx, double cy, double r, int n) {
  geo::Ring c;
  for (int i = 0; i < n; ++i) {
    double a = 2 * std::numbers::pi * i / n;
    c.push_back(geo::to_point(cx + r * std::cos(a), cy + r * std::sin(a)));
  }
  return c;
}
SeamOptions seam_mode(schema::Seam m) {
  SeamOptions o;
  o.mode = m;
  return o;
}
}  // namespace

TEST_CASE("seams: random is the same for the same seed and spread along the loop for others") {
  const geo::Ring c = circle_mm(0, 0, 10, 100);
  SeamOptions o = seam_mode(schema::Seam::Random);
  o.seed = seam_seed(7, 2, 1);
  const size_t first = choose_seam(c, o, {});
  CHECK(choose_seam(c, o, geo::to_point(50, 50)) == first);  // the nozzle does not matter
  CHECK(seam_seed(7, 2, 1) == o.seed);
  CHECK(seam_seed(8, 2, 1) != o.seed);
  CHECK(seam_seed(7, 3, 1) != o.seed);
  CHECK(seam_seed(7, 2, 0) != o.seed);
  // Over 400 layers the seams of one loop land all round it: each quarter gets 15% to 35%.
  std::set<size_t> seen;
  int quarter[4] = {0, 0, 0, 0};
  for (int layer = 0; layer < 400; ++layer) {
    o.seed = seam_seed(layer, 0, 0);
    size_t s = choose_seam(c, o, {});
    REQUIRE(s < c.size());
    seen.insert(s);
    ++quarter[s / 25];
  }
  CHECK(seen.size() > 80);
  for (int q : quarter) CHECK((q > 60 && q < 140));
  // Along the length, not by vertex: a square with one side cut into 100 vertices is not
  // favoured there (its share of seams follows its quarter of the length).
  geo::Ring sq;
  for (int i = 0; i < 100; ++i) sq.push_back(geo::to_point(i * 0.1, 0));
  sq.push_back(geo::to_point(10, 0));
  sq.push_back(geo::to_point(10, 10));
  sq.push_back(geo::to_point(0, 10));
  int bottom = 0;
  for (int layer = 0; layer < 400; ++layer) {
    o.seed = seam_seed(layer, 0, 0);
    const size_t v = choose_seam(sq, o, {});
    if (v >= 1 && v < 100) ++bottom;  // inside the bottom edge (vertex 0 also takes the left edge's end)
  }
  CHECK((bottom > 60 && bottom < 140));
}

TEST_CASE("seams: sharpest_corner hides in the concave corner wherever it is, falls back to aligned on a circle") {
  // A square with a notch in its front edge: aligned goes to the rear, sharpest_corner into the
  // notch's corners (equal: the rearmost, then leftmost).
  geo::Ring notch{geo::to_point(0, 0),  geo::to_point(4, 0),  geo::to_point(4, 3),   geo::to_point(6, 3),
                  geo::to_point(6, 0),  geo::to_point(10, 0), geo::to_point(10, 10), geo::to_point(0, 10)};
  CHECK(notch[choose_seam(notch, schema::Seam::Aligned, {})].Y == geo::to_point(0, 10).Y);
  CHECK(choose_seam(notch, seam_mode(schema::Seam::SharpestCorner), {}) == 2);
  // A concave right angle beats a sharper convex corner (convex ones count half).
  geo::Ring spike{geo::to_point(0, 0), geo::to_point(10, 0), geo::to_point(10, 5), geo::to_point(5, 5),
                  geo::to_point(5, 6), geo::to_point(0, 30)};
  CHECK(choose_seam(spike, seam_mode(schema::Seam::SharpestCorner), {}) == 3);
  // No concave corner: the sharpest convex one, the rear one among equals.
  geo::Ring sq{geo::to_point(0, 0), geo::to_point(10, 0), geo::to_point(10, 10), geo::to_point(0, 10)};
  CHECK(choose_seam(sq, seam_mode(schema::Seam::SharpestCorner), {}) == 3);
  geo::Ring tri{geo::to_point(0, 0), geo::to_point(20, 0), geo::to_point(0, 3)};
  CHECK(choose_seam(tri, seam_mode(schema::Seam::SharpestCorner), {}) == 1);
  // A corner rounded by many short edges counts as one corner: the seam lands inside it.
  geo::Ring rounded{geo::to_point(0, 0), geo::to_point(30, 0), geo::to_point(30, 10)};
  for (int i = 0; i <= 8; ++i) {  // a 90° fillet of radius 0.2 mm at (10, 10), concave
    double a = std::numbers::pi / 2 * i / 8;
    rounded.push_back(geo::to_point(10.2 - 0.2 * std::sin(a), 10.2 - 0.2 * std::cos(a)));
  }
  rounded.push_back(geo::to_point(10, 20));
  rounded.push_back(geo::to_point(0, 20));
  const size_t r = choose_seam(rounded, seam_mode(schema::Seam::SharpestCorner), {});
  CHECK(r >= 3);
  CHECK(r <= 11);
  // A circle turns by a few degrees per half millimetre: aligned's seam.
  const geo::Ring c = circle_mm(5, 5, 10, 200);
  CHECK(choose_seam(c, seam_mode(schema::Seam::SharpestCorner), {}) == choose_seam(c, schema::Seam::Aligned, {}));
}

TEST_CASE("seams: point starts at the vertex nearest the point, wherever the nozzle is") {
  geo::Ring sq{geo::to_point(0, 0), geo::to_point(10, 0), geo::to_point(10, 10), geo::to_point(0, 10)};
  SeamOptions o = seam_mode(schema::Seam::Point);
  o.toward = geo::to_point(11, -1);
  CHECK(choose_seam(sq, o, geo::to_point(0, 10)) == 1);
  o.toward = geo::to_point(-50, 6);
  CHECK(choose_seam(sq, o, geo::to_point(10, 0)) == 3);
  const geo::Ring c = circle_mm(0, 0, 10, 100);
  o.toward = geo::to_point(0, -40);
  CHECK(choose_seam(c, o, {}) == 75);
}

TEST_CASE("chain: nearest end first, reversing paths when their far end is closer") {
  geo::Ring a{geo::to_point(0, 0), geo::to_point(10, 0)};
  geo::Ring b{geo::to_point(20, 0), geo::to_point(11, 0)};
  auto order = chain_open({&b, &a}, geo::to_point(-1, 0));
  REQUIRE(order.size() == 2);
  CHECK(order[0].index == 1);
  CHECK_FALSE(order[0].reversed);
  CHECK(order[1].index == 0);
  CHECK(order[1].reversed);
}

TEST_CASE("chain: the best greedy order leaves no small path stranded across the part") {
  // A long zig-zag starts right at the nozzle, a short one a little aside: nearest first does
  // the long one and then crosses back 100 mm for the short one; the short one first costs one
  // short hop and a travel back to the long one's start.
  geo::Ring big{geo::to_point(1, 0), geo::to_point(100, 0)};
  geo::Ring small{geo::to_point(-5, 5), geo::to_point(-5, 10)};
  StepCost cost = [](size_t, const geo::Point& a, size_t, const geo::Point& b) {
    return std::sqrt(dist2(a, b)) * geo::kMmPerUnit + 10;
  };
  auto greedy = chain_open({&big, &small}, geo::to_point(0, 0));
  REQUIRE(greedy.size() == 2);
  CHECK(greedy[0].index == 0);
  auto best = chain_open_best({&big, &small}, geo::to_point(0, 0), cost);
  REQUIRE(best.size() == 2);
  CHECK(best[0].index == 1);
  CHECK(best[1].index == 0);
  CHECK_FALSE(best[1].reversed);
  // Beyond max_tries paths it is the plain greedy order.
  auto capped = chain_open_best({&big, &small}, geo::to_point(0, 0), cost, 1);
  CHECK(capped[0].index == 0);
}

TEST_CASE("motion: trapezoid times") {
  // 100 mm at 50 mm/s from and to rest, 1000 mm/s²: 2 s cruise + 0.05 s extra for the ramps.
  CHECK(trapezoid_time(100, 50, 0, 0, 1000) == Approx(2.05));
  // Too short to reach cruise speed: a triangle.
  CHECK(trapezoid_time(1, 100, 0, 0, 1000) == Approx(2 * std::sqrt(1.0 / 1000)));
  MotionClock c;
  c.start_at(geo::to_point(0, 0));
  c.move(geo::to_point(50, 0), 50, true);
  c.move(geo::to_point(100, 0), 50, true);  // straight on: no slowdown at the junction
  CHECK(c.finish() == Approx(2.05));
}

namespace {
// A blob whose radius wanders smoothly (finely tessellated, as outlines sliced from curved
// meshes are), centred at (cx, cy); clockwise for a hole.
geo::Ring blob(double cx, double cy, double r, double wobble, int lobes, double phase, int n, bool ccw = true) {
  geo::Ring out;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * (ccw ? i : n - i) / n;
    const double rr = r * (1 + wobble * std::sin(lobes * t + phase));
    out.emplace_back(geo::to_units(cx + rr * std::cos(t)), geo::to_units(cy + rr * std::sin(t)));
  }
  return out;
}

// Clipper's own offset with round joins, as toolpath::offset computed it before its own joins.
geo::Rings clipper_offset(const geo::Rings& region, double mm, double arc_tolerance) {
  geo::Rings out;
  ClipperLib::ClipperOffset co(2.0, arc_tolerance);
  co.AddPaths(region, ClipperLib::jtRound, ClipperLib::etClosedPolygon);
  co.Execute(out, mm * geo::kUnitsPerMm);
  return out;
}
}  // namespace

TEST_CASE("clip: offsets agree with Clipper's on curved, thin and holed shapes") {
  // The crossing points offset() takes instead of Clipper's detours must not change the region:
  // what differs is arcs within the tolerance, so the difference opened by 20 µm is empty. Shapes
  // from wide blobs to walls and necks thinner than twice the offset (where a careless join leaves
  // spurious loops), every offset both ways.
  test::Lcg rnd{12345};
  int compared = 0;
  for (int shape = 0; shape < 40; ++shape) {
    geo::Rings region;
    const double r = 0.3 + 8 * rnd();
    const int n = 16 + static_cast<int>(400 * rnd());
    region.push_back(blob(0, 0, r, 0.3 * rnd(), 1 + static_cast<int>(6 * rnd()), 6 * rnd(), n));
    if (shape % 3 == 1)  // a wall round a hole, down to 0.2 mm thin
      region.push_back(blob(0.05 * rnd(), 0, r * (0.6 + 0.35 * rnd()) - 0.1, 0.05, 3, 0, n / 2 + 8, false));
    if (shape % 3 == 2)  // a second blob joined by a neck (union below)
      region.push_back(blob(1.6 * r, 0.2 * r * rnd(), 0.8 * r, 0.2 * rnd(), 4, 0, n));
    region = toolpath::union_of(region);
    for (double mm : {0.05, 0.2, 0.45, 1.0, 3.0}) {
      for (double d : {mm, -mm}) {
        const geo::Rings ours = toolpath::offset(region, d);
        const geo::Rings theirs = clipper_offset(region, d, 5000);
        geo::Rings diff = toolpath::union_of(toolpath::difference(ours, theirs), toolpath::difference(theirs, ours));
        const geo::Rings opened = toolpath::offset_open(diff, -0.02, 0.02);
        INFO("shape " << shape << " r " << r << " n " << n << " offset " << d << " mm: " << area_mm2(ours)
                      << " mm² against " << area_mm2(theirs));
        CHECK(area_mm2(opened) < 1e-6);
        CHECK(std::abs(area_mm2(ours) - area_mm2(theirs)) <= 0.002 * std::max(1.0, area_mm2(theirs)));
        ++compared;
      }
    }
  }
  CHECK(compared == 400);
}

TEST_CASE("clip: offsets agree with Clipper's on polygons with corners: stars, combs, frames, random ones") {
  // offset() gives most curves back as built (trimmed where moved edges cross, no union): sharp
  // and right-angled corners, short edges between long ones, teeth narrower than the offset,
  // holes that grow into their outer, random self-touching polygons united first.
  test::Lcg rnd{777};
  auto pt = [](double x, double y) { return geo::Point(geo::to_units(x), geo::to_units(y)); };
  std::vector<geo::Rings> shapes;
  for (int k = 0; k < 12; ++k) {  // stars: 5..16 points, sharp to blunt
    const int m = 5 + k;
    const double r0 = 2 + 6 * rnd(), r1 = r0 * (0.2 + 0.6 * rnd());
    geo::Ring star;
    for (int i = 0; i < 2 * m; ++i) {
      const double t = std::numbers::pi * i / m, rr = i % 2 ? r1 : r0;
      star.push_back(pt(rr * std::cos(t), rr * std::sin(t)));
    }
    shapes.push_back({star});
  }
  for (int k = 0; k < 6; ++k) {  // combs: teeth 0.3..2 mm wide, gaps as narrow
    const double w = 0.3 + 1.7 * rnd(), g = 0.2 + 1.5 * rnd();
    geo::Ring comb{pt(0, 0)};
    double x = 0;
    for (int i = 0; i < 8; ++i) {
      comb.push_back(pt(x, 10));
      comb.push_back(pt(x + w, 10));
      comb.push_back(pt(x + w, 2));
      comb.push_back(pt(x + w + g, 2));
      x += w + g;
    }
    comb.push_back(pt(x, 10));
    comb.push_back(pt(x + w, 10));
    comb.push_back(pt(x + w, 0));
    shapes.push_back({comb});
  }
  for (int k = 0; k < 6; ++k) {  // square frames 0.3..3 mm thick, a short edge cut at one corner
    const double t = 0.3 + 2.7 * rnd(), c = 0.001 + 0.05 * rnd();
    geo::Ring outer{pt(0, 0), pt(20, 0), pt(20, 20 - c), pt(20 - c, 20), pt(0, 20)};
    geo::Ring hole{pt(t, t), pt(t, 20 - t), pt(20 - t, 20 - t), pt(20 - t, t)};
    shapes.push_back({outer, hole});
  }
  for (int k = 0; k < 16; ++k) {  // random polygons, united (self-crossings become rings)
    geo::Ring r;
    const int m = 5 + static_cast<int>(20 * rnd());
    for (int i = 0; i < m; ++i) r.push_back(pt(20 * rnd(), 20 * rnd()));
    shapes.push_back(toolpath::union_of(geo::Rings{r}));
  }
  int compared = 0;
  for (size_t k = 0; k < shapes.size(); ++k) {
    for (double mm : {0.02, 0.2, 0.45, 1.0, 2.5}) {
      for (double d : {mm, -mm}) {
        const geo::Rings ours = toolpath::offset(shapes[k], d);
        const geo::Rings theirs = clipper_offset(shapes[k], d, 5000);
        geo::Rings diff = toolpath::union_of(toolpath::difference(ours, theirs), toolpath::difference(theirs, ours));
        const geo::Rings opened = clipper_offset(clipper_offset(diff, -0.02, 5000), 0.02, 5000);
        INFO("shape " << k << " offset " << d << " mm: " << area_mm2(ours) << " mm² against " << area_mm2(theirs));
        CHECK(area_mm2(opened) < 1e-6);
        CHECK(std::abs(area_mm2(ours) - area_mm2(theirs)) <= 0.002 * std::max(1.0, area_mm2(theirs)));
        for (const auto& r : ours) CHECK(r.size() >= 3);
        ++compared;
      }
    }
  }
  CHECK(compared == 400);
}

TEST_CASE("clip: growing a region whose border zig-zags by noise agrees with Clipper's, and a hairline still grows") {
  // Where two nearly equal borders cross (a fill and a shrunk neighbour), a boolean leaves a run
  // of vertices a micrometre or two apart turning back and forth by a fraction of one: offset()
  // drops those within 0.5 µm of their chord before growing. The region grown must not change.
  geo::Ring ring{geo::to_point(20, 0), geo::to_point(20, 5)};
  for (int i = 0; i <= 10000; ++i)  // the top: 20 mm in 2 µm steps, ±0.3 µm of noise
    ring.push_back(geo::Point(geo::to_units(20 - 0.002 * i), geo::to_units(5) + (i % 2 ? 300 : -300)));
  ring.push_back(geo::to_point(0, 0));
  const geo::Rings region{ring};
  REQUIRE(area_mm2(region) == Approx(100).epsilon(1e-4));
  for (double d : {0.1125, 0.5625, 2.0}) {
    INFO("grown by " << d << " mm");
    const geo::Rings ours = toolpath::offset(region, d);
    const geo::Rings theirs = clipper_offset(region, d, 5000);
    // Apart from the arcs (within 5 µm) and the noise (0.3 µm): the same region. Its area is the
    // rectangle's grown with round corners (ClipperOffset's is up to 4 µm short along the noisy
    // top: its arcs at every noisy vertex cut in).
    // The arcs' chords cut in by at most the 5 µm tolerance along their length, the noise 0.3 µm
    // along the top.
    const double exact = 100 + 2 * d * 25 + std::numbers::pi * d * d;
    CHECK(std::abs(area_mm2(ours) - exact) <= 2 * std::numbers::pi * d * 0.005 + 20 * 0.0003);
    CHECK(area_mm2(toolpath::difference(ours, toolpath::offset(theirs, 0.006))) < 1e-6);
    CHECK(area_mm2(toolpath::difference(theirs, toolpath::offset(ours, 0.006))) < 1e-6);
  }
  // A hairline 0.2 µm wide and 1 mm long is narrower than the tolerance: it still grows into a
  // stadium (1 mm by 0.4 mm with round ends).
  const geo::Rings hair{{geo::to_point(0, 0), geo::to_point(0.5, 0), geo::Point(geo::to_units(1), 0),
                         geo::Point(geo::to_units(1), 200), geo::Point(geo::to_units(0.5), 200), geo::Point(0, 200)}};
  CHECK(area_mm2(toolpath::offset(hair, 0.2)) == Approx(0.4 + std::numbers::pi * 0.04).epsilon(0.01));
}

TEST_CASE("clip: a finely tessellated curve offset where it opens keeps one vertex per vertex, within 1 µm of the arc") {
  // A disc of 2000 vertices grown by 0.5 mm, and a hole of 2000 in a plate shrunk by 0.5 mm (the
  // hole widens): each turn of 0.18° is one mitre point (0.6 nm outside the arc), not two points
  // 1.6 µm apart, so the radius stays exact and later booleans carry half the vertices.
  const int n = 2000;
  auto circle = [&](double r, bool ccw) {
    geo::Ring ring;
    for (int i = 0; i < n; ++i) {
      const double t = 2 * std::numbers::pi * (ccw ? i : n - i) / n;
      ring.emplace_back(geo::to_units(r * std::cos(t)), geo::to_units(r * std::sin(t)));
    }
    return ring;
  };
  auto radii = [](const geo::Ring& ring, double& lo, double& hi) {
    lo = 1e9, hi = 0;
    for (const auto& q : ring) {
      const double r = std::hypot(double(q.X), double(q.Y)) * geo::kMmPerUnit;
      lo = std::min(lo, r), hi = std::max(hi, r);
    }
  };
  const geo::Rings grown = toolpath::offset(geo::Rings{circle(10, true)}, 0.5);
  REQUIRE(grown.size() == 1);
  CHECK(grown[0].size() <= static_cast<size_t>(n));
  double lo = 0, hi = 0;
  radii(grown[0], lo, hi);
  // The polygon's own vertices lie on r = 10; its edges 12 µm inside (cos(π/n)).
  CHECK(lo >= 10.5 - 0.0001);
  CHECK(hi <= 10.5 + 0.001);
  const geo::Rings plate{test::rect(-20, -20, 20, 20), circle(5, false)};
  const geo::Rings shrunk = toolpath::offset(plate, -0.5);
  REQUIRE(shrunk.size() == 2);
  const geo::Ring& hole = shrunk[0].size() > 4 ? shrunk[0] : shrunk[1];
  CHECK(hole.size() <= static_cast<size_t>(n));
  radii(hole, lo, hi);
  CHECK(lo >= 5.5 - 0.0001);
  CHECK(hi <= 5.5 + 0.001);
}

TEST_CASE("edge grid: inside and inside_fraction agree with a plain even-odd count everywhere, empty cells too") {
  // Blobs with holes: most grid cells hold no edge (answered from the cell), the rest are cast.
  test::Lcg rnd{777};
  auto even_odd = [](const geo::Rings& rings, double x, double y) {
    bool in = false;
    for (const auto& r : rings)
      for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
        const double xi = double(r[i].X), yi = double(r[i].Y), xj = double(r[j].X), yj = double(r[j].Y);
        if ((yi > y) != (yj > y) && x < xi + (y - yi) * (xj - xi) / (yj - yi)) in = !in;
      }
    return in;
  };
  for (int shape = 0; shape < 12; ++shape) {
    const double r = 2 + 20 * rnd();
    geo::Rings rings{blob(0, 0, r, 0.3 * rnd(), 2 + shape % 5, 6 * rnd(), 20 + static_cast<int>(300 * rnd()))};
    if (shape % 2) rings.push_back(blob(0.1 * r, 0, 0.4 * r, 0.1, 3, 1, 40, false));
    const EdgeGrid g(rings);
    int checked = 0;
    for (int k = 0; k < 2000; ++k) {
      // Points off the integer grid by half a unit: never on an edge.
      const double x = (rnd() * 2.6 - 1.3) * r, y = (rnd() * 2.6 - 1.3) * r;
      const geo::Point p(std::llround(x * geo::kUnitsPerMm), std::llround(y * geo::kUnitsPerMm));
      const bool expect = even_odd(rings, double(p.X) + 0.5, double(p.Y) + 0.5);
      if (g.inside(p) != expect) {
        // Only a point within a unit of an edge may differ (on it, either answer is right).
        CHECK(g.crosses(geo::Point(p.X - 1, p.Y - 1), geo::Point(p.X + 1, p.Y + 1)));
        continue;
      }
      ++checked;
      // A bead's width across from p: its inside fraction against 41 samples along it.
      const geo::Point q(p.X + std::llround(0.45 * geo::kUnitsPerMm * std::cos(k)),
                         p.Y + std::llround(0.45 * geo::kUnitsPerMm * std::sin(k)));
      int in = 0;
      for (int s = 0; s <= 40; ++s)
        in += even_odd(rings, double(p.X) + (double(q.X) - double(p.X)) * s / 40.0 + 0.5,
                       double(p.Y) + (double(q.Y) - double(p.Y)) * s / 40.0 + 0.5);
      CHECK(g.inside_fraction(p, q) == Approx(in / 41.0).epsilon(0.05).scale(1.0));
    }
    CHECK(checked > 1900);
    // box_state: a box said wholly inside (outside) has every sampled point inside (outside).
    int decided = 0;
    for (int k = 0; k < 300; ++k) {
      const double x = (rnd() * 2.4 - 1.2) * r, y = (rnd() * 2.4 - 1.2) * r, w = 0.2 + 2 * rnd();
      const geo::coord_t x0 = std::llround(x * geo::kUnitsPerMm), y0 = std::llround(y * geo::kUnitsPerMm);
      const geo::coord_t x1 = x0 + std::llround(w * geo::kUnitsPerMm), y1 = y0 + std::llround(w * geo::kUnitsPerMm);
      const int s = g.box_state(x0, y0, x1, y1);
      if (s < 0) continue;
      ++decided;
      for (int i = 0; i <= 6; ++i)
        for (int j = 0; j <= 6; ++j)
          CHECK(even_odd(rings, double(x0) + double(x1 - x0) * i / 6.0 + 0.5, double(y0) + double(y1 - y0) * j / 6.0 + 0.5) ==
                (s == 1));
    }
    CHECK(decided > 20);
  }
}

TEST_CASE("clip: rings listed clockwise (outers) are offset as Clipper offsets them, by zero too") {
  // A square with a hole, both rings reversed: the region is the same, read the other way round.
  geo::Rings cw{test::rect(0, 0, 10, 10, false), test::rect(3, 3, 7, 7, true)};
  for (double d : {0.0, 0.5, -0.5}) {
    INFO("offset " << d);
    const geo::Rings ours = toolpath::offset(cw, d), theirs = clipper_offset(cw, d, 5000);
    CHECK(area_mm2(ours) == Approx(area_mm2(theirs)).epsilon(1e-4));
    CHECK(area_mm2(ours) > 0);  // outers counter-clockwise in the result
  }
  CHECK(area_mm2(toolpath::offset(cw, 0)) == Approx(100 - 16).epsilon(1e-9));
}

// With many paths, chain_open_best's greedy order looks at the nearest ends first (a grid of
// their ends, `lower` bounding the cost by the step's length): the same order as trying every
// path at every step. 300 short paths scattered over 100 mm, joined for free when 1 mm apart
// or less, else a travel: the cost of emit_fills.
TEST_CASE("chain: the greedy order over a grid of ends is the one from trying every end") {
  std::vector<geo::Ring> rings;
  uint64_t seed = 12345;
  auto rnd = [&] {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(seed >> 11) / 9007199254740992.0;
  };
  for (int i = 0; i < 300; ++i) {
    const double x = 100 * rnd(), y = 100 * rnd(), a = 6.3 * rnd(), l = 0.2 + 3 * rnd();
    rings.push_back({geo::to_point(x, y), geo::to_point(x + l * std::cos(a), y + l * std::sin(a))});
  }
  // A few paths share an end (equal costs: the lowest index wins either way).
  rings[7][0] = rings[3][1];
  rings[200][1] = rings[100][0];
  std::vector<const geo::Ring*> paths;
  for (const auto& r : rings) paths.push_back(&r);
  StepCost cost = [](size_t i, const geo::Point& a, size_t, const geo::Point& b) {
    const double d = std::sqrt(dist2(a, b)) * geo::kMmPerUnit;
    return i != kStart && d <= 1 ? 0.0 : d + 10;
  };
  LowerCost lower = [](double d) { return d > 1 ? d + 10 : 0.0; };
  const auto plain = chain_open_best(paths, geo::to_point(50, 50), cost, 48);
  for (double cell : {0.5, 2.0, 10.0}) {
    CAPTURE(cell);
    const auto fast = chain_open_best(paths, geo::to_point(50, 50), cost, 48, {}, lower, cell);
    REQUIRE(fast.size() == plain.size());
    for (size_t k = 0; k < plain.size(); ++k) {
      CAPTURE(k);
      CHECK(fast[k].index == plain[k].index);
      CHECK(fast[k].reversed == plain[k].reversed);
    }
  }
  CHECK(plain.size() == 300);
}

TEST_CASE("clip: is_clean_region says when a region is already its own union") {
  const geo::Ring sq = test::rect(0, 0, 10, 10), hole = test::rect(3, 3, 6, 6, false);
  CHECK(is_clean_region({}));
  CHECK(is_clean_region({sq}));
  CHECK(is_clean_region({sq, hole}));
  CHECK(is_clean_region({sq, hole, test::rect(4, 4, 5, 5)}));  // an island in the hole
  CHECK(is_clean_region({sq, test::rect(20, 0, 30, 10)}));     // side by side
  CHECK(is_clean_region(offset({sq, hole}, -1)));
  CHECK_FALSE(is_clean_region({sq, test::rect(5, 5, 15, 15)}));          // overlapping outers
  CHECK_FALSE(is_clean_region({sq, test::rect(2, 2, 4, 4)}));            // an outer inside an outer
  CHECK_FALSE(is_clean_region({sq, test::rect(3, 3, 6, 6, true)}));      // the hole counter-clockwise
  CHECK_FALSE(is_clean_region({test::rect(3, 3, 6, 6, false)}));         // a hole alone
  CHECK_FALSE(is_clean_region({sq, test::rect(8, 3, 12, 6, false)}));    // a hole crossing its outer
  CHECK_FALSE(is_clean_region({sq, test::rect(0, 0, 10, 10)}));           // the same ring twice
  geo::Ring dup = sq;
  dup.insert(dup.begin() + 1, dup[1]);
  CHECK_FALSE(is_clean_region({dup}));  // a repeated vertex
  geo::Ring bow{geo::to_point(0, 0), geo::to_point(10, 10), geo::to_point(10, 0), geo::to_point(0, 10)};
  CHECK_FALSE(is_clean_region({bow}));  // a bow tie
  // Where it says so, the union gives the same region.
  for (const geo::Rings& r : {geo::Rings{sq, hole}, offset({sq, hole}, -1), geo::Rings{sq, test::rect(20, 0, 30, 10)}}) {
    REQUIRE(is_clean_region(r));
    CHECK(area_mm2(r) == Approx(area_mm2(union_of(r))));
    CHECK(area_mm2(difference(r, union_of(r))) < 1e-9);
    CHECK(area_mm2(difference(union_of(r), r)) < 1e-9);
  }
}

TEST_CASE("clip: buffer_loops is the area within a distance of each loop, as Clipper's line offset makes it") {
  // Loops from round to wavy, clockwise ones (the walls round holes) and loops with necks
  // narrower than twice the distance (where the inner side vanishes in part); the band's
  // non-zero union against ClipperOffset's closed lines, which differ by arcs within tolerance.
  test::Lcg rnd{777};
  int compared = 0;
  for (int shape = 0; shape < 30; ++shape) {
    const double r = 0.3 + 6 * rnd();
    const int n = 12 + static_cast<int>(300 * rnd());
    geo::Rings loops{blob(0, 0, r, 0.35 * rnd(), 1 + static_cast<int>(6 * rnd()), 6 * rnd(), n, shape % 2 == 0)};
    if (shape % 5 == 4) loops.push_back(blob(0.3 * r, 0, 0.4 * r, 0.1, 3, 0, n / 2 + 8, false));  // a second loop inside
    for (double mm : {0.05, 0.2, 0.45, 1.5}) {
      ClipperLib::ClipperOffset co(2.0, 5000);
      co.AddPaths(loops, ClipperLib::jtRound, ClipperLib::etClosedLine);
      geo::Rings theirs;
      co.Execute(theirs, mm * geo::kUnitsPerMm);
      const geo::Rings mine = toolpath::buffer_loops(loops, mm);
      const geo::Rings ours = toolpath::union_of(mine);
      geo::Rings diff = toolpath::union_of(toolpath::difference(ours, theirs), toolpath::difference(theirs, ours));
      INFO("shape " << shape << " r " << r << " n " << n << " distance " << mm << " mm: " << area_mm2(ours)
                    << " mm² against " << area_mm2(theirs));
      CHECK(area_mm2(toolpath::offset_open(diff, -0.02, 0.02)) < 1e-6);
      CHECK(std::abs(area_mm2(ours) - area_mm2(theirs)) <= 0.002 * std::max(1.0, area_mm2(theirs)));
      // The rings' signed areas add up to the band's (one loop: no two bands overlap).
      if (loops.size() == 1) CHECK(area_mm2(mine) == Approx(area_mm2(ours)).epsilon(1e-6));
      ++compared;
    }
  }
  CHECK(compared == 120);
  // A line or a point (no area) still gets its capsule or disc.
  const geo::Ring line{geo::to_point(0, 0), geo::to_point(5, 0), geo::to_point(10, 0)};
  CHECK(area_mm2(toolpath::union_of(toolpath::buffer_loops({line}, 0.5))) ==
        Approx(2 * 10 * 0.5 + M_PI * 0.25).epsilon(1e-3));
  // A loop going out 1 mm along a spike and back: the bead does, so its band has the spike's
  // stadium (offsets leave a spike of no width out of a region; the band is not a region's).
  const geo::Ring spiked{geo::to_point(0, 0),  geo::to_point(10, 0), geo::to_point(10, 5), geo::to_point(11, 5),
                         geo::to_point(10, 5), geo::to_point(10, 10), geo::to_point(0, 10)};
  const double square_band = 10.5 * 10.5 - 9.5 * 9.5 - 4 * (1 - M_PI / 4) * 0.25 * 0.25;
  CHECK(area_mm2(toolpath::union_of(toolpath::buffer_loops({spiked}, 0.25))) ==
        Approx(square_band + 0.75 * 0.5 + M_PI * 0.25 * 0.25 / 2).epsilon(1e-3));
}


namespace {
// offset() against ClipperOffset's round offset: the difference opened by 20 µm is empty and the
// areas agree within 0.2%; returns whether ours skipped the union.
bool offset_like_clipper(const geo::Rings& region, double d) {
  bool as_built = false;
  const geo::Rings ours = toolpath::offset(region, d, as_built);
  const geo::Rings theirs = clipper_offset(region, d, 5000);
  geo::Rings diff =
      toolpath::union_of(toolpath::difference(ours, theirs), toolpath::difference(theirs, ours));
  INFO("offset " << d << " mm: " << area_mm2(ours) << " mm² in " << ours.size() << " rings against "
                 << area_mm2(theirs) << " in " << theirs.size() << (as_built ? " (as built)" : " (united)"));
  CHECK(area_mm2(toolpath::offset_open(diff, -0.02, 0.02)) < 1e-6);
  CHECK(std::abs(area_mm2(ours) - area_mm2(theirs)) <= 0.002 * std::max(1.0, area_mm2(theirs)));
  CHECK(ours.size() == theirs.size());
  return as_built;
}
}  // namespace

TEST_CASE("clip: round joins are trimmed where a neighbouring moved edge crosses them, with no union") {
  auto pt = [](double x, double y) { return geo::Point(geo::to_units(x), geo::to_units(y)); };
  // A spike 0.1 mm high on a plate's top edge, grown by 0.45 mm: its sides lie wholly behind the
  // plate's moved edge, which cuts the arc round its apex on both sides (the top of the arc stays).
  // The trimmed curve used to give up on the side starting at the arc, for the union.
  const geo::Rings spike{
      {pt(0, 0), pt(20, 0), pt(20, 10), pt(10.1, 10), pt(10, 10.1), pt(9.9, 10), pt(0, 10)}};
  CHECK(offset_like_clipper(spike, 0.45));
  CHECK(offset_like_clipper(spike, 1.0));
  CHECK(offset_like_clipper(spike, -0.45));
  const geo::Rings grown = toolpath::offset(spike, 0.45);
  REQUIRE(grown.size() == 1);
  geo::BBox2 b = toolpath::bbox(grown);
  CHECK(b.max_y >= geo::to_units(10.55 - 0.006));  // the top of the apex's arc (chords within 5 µm)
  CHECK(b.max_y <= geo::to_units(10.55 + 0.001));
  // An L's concave corner holding a small spike (apex 0.21 mm from the corner, its sides 0.16 mm):
  // grown by 1 mm, the arc round the apex lies wholly inside the moved edges' crossing and is
  // dropped with both sides; by 0.45 mm it is cut on both sides; shrunk, the corner's arcs meet
  // the spike's short edges, which the moved edges of the other side of the spike cross.
  const geo::Rings ell{
      {pt(-10, -10), pt(10, -10), pt(10, 0), pt(0.2, 0), pt(0.15, 0.15), pt(0, 0.2), pt(0, 10), pt(-10, 10)}};
  for (double d : {0.05, 0.2, 0.45, 1.0, 2.5, -0.05, -0.2, -0.45, -1.0}) {
    INFO("L grown by " << d);
    CHECK(offset_like_clipper(ell, d));
  }
  const geo::Rings ell_grown = toolpath::offset(ell, 1.0);
  REQUIRE(ell_grown.size() == 1);
  // Grown by 1 mm, the corner is the point where the moved edges cross, (1, 1).
  bool corner = false;
  for (const auto& q : ell_grown[0]) corner = corner || (q == pt(1, 1));
  CHECK(corner);
}

TEST_CASE("clip: staircases and notched discs offset both ways agree with Clipper's, most with no union") {
  // Stairs of steps 10 µm to 0.5 mm (every convex corner's arc next to a short edge and a concave
  // corner, cut by the next step's moved edge when the offset exceeds the step), and discs with
  // notches shrunk past their radius (nothing left: no spurious loop).
  uint32_t seed = 4242;
  auto rnd = [&] {
    seed = seed * 1664525u + 1013904223u;
    return (seed >> 8) / double(1 << 24);
  };
  auto pt = [](double x, double y) { return geo::Point(geo::to_units(x), geo::to_units(y)); };
  int compared = 0, as_built = 0;
  for (int k = 0; k < 24; ++k) {
    geo::Ring stairs{pt(0, 0), pt(12, 0)};
    double x = 12, y = 0;
    const double step = 0.01 + 0.49 * rnd();
    while (x > 0.5) {
      y += step * (0.3 + 1.4 * rnd());
      stairs.push_back(pt(x, y));
      x -= step * (0.3 + 1.4 * rnd());
      stairs.push_back(pt(x, y));
    }
    stairs.push_back(pt(0, y));
    for (double mm : {0.02, 0.2, 0.45, 1.0}) {
      for (double d : {mm, -mm}) {
        INFO("stairs " << k << " of " << step << " mm steps, offset " << d);
        as_built += offset_like_clipper({stairs}, d);
        ++compared;
      }
    }
  }
  CHECK(compared == 192);
  // 146 of the 192 with no union (42 when a segment starting at a round join could not be consumed).
  CHECK(as_built >= 140);
  for (int k = 0; k < 8; ++k) {
    const double r = 0.5 + 2 * rnd();
    geo::Ring disc;
    for (int i = 0; i < 64; ++i) {
      const double t = 2 * std::numbers::pi * i / 64;
      const double rr = r * (i % 16 == 0 ? 0.8 + 0.15 * rnd() : 1.0);  // four notches
      disc.push_back(pt(rr * std::cos(t), rr * std::sin(t)));
    }
    for (double f : {0.3, 0.7, 0.95, 1.05, 1.5}) {
      INFO("disc " << k << " of radius " << r << " shrunk by " << f * r);
      offset_like_clipper({disc}, -f * r);
      if (f > 1) CHECK(toolpath::offset({disc}, -f * r).empty());
      offset_like_clipper({disc}, f * r);
    }
  }
}
