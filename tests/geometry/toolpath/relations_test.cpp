#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <thread>

#include "fixtures.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/relations.h"

using namespace tranche;
using namespace tranche::toolpath;
using doctest::Approx;
using schema::PathKind;

namespace {
double area_of(const std::vector<FillRegion>& regions, PathKind k) {
  double a = 0;
  for (const auto& r : regions)
    if (r.kind == k) a += area_mm2(r.rings);
  return a;
}
}  // namespace

TEST_CASE("relations: top, bottom and sparse regions of a solid block") {
  geo::Polygon sq{test::rect(0, 0, 20, 20), {}};
  auto layers = test::stack(20, 0.2, sq);
  geo::Rings fill{test::rect(2, 2, 18, 18)};
  SolidSpec spec;
  {  // layer 0: all bottom
    Neighbours nb(layers, 0);
    auto r = split_fill(fill, nb, spec);
    REQUIRE(r.size() == 1);
    CHECK(r[0].kind == PathKind::BottomSolid);
  }
  {  // layer 2: within bottom_layers of the bed: solid, nothing exposed
    Neighbours nb(layers, 2);
    auto r = split_fill(fill, nb, spec);
    CHECK(area_of(r, PathKind::SolidInfill) == Approx(256).epsilon(1e-3));
    CHECK(area_of(r, PathKind::Infill) == 0);
  }
  {  // layer 10: deep inside: sparse only
    Neighbours nb(layers, 10);
    auto r = split_fill(fill, nb, spec);
    REQUIRE(r.size() == 1);
    CHECK(r[0].kind == PathKind::Infill);
    CHECK(nb.covers(1, fill, EdgeGrid(fill)));
  }
  {  // last layer: top skin
    Neighbours nb(layers, 19);
    auto r = split_fill(fill, nb, spec);
    CHECK(area_of(r, PathKind::TopSolid) == Approx(256).epsilon(1e-3));
  }
  {  // two below the top: internal solid (covered by the next layer, not by all three)
    Neighbours nb(layers, 17);
    auto r = split_fill(fill, nb, spec);
    CHECK(area_of(r, PathKind::SolidInfill) == Approx(256).epsilon(1e-3));
    CHECK(area_of(r, PathKind::TopSolid) == 0);
  }
  {  // fully solid density: no sparse region anywhere
    SolidSpec full = spec;
    full.density = 1.0;
    Neighbours nb(layers, 10);
    auto r = split_fill(fill, nb, full);
    CHECK(area_of(r, PathKind::Infill) == 0);
    CHECK(area_of(r, PathKind::SolidInfill) == Approx(256).epsilon(1e-3));
  }
}

TEST_CASE("relations: a step gives a bridge over empty space and a top under nothing") {
  // Layers 0-4: 10 × 20; layers 5-9: 20 × 20, overhanging by 10 mm.
  auto layers = test::stack(10, 0.2, geo::Polygon{test::rect(0, 0, 20, 20), {}});
  for (int i = 0; i < 5; ++i)
    layers[static_cast<size_t>(i)].islands[0].shape.outer = test::rect(0, 0, 10, 20);
  geo::Rings fill{test::rect(1, 1, 19, 19)};
  Neighbours nb(layers, 5);
  auto r = split_fill(fill, nb, SolidSpec{});
  CHECK(area_of(r, PathKind::Bridge) == Approx(9 * 18).epsilon(0.02));
  CHECK(area_of(r, PathKind::TopSolid) == 0);
  // Over the lower block the fill stays sparse, save a one-bead anchor beside the bridge.
  CHECK(area_of(r, PathKind::Infill) == Approx((9 - 0.45) * 18).epsilon(0.02));
  CHECK(area_of(r, PathKind::SolidInfill) == Approx(0.45 * 18).epsilon(0.1));
  double total = 0;
  for (const auto& x : r) total += area_mm2(x.rings);
  CHECK(total == Approx(18 * 18).epsilon(1e-3));
  // Layer 4: the part under the step's edge is covered; its own top region is where layer 5
  // does not reach: none (layer 5 is larger).
  Neighbours nb4(layers, 4);
  geo::Rings fill4{test::rect(1, 1, 9, 19)};
  auto r4 = split_fill(fill4, nb4, SolidSpec{});
  CHECK(area_of(r4, PathKind::TopSolid) == 0);
  CHECK(area_of(r4, PathKind::Bridge) == 0);
}

TEST_CASE("relations: fraction of an island supported by the layer below") {
  geo::Rings isl{test::rect(0, 0, 10, 10)};
  geo::Rings below{test::rect(0, 0, 5, 10)};
  CHECK(fraction_on(isl, below) == Approx(0.5));
  CHECK(fraction_on(isl, {}) == 0);
}

TEST_CASE("relations: vertical shell: the fill under a gentle slope's shells is solid, a straight wall's is not") {
  // A pyramid of squares shrinking by 0.3 mm a side per 0.2 mm layer (a 34° slope); layer 10's
  // fill region lies 1 mm inside its square (3 mm from the first layer's side).
  std::vector<geo::Layer> layers = test::stack(30, 0.2, geo::Polygon{test::rect(0, 0, 20, 20), {}});
  for (int i = 0; i < 30; ++i) {
    const double d = 0.3 * i;
    layers[static_cast<size_t>(i)].islands[0].shape.outer = test::rect(d, d, 20 - d, 20 - d);
  }
  geo::Rings fill{test::rect(4, 4, 16, 16)};
  SolidSpec spec;
  Neighbours nb(layers, 10);
  const auto plain = split_fill(fill, nb, spec);
  spec.shell_mm = 0.5;
  const auto shell = split_fill(fill, nb, spec);
  // Without: the next three layers (3.3, 3.6 and 3.9 mm from the side) cover the fill: all
  // sparse. With: the fill within 0.5 mm of layer 13's side (4.4 mm) is solid, a ring 0.4 mm
  // wide, grown by a bead and a quarter into the sparse fill.
  CHECK(area_of(plain, PathKind::SolidInfill) == 0);
  CHECK(area_of(shell, PathKind::SolidInfill) > 4 * 12 * 0.4);
  CHECK(area_of(shell, PathKind::Infill) < area_of(plain, PathKind::Infill));
  // A straight wall: the neighbours are the same square, the fill 1 mm in: nothing changes.
  auto straight = test::stack(30, 0.2, geo::Polygon{test::rect(0, 0, 20, 20), {}});
  Neighbours nb2(straight, 10);
  const auto s_plain = split_fill(geo::Rings{test::rect(1, 1, 19, 19)}, nb2, SolidSpec{});
  const auto s_shell = split_fill(geo::Rings{test::rect(1, 1, 19, 19)}, nb2, spec);
  CHECK(area_of(s_shell, PathKind::SolidInfill) == 0);
  CHECK(area_of(s_shell, PathKind::Infill) == Approx(area_of(s_plain, PathKind::Infill)));
}

TEST_CASE("relations: piece.overhang averaged along the path over short pieces, long pieces keep theirs") {
  auto pt = [](double x) { return geo::Point(std::llround(x * geo::kUnitsPerMm), 0); };
  // Pieces 0.2 mm long alternating 0 and 1 (a curved wall's noise), then a 5 mm piece at 0.6.
  geo::Ring pts;
  std::vector<float> v;
  double x = 0;
  pts.push_back(pt(x));
  for (int i = 0; i < 20; ++i) {
    x += 0.2;
    pts.push_back(pt(x));
    v.push_back(i % 2 ? 1.0f : 0.0f);
  }
  x += 5;
  pts.push_back(pt(x));
  v.push_back(0.6f);
  auto a = average_along(v, pts, 1.0);
  REQUIRE(a.size() == v.size());
  // A short piece in the middle of the noise: the mean of the 1 mm around it (pieces 8..12: two
  // ones of five).
  CHECK(a[10] == Approx(0.4).epsilon(1e-3));
  CHECK(a[1] == Approx(0.4).epsilon(1e-3));  // at the start, the window is moved inward (pieces 0..4)
  CHECK(a[20] == Approx(0.6));                // a piece longer than the window keeps its value
  // The last short piece's window (3.4..4.4 mm) reaches 0.4 mm into the long piece:
  // (0.2 + 0.2 + 0.6·0.4) / 1.
  CHECK(a[19] == Approx(0.64).epsilon(1e-3));
  // A bead wholly in the air stays exactly 1 after averaging, and one wholly resting stays 0.
  std::vector<float> ones(20, 1.0f), zeros(20, 0.0f);
  geo::Ring short_pts(pts.begin(), pts.begin() + 21);
  for (float f : average_along(ones, short_pts, 1.0)) CHECK(f == 1.0f);
  for (float f : average_along(zeros, short_pts, 1.0)) CHECK(f == 0.0f);
  // A path shorter than the window: every piece gets the whole path's mean.
  geo::Ring two{pt(0), pt(0.2), pt(0.5)};
  auto b = average_along({0.0f, 1.0f}, two, 1.0);
  CHECK(b[0] == Approx(0.6).epsilon(1e-3));
  CHECK(b[1] == Approx(0.6).epsilon(1e-3));
  // Zero-length pieces and mismatched input do not produce NaN.
  geo::Ring still{pt(1), pt(1), pt(1)};
  auto c = average_along({0.3f, 0.7f}, still, 1.0);
  CHECK(c[0] == 0.3f);
  CHECK(average_along({0.5f}, geo::Ring{pt(0)}, 1.0) == std::vector<float>{0.5f});
}

TEST_CASE("relations: a LayerCache shared by threads gives what each layer computes alone, also after release") {
  // A pyramid of squares with a hole: every layer's neighbours differ, so every region depends on
  // what the cache returns. Each layer split with its own Neighbours and with one sharing the
  // cache, from two threads at once; then every layer released and asked again.
  std::vector<geo::Layer> layers = test::stack(40, 0.2, geo::Polygon{test::rect(0, 0, 30, 30), {}});
  for (int i = 0; i < 40; ++i) {
    const double d = 0.25 * i;
    auto& shape = layers[static_cast<size_t>(i)].islands[0].shape;
    shape.outer = test::rect(d, d, 30 - d, 30 - d);
    shape.holes = {test::rect(12 - 0.1 * i, 12, 18, 18, false)};
  }
  SolidSpec spec;
  spec.shell_mm = 0.5;
  auto fill_of = [&](int i) {
    const double d = 0.25 * i + 1;
    return geo::Rings{test::rect(d, d, 30 - d, 30 - d), test::rect(11 - 0.1 * i, 11, 19, 19, false)};
  };
  auto areas = [&](const std::vector<FillRegion>& r) {
    std::vector<double> a;
    for (PathKind k : {PathKind::Bridge, PathKind::SolidInfill, PathKind::TopSolid, PathKind::Infill})
      a.push_back(area_of(r, k));
    return a;
  };
  std::vector<std::vector<double>> alone(40), shared(40), again(40);
  for (int i = 0; i < 40; ++i) {
    Neighbours nb(layers, i);
    alone[static_cast<size_t>(i)] = areas(split_fill(fill_of(i), nb, spec));
  }
  LayerCache cache(layers);
  auto run = [&](int from, int step, std::vector<std::vector<double>>& out) {
    for (int i = from; i < 40; i += step) {
      Neighbours nb(layers, i, &cache);
      out[static_cast<size_t>(i)] = areas(split_fill(fill_of(i), nb, spec));
    }
  };
  std::thread t([&] { run(0, 2, shared); });
  run(1, 2, shared);
  t.join();
  for (size_t i = 0; i < 40; ++i) cache.release(i);
  run(0, 1, again);
  for (size_t i = 0; i < 40; ++i) {
    INFO("layer " << i);
    for (size_t k = 0; k < 4; ++k) {
      CHECK(shared[i][k] == Approx(alone[i][k]).epsilon(1e-9));
      CHECK(again[i][k] == Approx(alone[i][k]).epsilon(1e-9));
    }
  }
  // The shell made some of the pyramid's fill solid, so the comparison saw it.
  double solid = 0;
  for (const auto& a : alone) solid += a[1];
  CHECK(solid > 10);
}

TEST_CASE("relations: the solid fill with the vertical shell is the union of what each neighbour leaves, from two booleans") {
  // A wobbling, swelling and shrinking disc (many vertices, every slope) with an off-centre hole:
  // each layer's solid_region against the definition, the union over the layers above and below
  // of fill − layer and of fill − (the side's layers shrunk, intersected), near the bottom and
  // the top too (a side outside the print: all solid), with and without a shared LayerCache.
  const int count = 40;
  auto disc = [](double cx, double cy, double r, bool ccw) {
    geo::Ring ring;
    for (int k = 0; k < 180; ++k) {
      const double a = 2 * M_PI * k / 180;
      const double rr = r * (1 + 0.04 * std::sin(7 * a));
      ring.push_back(geo::to_point(cx + rr * std::cos(a), cy + rr * std::sin(a)));
    }
    if (!ccw) ClipperLib::ReversePath(ring);
    return ring;
  };
  std::vector<geo::Layer> layers = test::stack(count, 0.2, geo::Polygon{test::rect(0, 0, 1, 1), {}});
  for (int i = 0; i < count; ++i) {
    auto& shape = layers[static_cast<size_t>(i)].islands[0].shape;
    const double r = 10 + 3 * std::sin(i * 0.25);
    shape.outer = disc(15 + 0.15 * i, 15, r, true);
    shape.holes = {disc(15 + 0.1 * i, 14, 2 + 0.08 * i, false)};
  }
  SolidSpec spec;
  spec.shell_mm = 0.6;
  auto definition = [&](int i, const geo::Rings& fill) {
    geo::Rings solid;
    for (const auto& [sign, n] : {std::pair{1, spec.top_layers}, std::pair{-1, spec.bottom_layers}}) {
      geo::Rings window;
      bool outside = false;
      for (int k = 1; k <= n; ++k) {
        const int j = i + sign * k;
        if (j < 0 || j >= count) {
          outside = true;
          break;
        }
        const geo::Rings m = material(layers[static_cast<size_t>(j)]);
        solid = union_of(solid, difference(fill, m));
        const geo::Rings e = offset_coarse(m, -spec.shell_mm);
        window = k == 1 ? e : intersection(window, e);
      }
      solid = union_of(solid, outside ? fill : difference(fill, window));
    }
    return solid;
  };
  LayerCache cache(layers);
  double total = 0;
  for (int i = 1; i < count; ++i) {
    INFO("layer " << i);
    const geo::Rings fill = offset(material(layers[static_cast<size_t>(i)]), -0.9);
    const EdgeGrid grid(fill);
    Neighbours alone(layers, i), shared(layers, i, &cache);
    const geo::Rings got = solid_region(fill, grid, alone, spec);
    const geo::Rings want = definition(i, fill);
    const double a = area_mm2(want);
    total += a;
    CHECK(area_mm2(got) == Approx(a).epsilon(1e-6));
    CHECK(area_mm2(difference(got, want)) < 1e-4);
    CHECK(area_mm2(difference(want, got)) < 1e-4);
    CHECK(solid_region(fill, grid, shared, spec) == got);
  }
  CHECK(total > 100);  // the shell made a good part of the fill solid: the comparison saw it
}

namespace {

// The layer-below questions as they were answered before the grid's shortcuts (a ray to +x over
// every edge, crossings at or right of the point; a bead's samples split at their crossings, each
// stretch classified by its rounded midpoint; std::llround): piece.overhang must not change.
struct RefEdges {
  std::vector<std::pair<geo::Point, geo::Point>> edges;
  explicit RefEdges(const geo::Rings& rings) {
    for (const auto& r : rings)
      for (size_t i = 0; i < r.size(); ++i) edges.emplace_back(r[i], r[(i + 1) % r.size()]);
  }
  bool inside(const geo::Point& p) const {
    bool in = false;
    for (const auto& [a, b] : edges) {
      if ((a.Y > p.Y) == (b.Y > p.Y)) continue;
      const double x = double(a.X) + double(p.Y - a.Y) * double(b.X - a.X) / double(b.Y - a.Y);
      if (x >= double(p.X)) in = !in;
    }
    return in;
  }
  double inside_fraction(const geo::Point& a, const geo::Point& b) const {
    std::vector<double> ts;
    for (const auto& [c, d] : edges) {
      if (!segments_meet(a, b, c, d)) continue;
      const double rx = double(b.X - a.X), ry = double(b.Y - a.Y), sx = double(d.X - c.X), sy = double(d.Y - c.Y);
      const double den = rx * sy - ry * sx;
      if (den == 0) continue;
      ts.push_back((double(c.X - a.X) * sy - double(c.Y - a.Y) * sx) / den);
    }
    std::sort(ts.begin(), ts.end());
    ts.erase(std::unique(ts.begin(), ts.end(), [](double u, double v) { return std::abs(u - v) < 1e-12; }), ts.end());
    double covered = 0, prev = 0;
    ts.push_back(1.0);
    for (double t : ts) {
      t = std::clamp(t, 0.0, 1.0);
      if (t > prev) {
        const double mid = 0.5 * (prev + t);
        const geo::Point m(a.X + std::llround(mid * double(b.X - a.X)), a.Y + std::llround(mid * double(b.Y - a.Y)));
        if (inside(m)) covered += t - prev;
      }
      prev = std::max(prev, t);
    }
    return covered;
  }
  std::vector<float> overhang_fractions(const geo::Ring& pts, double width_mm) const {
    const size_t n = pts.size() < 2 ? 0 : pts.size() - 1;
    std::vector<float> out(n, 0.0f);
    const double half = 0.5 * width_mm * geo::kUnitsPerMm;
    for (size_t i = 0; i < n; ++i) {
      const geo::Point &a = pts[i], &b = pts[i + 1];
      const double dx = double(b.X - a.X), dy = double(b.Y - a.Y), len = std::hypot(dx, dy);
      if (len <= 0) continue;
      const double nx = -dy / len * half, ny = dx / len * half;
      std::vector<double> ts{0.25, 0.5, 0.75};
      if (len < width_mm * geo::kUnitsPerMm) ts = {0.5};
      double miss = 0;
      for (double t : ts) {
        const double mx = double(a.X) + dx * t, my = double(a.Y) + dy * t;
        const geo::Point l(std::llround(mx + nx), std::llround(my + ny)), r(std::llround(mx - nx), std::llround(my - ny));
        miss += 1.0 - inside_fraction(l, r);
      }
      out[i] = static_cast<float>(miss / static_cast<double>(ts.size()));
    }
    return out;
  }
};

// A wobbly ring of n vertices round (cx, cy), radius r ± wobble.
geo::Ring wobbly(std::mt19937& rng, double cx, double cy, double r, double wobble, int n) {
  std::uniform_real_distribution<double> u(-1, 1);
  geo::Ring ring;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n, rr = r + wobble * u(rng);
    ring.push_back(geo::to_point(cx + rr * std::cos(a), cy + rr * std::sin(a)));
  }
  return ring;
}

}  // namespace

TEST_CASE("relations: piece.overhang and point-in-layer answer as before the grid's shortcuts") {
  // Layers below of a few hundred edges (holes, separate parts), walls of the layer above shifted
  // off them by up to 2 mm, grids of several pitches (the walk to a cell no edge passes through
  // goes right or left): every fraction is the reference's, to the bit.
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(0, 1);
  int pieces = 0, partial = 0, points = 0;
  for (int t = 0; t < 40; ++t) {
    geo::Rings below{wobbly(rng, 0, 0, 20 + 10 * u(rng), 1.5, 200 + int(300 * u(rng)))};
    if (t % 2 == 0) {
      geo::Ring hole = wobbly(rng, 3 * u(rng), 3 * u(rng), 6, 1, 80);
      std::reverse(hole.begin(), hole.end());
      below.push_back(hole);
    }
    if (t % 3 == 0) below.push_back(wobbly(rng, 45, 0, 8, 1, 60));
    const RefEdges ref(below);
    const double dx = 2 * u(rng) - 1, dy = 2 * u(rng) - 1;
    geo::Rings above = below;
    for (auto& r : above)
      for (auto& p : r) p.X += geo::to_units(dx), p.Y += geo::to_units(dy);
    for (geo::coord_t cell : {geo::coord_t(0), geo::to_units(0.7), geo::to_units(3.0)}) {
      const EdgeGrid grid(below, cell);
      for (const geo::Ring& wall : offset(above, -0.225)) {
        geo::Ring path = wall;
        path.push_back(wall.front());
        const auto got = overhang_fractions(path, 0.45, grid);
        const auto want = ref.overhang_fractions(path, 0.45);
        REQUIRE(got.size() == want.size());
        for (size_t i = 0; i < got.size(); ++i) {
          CHECK(got[i] == want[i]);
          ++pieces;
          if (want[i] > 0 && want[i] < 1) ++partial;
        }
      }
      for (int k = 0; k < 300; ++k) {
        const geo::Point p = geo::to_point(-35 + 90 * u(rng), -35 + 70 * u(rng));
        CHECK(grid.inside(p) == ref.inside(p));
        ++points;
      }
    }
  }
  CHECK(partial > pieces / 20);  // the walls do straddle the layer below's border
  CHECK(points == 40 * 3 * 300);
}

TEST_CASE("relations: EdgeGrid::box_clear: no edge meets the box, also edges passing its corners") {
  // A triangle (0,0) (10,0) (0,10): its long edge runs along x + y = 10.
  const geo::Rings tri{{geo::to_point(0, 0), geo::to_point(10, 0), geo::to_point(0, 10)}};
  for (geo::coord_t cell : {geo::coord_t(0), geo::to_units(0.3), geo::to_units(20.0)}) {
    const EdgeGrid g(tri, cell);
    auto box = [&](double x0, double y0, double x1, double y1) {
      return g.box_clear(geo::to_units(x0), geo::to_units(y0), geo::to_units(x1), geo::to_units(y1));
    };
    CHECK(box(1, 1, 3, 3));        // inside
    CHECK(box(6, 6, 8, 8));        // outside, its corner (6, 6) beyond the long edge: the boxes' overlap is not a meeting
    CHECK(box(4.9, 5.2, 6, 6));    // its corner a tenth of a millimetre off the long edge
    CHECK_FALSE(box(4, 4, 6, 6));  // the long edge crosses it, no vertex inside
    CHECK_FALSE(box(5, 5, 6, 6));  // touches it at a corner
    CHECK_FALSE(box(-1, -1, 1, 1));  // holds a vertex
    CHECK(box(20, 20, 30, 30));    // clear of the grid
  }
}

TEST_CASE("relations: EdgeGrid::along answers as testing every edge does, near edges and off them") {
  // Segments laid along a layer's edges, a little off them, past their ends, and across them:
  // the grid (which passes by edges far from the segment's midpoint in four comparisons) says
  // what the definition over every edge says.
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(0, 1);
  const geo::Rings rings{wobbly(rng, 0, 0, 20, 2, 300)};
  const RefEdges ref(rings);
  const geo::coord_t tol = geo::to_units(0.01);
  auto along_ref = [&](const geo::Point& a, const geo::Point& b) {
    const geo::Point m((a.X + b.X) / 2, (a.Y + b.Y) / 2);
    const double t2 = double(tol) * double(tol);
    for (const auto& [ea, eb] : ref.edges) {
      const double ex = double(eb.X - ea.X), ey = double(eb.Y - ea.Y), len2 = ex * ex + ey * ey;
      auto d2 = [&](const geo::Point& p) {
        const double cr = ex * double(p.Y - ea.Y) - ey * double(p.X - ea.X);
        return cr * cr / len2;
      };
      if (d2(a) > t2 || d2(b) > t2) continue;
      const double t = (ex * double(m.X - ea.X) + ey * double(m.Y - ea.Y)) / len2, slack = double(tol) / std::sqrt(len2);
      if (t >= -slack && t <= 1 + slack) return true;
    }
    return false;
  };
  int yes = 0, no = 0;
  for (geo::coord_t cell : {geo::coord_t(0), geo::to_units(1.0)}) {
    const EdgeGrid g(rings, cell);
    for (int k = 0; k < 3000; ++k) {
      const auto& [ea, eb] = ref.edges[static_cast<size_t>(u(rng) * double(ref.edges.size())) % ref.edges.size()];
      const double ex = double(eb.X - ea.X), ey = double(eb.Y - ea.Y), len = std::hypot(ex, ey);
      const double nx = -ey / len, ny = ex / len;
      auto at = [&](double s, double off) {  // s along the edge (0..1), off across it (units)
        return geo::Point(std::llround(double(ea.X) + ex * s + nx * off), std::llround(double(ea.Y) + ey * s + ny * off));
      };
      const double off = (u(rng) * 3 - 1.5) * double(tol);
      const double s0 = u(rng) * 1.4 - 0.2, s1 = s0 + (u(rng) - 0.5) * 0.8;
      const geo::Point a = at(s0, off), b = k % 5 == 0 ? at(s1, off + (u(rng) - 0.5) * 1e6) : at(s1, off * (0.5 + u(rng)));
      const bool want = along_ref(a, b);
      CHECK(g.along(a, b, tol) == want);
      (want ? yes : no) += 1;
    }
  }
  CHECK(yes > 1000);
  CHECK(no > 1000);
}
