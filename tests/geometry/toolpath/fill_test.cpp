#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "fixtures.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/edge_grid.h"
#include "geometry/toolpath/perimeters.h"
#include "geometry/toolpath/zigzag.h"
#include "geometry/toolpath/zigzag_ring.h"

using namespace tranche;
using namespace tranche::toolpath;
using doctest::Approx;

namespace {
double dist_to_segment_mm(const geo::Point& p, const geo::Point& a, const geo::Point& b) {
  double ax = geo::to_mm(a.X), ay = geo::to_mm(a.Y), bx = geo::to_mm(b.X), by = geo::to_mm(b.Y);
  double px = geo::to_mm(p.X), py = geo::to_mm(p.Y);
  double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / l2, 0.0, 1.0) : 0;
  return std::hypot(px - ax - t * dx, py - ay - t * dy);
}
double dist_to_ring_mm(const geo::Point& p, const geo::Ring& r) {
  double d = 1e9;
  for (size_t i = 0; i < r.size(); ++i) d = std::min(d, dist_to_segment_mm(p, r[i], r[(i + 1) % r.size()]));
  return d;
}
}  // namespace

TEST_CASE("perimeters: loops at w/2 and w/2 + spacing from the outline, fill region beyond") {
  geo::Rings sq{test::rect(0, 0, 20, 20)};
  PerimeterSpec spec;
  auto per = make_perimeters(sq, spec);
  REQUIRE(per.loops.size() == 2);
  CHECK(per.loops[0].depth == 0);
  CHECK(per.loops[1].depth == 1);
  const double s = 0.45 - 0.2 * (1 - M_PI / 4);
  for (const auto& p : per.loops[0].ring) CHECK(dist_to_ring_mm(p, sq[0]) == Approx(0.225).epsilon(1e-4));
  // The second loop is opened (corners rounded by 0.3·spacing), never closer than its offset.
  for (const auto& p : per.loops[1].ring) {
    CHECK(dist_to_ring_mm(p, sq[0]) >= 0.225 + s - 1e-4);
    CHECK(dist_to_ring_mm(p, sq[0]) <= 0.225 + s + 0.3 * s * (std::sqrt(2.0) - 1) + 1e-4);
  }
  // The fill region keeps one spacing from the inner loop, less the overlap.
  double expect = 0.225 + s + s - 0.15 * 0.45;
  double side = 20 - 2 * expect;
  CHECK(area_mm2(per.fill_region) == Approx(side * side).epsilon(2e-3));
}

TEST_CASE("perimeters: a hole gets its own loops, clockwise") {
  geo::Rings ring{test::rect(0, 0, 20, 20), test::rect(8, 8, 12, 12, false)};
  auto per = make_perimeters(ring, PerimeterSpec{});
  int holes = 0;
  for (const auto& l : per.loops) holes += l.hole ? 1 : 0;
  CHECK(holes == 2);
  for (const auto& l : per.loops) CHECK(ClipperLib::Orientation(l.ring) == !l.hole);
}

TEST_CASE("perimeters: in a part too thin for two loops the second vanishes instead of overlapping") {
  // 1.0 mm wide: the outer loop fits (its two sides 0.55 mm apart), a second would overlap it.
  geo::Rings thin{test::rect(0, 0, 20, 1.0)};
  auto per = make_perimeters(thin, PerimeterSpec{});
  REQUIRE(!per.loops.empty());
  for (const auto& l : per.loops) CHECK(l.depth == 0);
  CHECK(per.fill_region.empty());
}

TEST_CASE("perimeters: the outer loop follows the wall outline, the rest the island simplified more") {
  // A disc of radius 5 mm as a 720-gon (the wall outline) and as a 24-gon (the island: its
  // chords up to 43 µm inside the circle).
  auto disc = [](int n) {
    geo::Ring r;
    for (int k = 0; k < n; ++k)
      r.push_back(geo::to_point(5 * std::cos(2 * M_PI * k / n), 5 * std::sin(2 * M_PI * k / n)));
    return geo::Rings{r};
  };
  const geo::Rings fine = disc(720), coarse = disc(24);
  // The nearest and farthest the ring comes to the centre (vertices and edges' midpoints).
  auto radii = [](const geo::Ring& r) {
    double lo = 1e9, hi = 0;
    for (size_t i = 0; i < r.size(); ++i) {
      const geo::Point &p = r[i], &q = r[(i + 1) % r.size()];
      for (double t : {0.0, 0.5}) {
        const double d = std::hypot(geo::to_mm(p.X) + t * geo::to_mm(q.X - p.X), geo::to_mm(p.Y) + t * geo::to_mm(q.Y - p.Y));
        lo = std::min(lo, d), hi = std::max(hi, d);
      }
    }
    return std::pair{lo, hi};
  };
  for (WallMode mode : {WallMode::Classic, WallMode::Variable}) {
    PerimeterSpec spec;
    spec.mode = mode;
    for (bool thin : {false, true}) {
      INFO("variable " << (mode == WallMode::Variable) << ", thin path " << thin);
      // A strip too thin for two loops beside the disc, in both, sends the walls down the path
      // that opens loops.
      geo::Rings island = coarse, outline = fine;
      if (thin) {
        island.push_back(test::rect(10, -0.4, 30, 0.4));
        outline.push_back(test::rect(10, -0.4, 30, 0.4));
      }
      const auto with = make_perimeters(island, spec, &outline);
      const auto without = make_perimeters(island, spec);
      REQUIRE(with.loops.size() == without.loops.size());
      if (thin) CHECK(!with.beads.empty());  // the strip's middle
      // Loop 0 of the disc lies 0.225 mm inside the circle (the 720-gon's chords sag 0.05 µm),
      // not inside the 24-gon; the inner loops and the fill region are the same as without.
      const Loop* disc0 = nullptr;
      for (const auto& l : with.loops)
        if (l.depth == 0 && std::abs(geo::to_mm(l.ring[0].X)) < 6) disc0 = &l;
      const Loop* disc0_without = nullptr;
      for (const auto& l : without.loops)
        if (l.depth == 0 && std::abs(geo::to_mm(l.ring[0].X)) < 6) disc0_without = &l;
      REQUIRE(disc0);
      REQUIRE(disc0_without);
      const auto [lo, hi] = radii(disc0->ring);
      CHECK(lo >= 5 - 0.225 - 0.002);
      CHECK(hi <= 5 - 0.225 + 0.002);
      CHECK(radii(disc0_without->ring).first < 5 - 0.225 - 0.03);
      for (size_t k = 0; k < with.loops.size(); ++k)
        if (with.loops[k].depth > 0) CHECK(with.loops[k].ring == without.loops[k].ring);
      CHECK(area_mm2(difference(with.fill_region, without.fill_region)) < 1e-6);
      CHECK(area_mm2(difference(without.fill_region, with.fill_region)) < 1e-6);
      CHECK(area_mm2(with.fill_region) > 40);
    }
  }
}

TEST_CASE("zig-zag: a convex cell is filled by one continuous path along its border") {
  geo::Rings sq{test::rect(0, 0, 10, 10)};
  FillSpec spec;
  spec.angle_deg = 0;
  spec.pitch_mm = 1.0;
  auto paths = zigzag(fill_shape(sq, geo::EdgeKind::Real), spec);
  REQUIRE(paths.size() == 1);
  const auto& p = paths[0];
  REQUIRE(p.border.size() + 1 == p.pts.size());
  int lines = 0, connectors = 0;
  for (size_t i = 0; i + 1 < p.pts.size(); ++i) {
    const auto &a = p.pts[i], &b = p.pts[i + 1];
    if (p.border[i] == schema::Border::None) {
      ++lines;
      CHECK(a.Y == b.Y);  // fill lines run at the fill angle (0°)
      CHECK(std::abs(geo::to_mm(b.X - a.X)) == Approx(10).epsilon(1e-6));
    } else {
      ++connectors;
      CHECK(p.border[i] == schema::Border::Real);
      CHECK((a.X == b.X && (a.X == 0 || a.X == geo::to_units(10))));  // along the side
    }
  }
  CHECK(lines == 11);  // 10 mm at pitch 1: border to border
  CHECK(connectors == 10);
}

TEST_CASE("zig-zag: sparse lines sit on a bed grid so neighbouring cells line up") {
  FillSpec spec;
  spec.angle_deg = 0;
  spec.pitch_mm = 2.0;
  auto a = zigzag(fill_shape({test::rect(0.3, 0.3, 5, 9.7)}, geo::EdgeKind::Real), spec);
  REQUIRE(a.size() == 1);
  for (size_t i = 0; i + 1 < a[0].pts.size(); ++i)
    if (a[0].border[i] == schema::Border::None) CHECK(a[0].pts[i].Y % geo::to_units(2.0) == 0);
}

TEST_CASE("zig-zag: artificial edges are kept half a bead away, real ones followed") {
  geo::Ring sq = test::rect(0, 0, 10, 10);
  FillShape shape = fill_shape({sq}, geo::EdgeKind::Real);
  shape.kinds[0][1] = geo::EdgeKind::Artificial;  // the right side (10,0)-(10,10) is a cut
  FillSpec spec;
  spec.angle_deg = 0;
  spec.pitch_mm = 0.5;
  spec.artificial_inset_mm = 0.2;
  auto paths = zigzag(shape, spec);
  REQUIRE(paths.size() == 1);
  double max_x = 0, min_x = 100;
  bool artificial_connector = false;
  for (size_t i = 0; i < paths[0].pts.size(); ++i) {
    max_x = std::max(max_x, geo::to_mm(paths[0].pts[i].X));
    min_x = std::min(min_x, geo::to_mm(paths[0].pts[i].X));
    if (i < paths[0].border.size() && paths[0].border[i] == schema::Border::Artificial)
      artificial_connector = true;
  }
  CHECK(max_x == Approx(9.8));
  CHECK(min_x == Approx(0));
  CHECK(artificial_connector);
}

TEST_CASE("zig-zag: solid grids spread border to border; a slanted cut pulls line ends back half a bead") {
  auto g = region_grid({1.0, 11.2}, 0.4);
  CHECK(g.origin_mm == 1.0);
  CHECK(g.pitch_mm * std::lround(10.2 / 0.4) == Approx(10.2));
  CHECK(g.ratio == Approx(g.pitch_mm / 0.4));
  auto one = region_grid({0, 0.1}, 0.4);  // thinner than half a pitch: one line in the middle
  CHECK(one.origin_mm == Approx(0.05));
  // A triangle cell whose hypotenuse is a cut at 30° to the (horizontal) lines.
  geo::Ring tri{geo::to_point(0, 0), geo::to_point(10, 0), geo::to_point(0, 10 * std::tan(M_PI / 6))};
  FillShape shape = fill_shape({tri}, geo::EdgeKind::Real);
  shape.kinds[0][1] = geo::EdgeKind::Artificial;
  FillSpec spec;
  spec.angle_deg = 0;
  spec.pitch_mm = 0.5;
  spec.artificial_inset_mm = 0.2;
  auto paths = zigzag(shape, spec);
  REQUIRE(paths.size() == 1);
  const auto& p = paths[0];
  for (size_t i = 0; i + 1 < p.pts.size(); ++i) {
    if (p.border[i] != schema::Border::None) continue;
    double y = geo::to_mm(p.pts[i].Y), x_end = std::max(geo::to_mm(p.pts[i].X), geo::to_mm(p.pts[i + 1].X));
    double x_cut = (10 * std::tan(M_PI / 6) - y) / std::tan(M_PI / 6);
    CHECK(x_cut - x_end == Approx(0.2).epsilon(0.01));
  }
}

TEST_CASE("zig-zag: a U shape (not monotone) needs more than one run; every point stays inside") {
  geo::Ring u{geo::to_point(0, 0), geo::to_point(10, 0), geo::to_point(10, 10), geo::to_point(7, 10),
              geo::to_point(7, 3), geo::to_point(3, 3),  geo::to_point(3, 10),  geo::to_point(0, 10)};
  FillSpec spec;
  spec.angle_deg = 0;
  spec.pitch_mm = 0.5;
  auto paths = zigzag(fill_shape({u}, geo::EdgeKind::Real), spec);
  CHECK(paths.size() >= 2);
  EdgeGrid g(geo::Rings{u});
  for (const auto& p : paths)
    for (size_t i = 0; i + 1 < p.pts.size(); ++i) {
      geo::Point m((p.pts[i].X + p.pts[i + 1].X) / 2, (p.pts[i].Y + p.pts[i + 1].Y) / 2);
      CHECK((g.inside(m) || g.along(p.pts[i], p.pts[i + 1], 10)));
    }
  // The same shape at 90° is monotone: one path.
  spec.angle_deg = 90;
  CHECK(zigzag(fill_shape({u}, geo::EdgeKind::Real), spec).size() == 1);
}

TEST_CASE("zig-zag: any angle, the lines keep the requested direction and pitch") {
  FillSpec spec;
  spec.angle_deg = 45;
  spec.pitch_mm = 0.8;
  auto paths = zigzag(fill_shape({test::rect(0, 0, 10, 10)}, geo::EdgeKind::Real), spec);
  REQUIRE(paths.size() == 1);
  const auto& p = paths[0];
  std::vector<double> offsets;
  for (size_t i = 0; i + 1 < p.pts.size(); ++i) {
    if (p.border[i] != schema::Border::None) continue;
    double dx = double(p.pts[i + 1].X - p.pts[i].X), dy = double(p.pts[i + 1].Y - p.pts[i].Y);
    if (std::hypot(dx, dy) < 1e5) continue;
    CHECK(std::abs(std::abs(std::atan2(dy, dx)) * 180 / M_PI - (dx > 0 ? 45 : 135)) < 0.01);
    offsets.push_back((-geo::to_mm(p.pts[i].X) + geo::to_mm(p.pts[i].Y)) / std::sqrt(2.0));
  }
  std::sort(offsets.begin(), offsets.end());
  for (size_t i = 1; i < offsets.size(); ++i) CHECK(offsets[i] - offsets[i - 1] == Approx(0.8).epsilon(1e-3));
}

TEST_CASE("perimeters: an island thinner than a bead gets no loop: a bead along its axis (gap_fill_test.cpp)") {
  geo::Rings sliver{test::rect(0, 0, 10, 0.3)};
  auto per = make_perimeters(sliver, PerimeterSpec{});
  CHECK(per.loops.empty());
  CHECK(per.fill_region.empty());
  CHECK(per.beads.size() == 1);
}

TEST_CASE("perimeters: a thin island's parts narrower than min_bead_width are not printed") {
  // A cone's tip or an ear's last layer: a speck 0.05 mm across gets nothing (a bead around or
  // along it would lay its plastic outside the part).
  PerimeterSpec spec;
  spec.min_bead_width = 0.1;
  auto speck = make_perimeters(geo::Rings{test::rect(0, 0, 0.05, 0.05)}, spec);
  CHECK((speck.loops.empty() && speck.beads.empty()));
  auto needle = make_perimeters(geo::Rings{test::rect(0, 0, 10, 0.05)}, spec);
  CHECK((needle.loops.empty() && needle.beads.empty()));
  // A 0.3 mm sliver with a 0.05 mm whisker: the sliver gets its bead, the whisker nothing.
  geo::Ring t{geo::to_point(0, 0),       geo::to_point(10, 0),    geo::to_point(10, 0.3),
              geo::to_point(5.025, 0.3), geo::to_point(5.025, 3), geo::to_point(4.975, 3),
              geo::to_point(4.975, 0.3), geo::to_point(0, 0.3)};
  auto per = make_perimeters(geo::Rings{t}, spec);
  CHECK(per.loops.empty());
  REQUIRE(!per.beads.empty());
  for (const auto& b : per.beads)
    for (const auto& p : b.pts) CHECK(geo::to_mm(p.Y) < 0.31);
}

TEST_CASE("zig-zag: runs split by a notch are linked along the border when the walk is short") {
  // A 10 x 10 square with a slot 0.6 mm wide and 6 mm deep cut down from the top at x = 5:
  // horizontal lines above y = 4 meet two intervals, so the fill needs two runs.
  geo::Ring slot{geo::to_point(0, 0),   geo::to_point(10, 0),  geo::to_point(10, 10),  geo::to_point(5.3, 10),
                 geo::to_point(5.3, 4), geo::to_point(4.7, 4), geo::to_point(4.7, 10), geo::to_point(0, 10)};
  FillSpec spec;
  spec.angle_deg = 0;
  spec.pitch_mm = 1.0;
  auto apart = zigzag(fill_shape({slot}, geo::EdgeKind::Real), spec);
  REQUIRE(apart.size() == 2);
  double area = apart[0].area_mm2 + apart[1].area_mm2;
  // The walk between the two runs' ends goes round the slot: about 2 × 6 + 0.6 mm at most.
  spec.link_max_mm = 3.0;
  CHECK(zigzag(fill_shape({slot}, geo::EdgeKind::Real), spec).size() == 2);  // too far
  spec.link_max_mm = 14.0;
  auto linked = zigzag(fill_shape({slot}, geo::EdgeKind::Real), spec);
  REQUIRE(linked.size() == 1);
  const auto& p = linked[0];
  CHECK(p.runs == 2);
  CHECK(p.area_mm2 == Approx(area));
  REQUIRE(p.border.size() + 1 == p.pts.size());
  // Every piece is a fill line (horizontal) or runs along the border, and stays in the shape.
  EdgeGrid g(geo::Rings{slot});
  for (size_t i = 0; i + 1 < p.pts.size(); ++i) {
    const auto &a = p.pts[i], &b = p.pts[i + 1];
    if (p.border[i] == schema::Border::None)
      CHECK(a.Y == b.Y);
    else
      CHECK(g.along(a, b, 10));
  }
}

TEST_CASE("zig-zag: on a ring, links join the runs round the hole, each stretch of border walked once") {
  // A ring (r 1.2 to 2.5 mm) at 45°: every line meets two intervals round the hole, and the
  // short runs are joined by links along the border, none over another (a link may run over the
  // lines' connectors, never over a link).
  auto circle = [](double r, bool ccw) {
    geo::Ring c;
    for (int i = 0; i < 72; ++i) {
      double t = (ccw ? 1 : -1) * i * M_PI / 36;
      c.push_back(geo::to_point(r * std::cos(t), r * std::sin(t)));
    }
    return c;
  };
  geo::Rings ring{circle(2.5, true), circle(1.2, false)};
  FillSpec spec;
  spec.angle_deg = 45;
  spec.pitch_mm = 0.42;
  // The pieces along the border without links: the connectors.
  using Piece = std::pair<std::pair<long long, long long>, std::pair<long long, long long>>;
  auto pieces = [](const std::vector<FillPath>& paths) {
    std::multiset<Piece> out;
    for (const auto& p : paths)
      for (size_t i = 0; i + 1 < p.pts.size(); ++i) {
        if (p.border[i] == schema::Border::None) continue;
        std::pair<long long, long long> a{p.pts[i].X, p.pts[i].Y};
        std::pair<long long, long long> b{p.pts[i + 1].X, p.pts[i + 1].Y};
        out.insert(a < b ? Piece{a, b} : Piece{b, a});
      }
    return out;
  };
  auto connectors = pieces(zigzag(fill_shape(ring, geo::EdgeKind::Real), spec));
  spec.link_max_mm = 16 * 0.42;
  auto paths = zigzag(fill_shape(ring, geo::EdgeKind::Real), spec);
  size_t runs = 0;
  for (const auto& p : paths) runs += static_cast<size_t>(p.runs);
  CHECK(paths.size() < runs);  // some runs were joined
  // The links: the pieces along the border that are not connectors. Each edge of either circle
  // is covered by at most one link.
  auto all = pieces(paths);
  for (const auto& c : connectors) {
    auto it = all.find(c);
    if (it != all.end()) all.erase(it);
  }
  REQUIRE_FALSE(all.empty());
  std::map<std::pair<int, int>, int> cover;  // (circle, edge) -> links along it
  for (const auto& [a, b] : all) {
    double mx = geo::kMmPerUnit * 0.5 * double(a.first + b.first),
           my = geo::kMmPerUnit * 0.5 * double(a.second + b.second);
    int which = std::hypot(mx, my) > 1.85 ? 0 : 1;
    double t = std::atan2(my, mx);
    int edge = ((static_cast<int>(std::floor(t / (M_PI / 36))) % 72) + 72) % 72;
    ++cover[{which, edge}];
  }
  for (const auto& [edge, n] : cover) CHECK_MESSAGE(n <= 1, "circle ", edge.first, " edge ", edge.second);
}

namespace {
// A square `mm` wide from the origin, as the links along the border see a ring: real edges.
tranche::toolpath::zigzag_detail::Ring2 square_ring2(double mm) {
  const double u = geo::kUnitsPerMm;
  tranche::toolpath::zigzag_detail::Ring2 sq;
  sq.pts = {{0, 0}, {mm * u, 0}, {mm * u, mm * u}, {0, mm * u}};
  sq.kinds.assign(4, geo::EdgeKind::Real);
  return sq;
}
}  // namespace

// With many polylines, the links along the border look up the ends on a grid of cells a link
// long: the same paths as trying every end. 150 chords across a 60 mm square at shuffled x, links
// up to 2 mm.
TEST_CASE("zigzag links: the grid of ends links as trying every end does") {
  using namespace tranche::toolpath::zigzag_detail;
  const double u = geo::kUnitsPerMm;
  const Ring2 sq = square_ring2(60);
  std::vector<Poly> polys;
  uint64_t seed = 777;
  for (int i = 0; i < 150; ++i) {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    const double x = (0.2 + 0.39 * ((i * 37) % 150) + 0.05 * static_cast<double>(seed >> 60)) * u;
    Poly p;
    p.pts = {{x, 0}, {x, 60 * u}};
    p.border = {schema::Border::None};
    p.first = End{0, 0, p.pts[0]};
    p.last = End{0, 2, p.pts[1]};
    if (i % 3 == 0) std::swap(p.first, p.last), std::reverse(p.pts.begin(), p.pts.end());
    polys.push_back(p);
  }
  const auto slow = link_along_border(polys, {sq}, 2 * u, false);
  const auto fast = link_along_border(polys, {sq}, 2 * u, true);
  REQUIRE(fast.size() == slow.size());
  CHECK(slow.size() < 20);  // linked: a handful of paths, not 150
  for (size_t k = 0; k < slow.size(); ++k) {
    CAPTURE(k);
    REQUIRE(fast[k].pts.size() == slow[k].pts.size());
    for (size_t j = 0; j < slow[k].pts.size(); ++j) {
      CHECK(fast[k].pts[j].u == slow[k].pts[j].u);
      CHECK(fast[k].pts[j].v == slow[k].pts[j].v);
    }
  }
}

// Anchors (PrusaSlicer's infill_anchor): an end no link reaches runs on along the border by the
// anchor's length, the way with more room, and stops the clearance short of another end. On a
// 20 mm square, two chords at x = 5 and x = 6 mm (links up to 0.5 mm: none), anchors of 3 mm,
// clearance 0.25 mm: each end at x = 5 has 1 mm to its neighbour one way and 5 mm to the corner
// and beyond the other, so it runs 3 mm towards x = 2; those at x = 6 run 3 mm towards x = 9.
TEST_CASE("zigzag links: free ends are anchored along the border, short of other ends") {
  using namespace tranche::toolpath::zigzag_detail;
  const double u = geo::kUnitsPerMm;
  const Ring2 sq = square_ring2(20);
  auto chord = [&](double x) {
    Poly p;
    p.pts = {{x * u, 0}, {x * u, 20 * u}};
    p.border = {schema::Border::None};
    p.first = End{0, 0, p.pts[0]};
    p.last = End{0, 2, p.pts[1]};
    return p;
  };
  const std::vector<Poly> polys{chord(5), chord(6)};
  // Without anchors: the chords as they were (no link is short enough).
  const auto plain = link_along_border(polys, {sq}, 0.5 * u);
  REQUIRE(plain.size() == 2);
  CHECK(plain[0].pts.size() == 2);
  const auto anchored = link_along_border(polys, {sq}, 0.5 * u, true, 3 * u, 0.25 * u);
  REQUIRE(anchored.size() == 2);
  for (size_t k = 0; k < 2; ++k) {
    CAPTURE(k);
    const auto& P = anchored[k];
    REQUIRE(P.pts.size() == 4);
    REQUIRE(P.border.size() == 3);
    CHECK(P.border.front() == schema::Border::Real);
    CHECK(P.border.back() == schema::Border::Real);
    const double x = k == 0 ? 5 : 6, away = k == 0 ? -3 : 3;
    // First point: 3 mm along the bottom edge; last: 3 mm along the top one.
    CHECK(P.pts.front().u == doctest::Approx((x + away) * u));
    CHECK(P.pts.front().v == doctest::Approx(0));
    CHECK(P.pts[1].u == doctest::Approx(x * u));
    CHECK(P.pts.back().u == doctest::Approx((x + away) * u));
    CHECK(P.pts.back().v == doctest::Approx(20 * u));
  }
  // Three chords 1 mm apart: the middle one's ends have 1 mm each way, less the clearance, less
  // where its neighbours' anchors went (away from it): 0.75 mm.
  const std::vector<Poly> three{chord(5), chord(6), chord(7)};
  const auto mid = link_along_border(three, {sq}, 0.5 * u, true, 3 * u, 0.25 * u);
  REQUIRE(mid.size() == 3);
  REQUIRE(mid[1].pts.size() == 4);
  CHECK(std::abs(mid[1].pts.front().u - 6 * u) == doctest::Approx(0.75 * u));
  CHECK(std::abs(mid[1].pts.back().u - 6 * u) == doctest::Approx(0.75 * u));
}
