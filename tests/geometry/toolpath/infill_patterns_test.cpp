#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "fixtures.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/infill_patterns.h"

using namespace tranche;
using namespace tranche::toolpath;
using schema::InfillPattern;

namespace {

constexpr double kSpacing = 0.45;

PatternSpec spec_of(InfillPattern p, double density = 0.2, double z = 0.3) {
  PatternSpec s;
  s.pattern = p;
  s.angle_deg = 45;
  s.spacing_mm = kSpacing;
  s.density = density;
  s.z_mm = z;
  s.artificial_inset_mm = 0.5 * kSpacing;
  s.link_max_mm = 5 * kSpacing / density;
  return s;
}

double length_mm(const std::vector<FillPath>& fps) {
  double l = 0;
  for (const auto& fp : fps)
    for (size_t i = 1; i < fp.pts.size(); ++i)
      l += std::hypot(geo::to_mm(fp.pts[i].X - fp.pts[i - 1].X), geo::to_mm(fp.pts[i].Y - fp.pts[i - 1].Y));
  return l;
}

// Whether every point of every path lies in `rings` or within `tol_mm` of their border.
bool all_inside(const std::vector<FillPath>& fps, const geo::Rings& rings, double tol_mm) {
  const geo::Rings grown = offset(rings, tol_mm);
  for (const auto& fp : fps)
    for (const auto& p : fp.pts) {
      int w = 0;
      for (const auto& r : grown)
        if (ClipperLib::PointInPolygon(p, r) != 0) w += ClipperLib::Orientation(r) ? 1 : -1;
      if (w <= 0) return false;
    }
  return true;
}

const InfillPattern kLinePatterns[] = {InfillPattern::Grid, InfillPattern::Triangles, InfillPattern::Cubic,
                                       InfillPattern::Honeycomb, InfillPattern::Gyroid, InfillPattern::Concentric};

std::string name_of(InfillPattern p) { return std::string(schema::enum_value_name(schema::EnumType::InfillPattern, static_cast<int>(p))); }

}  // namespace

// Coverage: a pattern at density ρ lays ρ·area/spacing of line on a square (honeycomb ρ(4 − ρ)/3,
// plastic_fraction: PrusaSlicer's hexagons at ρ, their shared sides printed twice). The lines are clipped
// at the border: on a square 3 to 9 pitches wide (20 mm at 20 % and 40 %, 40 mm at 10 %, where
// the triangles' pitch is 13.5 mm), the lines against the border
// differ from the ideal infinite pattern's by up to ±10 % (a line more or less, a wave cut at
// another phase), and the gyroid's section varies from −6 % to +9 % with z about its mean, so the
// lines alone are within ±12 %. The links along the border add at most one bead round the
// region (4 × 20 mm × spacing).
TEST_CASE("infill patterns: extruded area on a 20 mm square is density × area") {
  for (double density : {0.1, 0.2, 0.4}) {
    const double side = density < 0.2 ? 40 : 20, whole = side * side;
    const geo::Rings sq{test::rect(0, 0, side, side)};
    for (InfillPattern p : kLinePatterns) {
      CAPTURE(name_of(p));
      CAPTURE(density);
      PatternSpec unlinked = spec_of(p, density);
      unlinked.link_max_mm = 0;
      auto lines = pattern_fill(fill_shape(sq, geo::EdgeKind::Real), unlinked);
      const double extruded = length_mm(lines) * kSpacing;
      const double share = plastic_fraction(p, density);
      CHECK(share == doctest::Approx(p == InfillPattern::Honeycomb ? density * (4 - density) / 3
                                     : p == InfillPattern::Gyroid  ? density * 2.45 * 2.44 / (2 * M_PI)
                                                                   : density));
      CHECK(extruded > 0.88 * share * whole);
      // Concentric: its first loop touches the border (half a spacing inside it), which adds
      // (pitch − spacing) / 2 of band along the border: 4·side·(pitch − spacing)/2 of area.
      const double pitch = kSpacing / density;
      const double extra = p == InfillPattern::Concentric ? 4 * side * 0.5 * (pitch - kSpacing) * density : 0.0;
      CHECK(extruded < 1.12 * share * whole + extra);
      auto fps = pattern_fill(fill_shape(sq, geo::EdgeKind::Real), spec_of(p, density));
      const double linked = length_mm(fps) * kSpacing;
      CHECK(linked >= extruded - 1e-6);
      CHECK(linked <= extruded + 4 * side * kSpacing);
      // A path's area is that of its lines (links left out): their length times spacing / share.
      double area = 0;
      for (const auto& fp : fps) area += fp.area_mm2;
      CHECK(area == doctest::Approx(extruded / share).epsilon(0.01));
    }
  }
}

// The gyroid's density means PrusaSlicer's (FillGyroid: waves 2π·spacing/(2.44·density) apart):
// its lines, averaged over a period of z, lay 2.45 · 2.44 / 2π = 0.951 × density × area of bead
// (2.45: the section's length per area times its period, measured). On an 80 mm square (15
// periods) the clipped border moves that by about 1 %; the period of 2.45·spacing/density used
// before laid density × area, 5 % more, and fails.
TEST_CASE("infill patterns: the gyroid lays PrusaSlicer's plastic per area at 20 %") {
  const double side = 80, whole = side * side;
  const geo::Rings sq{test::rect(0, 0, side, side)};
  const double period = 2 * M_PI * kSpacing / (2.44 * 0.2);
  double sum = 0;
  const int n = 16;
  for (int k = 0; k < n; ++k) {
    PatternSpec s = spec_of(InfillPattern::Gyroid, 0.2, (k + 0.5) * period / n);
    s.link_max_mm = 0;
    sum += length_mm(pattern_fill(fill_shape(sq, geo::EdgeKind::Real), s)) * kSpacing;
  }
  CAPTURE(sum / n / whole);
  CHECK(sum / n == doctest::Approx(0.951 * 0.2 * whole).epsilon(0.02));
  CHECK(plastic_fraction(InfillPattern::Gyroid, 0.2) == doctest::Approx(0.951 * 0.2).epsilon(0.001));
}

// Free ends are anchored along the border (PatternSpec::anchor_mm): on a 20 mm square with a
// round hole, with no links, the anchors add at most anchor_mm per end, and every point stays on
// the region.
TEST_CASE("infill patterns: gyroid's free ends anchored along the border") {
  const geo::Rings ring{test::rect(0, 0, 20, 20), test::rect(7, 7, 13, 13, false)};
  PatternSpec s = spec_of(InfillPattern::Gyroid);
  s.link_max_mm = 0;
  const auto bare = pattern_fill(fill_shape(ring, geo::EdgeKind::Real), s);
  s.anchor_mm = 2.7;
  const auto anchored = pattern_fill(fill_shape(ring, geo::EdgeKind::Real), s);
  REQUIRE(bare.size() == anchored.size());
  const double extra = length_mm(anchored) - length_mm(bare);
  CAPTURE(extra);
  CHECK(extra > 0.5 * 2.7 * bare.size());  // most ends anchored, most of the way
  CHECK(extra <= 2 * 2.7 * bare.size() + 1e-6);
  CHECK(all_inside(anchored, ring, 0.001));
}

// Slanted borders, long edges and a slanted hole: every segment of every path, sampled along
// its length, stays inside (the clipping answers the segments away from the border from a grid
// of cells no edge passes through; a cell a slanted edge crosses but its grid missed would let a
// segment run out through it).
TEST_CASE("infill patterns: segments stay inside a slanted region") {
  const geo::Rings region{
      {geo::to_point(20, 0), geo::to_point(43, 21), geo::to_point(21, 44), geo::to_point(0, 19)},
      {geo::to_point(17, 15), geo::to_point(19.5, 29), geo::to_point(31, 25)},  // clockwise
  };
  REQUIRE(ClipperLib::Orientation(region[0]));
  REQUIRE(!ClipperLib::Orientation(region[1]));
  const geo::Rings grown = offset(region, 0.001);
  auto inside = [&](const geo::Point& q) {
    int w = 0;
    for (const auto& r : grown)
      if (ClipperLib::PointInPolygon(q, r) != 0) w += ClipperLib::Orientation(r) ? 1 : -1;
    return w > 0;
  };
  for (InfillPattern p : kLinePatterns)
    for (double density : {0.2, 0.45}) {
      CAPTURE(name_of(p));
      CAPTURE(density);
      auto fps = pattern_fill(fill_shape(region, geo::EdgeKind::Real), spec_of(p, density));
      REQUIRE(!fps.empty());
      int outside = 0;
      for (const auto& fp : fps)
        for (size_t i = 1; i < fp.pts.size(); ++i)
          for (double t : {0.1, 0.3, 0.5, 0.7, 0.9}) {
            const geo::Point& a = fp.pts[i - 1];
            const geo::Point& b = fp.pts[i];
            const geo::Point q(a.X + static_cast<geo::coord_t>(t * static_cast<double>(b.X - a.X)),
                               a.Y + static_cast<geo::coord_t>(t * static_cast<double>(b.Y - a.Y)));
            if (!inside(q)) ++outside;
          }
      CHECK(outside == 0);
    }
}

TEST_CASE("infill patterns: every line stays inside the region, also round a hole") {
  const geo::Rings ring{test::rect(0, 0, 20, 20), test::rect(6, 6, 12, 11, false)};
  for (InfillPattern p : kLinePatterns) {
    CAPTURE(name_of(p));
    auto fps = pattern_fill(fill_shape(ring, geo::EdgeKind::Real), spec_of(p));
    REQUIRE(!fps.empty());
    CHECK(all_inside(fps, ring, 0.001));
    // Nothing in the hole (shrunk by the 1 µm tolerance).
    const geo::Rings hole{test::rect(6.01, 6.01, 11.99, 10.99)};
    for (const auto& fp : fps)
      for (const auto& pt : fp.pts) CHECK(ClipperLib::PointInPolygon(pt, hole[0]) == 0);
  }
}

// Continuity: the links along the border join the pieces. On the square, without links a grid
// at 20 % has 18 separate lines and the triangles 27; with them a handful of paths remain (the
// links may not run over one another, so some ends stay apart).
TEST_CASE("infill patterns: pieces are linked along the border into few paths") {
  const geo::Rings sq{test::rect(0, 0, 20, 20)};
  for (InfillPattern p : kLinePatterns) {
    CAPTURE(name_of(p));
    PatternSpec unlinked = spec_of(p);
    unlinked.link_max_mm = 0;
    const auto pieces = pattern_fill(fill_shape(sq, geo::EdgeKind::Real), unlinked);
    const auto paths = pattern_fill(fill_shape(sq, geo::EdgeKind::Real), spec_of(p));
    CAPTURE(pieces.size());
    CAPTURE(paths.size());
    CHECK(paths.size() <= 6);
    if (p != InfillPattern::Concentric) CHECK(paths.size() * 3 <= pieces.size());
    // Linked paths are made of the same pieces (plus the links): no plastic lost.
    CHECK(length_mm(paths) >= length_mm(pieces) - 1e-3);
  }
}

TEST_CASE("infill patterns: cubic and gyroid change with z, the others stack") {
  const geo::Rings sq{test::rect(0, 0, 20, 20)};
  auto at = [&](InfillPattern p, double z) { return pattern_lines(spec_of(p, 0.2, z), 0, 0, 20, 20); };
  for (InfillPattern p : {InfillPattern::Cubic, InfillPattern::Gyroid}) {
    CAPTURE(name_of(p));
    CHECK(at(p, 0.3) != at(p, 1.3));
  }
  for (InfillPattern p : {InfillPattern::Grid, InfillPattern::Triangles, InfillPattern::Honeycomb}) {
    CAPTURE(name_of(p));
    CHECK(at(p, 0.3) == at(p, 1.3));
  }
  // Cubic: each set moves across by Δz/√2; after a whole pitch·√2 of z the lines are back.
  const double pitch = 3 * kSpacing / 0.2;
  const auto a = pattern_lines(spec_of(InfillPattern::Cubic, 0.2, 0.0), -50, -50, 50, 50);
  const auto b = pattern_lines(spec_of(InfillPattern::Cubic, 0.2, 0.1), -50, -50, 50, 50);
  REQUIRE(!a.empty());
  REQUIRE(!b.empty());
  // The first line of the first set (at 45°) moved across by 0.1/√2 mm.
  auto across = [](const geo::Ring& l) {
    const double c = std::cos(M_PI / 4), s = std::sin(M_PI / 4);
    return -geo::to_mm(l[0].X) * s + geo::to_mm(l[0].Y) * c;
  };
  CHECK(std::fmod(across(b[0]) - across(a[0]) + pitch, pitch) == doctest::Approx(0.1 / std::sqrt(2.0)).epsilon(1e-3));
  // The gyroid repeats after one period of z.
  const double period = 2 * M_PI * kSpacing / (2.44 * 0.2);
  CHECK(pattern_lines(spec_of(InfillPattern::Gyroid, 0.2, 0.5), 0, 0, 20, 20).size() ==
        pattern_lines(spec_of(InfillPattern::Gyroid, 0.2, 0.5 + period), 0, 0, 20, 20).size());
}

TEST_CASE("infill patterns: density 0 gives nothing") {
  const geo::Rings sq{test::rect(0, 0, 20, 20)};
  for (InfillPattern p : kLinePatterns) CHECK(pattern_fill(fill_shape(sq, geo::EdgeKind::Real), spec_of(p, 0.0)).empty());
}

TEST_CASE("infill patterns: line ends keep half a bead from a cut to a solid region") {
  // The right edge (x = 20) is artificial: a solid region lies beyond it.
  FillShape shape = fill_shape({test::rect(0, 0, 20, 20)}, geo::EdgeKind::Real);
  shape.kinds[0][1] = geo::EdgeKind::Artificial;  // (20,0) -> (20,20)
  for (InfillPattern p : kLinePatterns) {
    CAPTURE(name_of(p));
    auto fps = pattern_fill(shape, spec_of(p));
    REQUIRE(!fps.empty());
    double max_x = -1e9;
    for (const auto& fp : fps)
      for (const auto& pt : fp.pts) max_x = std::max(max_x, geo::to_mm(pt.X));
    CHECK(max_x <= 20 - 0.5 * kSpacing + 0.01);
    CHECK(max_x >= 20 - 0.5 * kSpacing - 0.6 * kSpacing / 0.2 * 3);
  }
}

// Cuts made of many edges, as the outlines of solid regions sliced from curved meshes are: a run
// of artificial edges through the ring's first vertex (the last side's upper half and the first
// side's left half of a square drawn with 20 edges a side), and a hole artificial all round.
// Every line end keeps half a bead from every cut; lines still reach the real edges.
TEST_CASE("infill patterns: line ends keep half a bead from runs of cut edges") {
  geo::Ring outer;
  const double corners[5][2] = {{0, 0}, {20, 0}, {20, 20}, {0, 20}, {0, 0}};
  for (int side = 0; side < 4; ++side)
    for (int k = 0; k < 20; ++k) {
      const double t = k / 20.0;
      outer.push_back(geo::to_point(corners[side][0] + t * (corners[side + 1][0] - corners[side][0]),
                                    corners[side][1] + t * (corners[side + 1][1] - corners[side][1])));
    }
  FillShape shape = fill_shape({outer, test::rect(8, 8, 12, 12, false)}, geo::EdgeKind::Real);
  for (size_t i = 0; i < 80; ++i)
    if (i < 10 || i >= 70) shape.kinds[0][i] = geo::EdgeKind::Artificial;
  for (auto& k : shape.kinds[1]) k = geo::EdgeKind::Artificial;
  // Distance (mm) from p to the nearest edge of the given kind.
  auto nearest = [&](const geo::Point& p, geo::EdgeKind kind) {
    double best = 1e9;
    for (size_t r = 0; r < shape.rings.size(); ++r) {
      const auto& ring = shape.rings[r];
      for (size_t i = 0; i < ring.size(); ++i) {
        if (shape.kinds[r][i] != kind) continue;
        const geo::Point &a = ring[i], &b = ring[(i + 1) % ring.size()];
        const double ax = geo::to_mm(a.X), ay = geo::to_mm(a.Y), bx = geo::to_mm(b.X), by = geo::to_mm(b.Y);
        const double px = geo::to_mm(p.X), py = geo::to_mm(p.Y), dx = bx - ax, dy = by - ay;
        const double t = std::clamp(((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
        best = std::min(best, std::hypot(px - ax - t * dx, py - ay - t * dy));
      }
    }
    return best;
  };
  for (InfillPattern p : kLinePatterns) {
    CAPTURE(name_of(p));
    auto fps = pattern_fill(shape, spec_of(p));
    REQUIRE(!fps.empty());
    double to_cut = 1e9, to_real = 1e9;
    for (const auto& fp : fps)
      for (const auto& pt : fp.pts) {
        to_cut = std::min(to_cut, nearest(pt, geo::EdgeKind::Artificial));
        to_real = std::min(to_real, nearest(pt, geo::EdgeKind::Real));
      }
    // Concentric loops are simplified to 10 µm and their arcs are chords to 25 µm.
    CHECK(to_cut >= 0.5 * kSpacing - (p == InfillPattern::Concentric ? 0.03 : 0.005));
    CHECK(to_cut <= 0.5 * kSpacing + 0.05);
    if (p != InfillPattern::Concentric) CHECK(to_real <= 0.005);  // concentric: half a bead inside
  }
}

// The waves and gyroid curves are drawn only where they reach the box (at 45° the pattern's own
// frame holds twice the box): every line must still run across the box's inside, 1 mm in from
// its sides (the margin the fill leaves round a region), starting and ending with a segment
// clear of it, and lay its share of line there, at any angle.
TEST_CASE("infill patterns: lines cross the whole box at any angle") {
  const double x0 = 0, y0 = 0, x1 = 30, y1 = 24, m = 1.0;
  // Length of segment ab inside the inner box (Liang-Barsky), mm.
  auto inside_len = [&](const geo::Point& a, const geo::Point& b) {
    const double ax = geo::to_mm(a.X), ay = geo::to_mm(a.Y), dx = geo::to_mm(b.X) - ax, dy = geo::to_mm(b.Y) - ay;
    double t0 = 0, t1 = 1;
    const double p[4] = {-dx, dx, -dy, dy}, q[4] = {ax - (x0 + m), (x1 - m) - ax, ay - (y0 + m), (y1 - m) - ay};
    for (int i = 0; i < 4; ++i) {
      if (p[i] == 0) {
        if (q[i] < 0) return 0.0;
        continue;
      }
      const double r = q[i] / p[i];
      if (p[i] < 0) t0 = std::max(t0, r);
      else t1 = std::min(t1, r);
    }
    return t1 > t0 ? (t1 - t0) * std::hypot(dx, dy) : 0.0;
  };
  for (InfillPattern p : {InfillPattern::Honeycomb, InfillPattern::Gyroid})
    for (double angle : {0.0, 20.0, 45.0, 70.0, 135.0})
      for (double z : {0.3, 1.1, 2.9}) {
        CAPTURE(name_of(p));
        CAPTURE(angle);
        CAPTURE(z);
        PatternSpec spec = spec_of(p, 0.2, z);
        spec.angle_deg = angle;
        const geo::Rings lines = pattern_lines(spec, x0, y0, x1, y1);
        double len = 0;
        bool ends_clear = true;
        for (const auto& l : lines) {
          REQUIRE(l.size() >= 2);
          if (inside_len(l[0], l[1]) > 0 || inside_len(l[l.size() - 2], l.back()) > 0) ends_clear = false;
          for (size_t i = 1; i < l.size(); ++i) len += inside_len(l[i - 1], l[i]);
        }
        CHECK(ends_clear);
        const double area = (x1 - x0 - 2 * m) * (y1 - y0 - 2 * m);
        CHECK(len * kSpacing == doctest::Approx(plastic_fraction(p, 0.2) * area).epsilon(0.12));
      }
}

TEST_CASE("infill patterns: concentric loops follow the border inward") {
  const geo::Rings sq{test::rect(0, 0, 20, 20)};
  auto fps = pattern_fill(fill_shape(sq, geo::EdgeKind::Real), spec_of(InfillPattern::Concentric));
  REQUIRE(!fps.empty());
  // The first point is on the outermost loop, half a spacing inside the border: on a side, or on
  // a corner, which the loop rounds with a radius of half a spacing (the parts narrower than a
  // bead left out), up to 0.5 · spacing · (2 − 1/√2) from both sides.
  const auto& p = fps[0].pts[0];
  const double d = std::min({geo::to_mm(p.X), geo::to_mm(p.Y), 20 - geo::to_mm(p.X), 20 - geo::to_mm(p.Y)});
  CHECK(d >= 0.5 * kSpacing - 0.005);
  CHECK(d <= 0.5 * kSpacing * (2 - 1 / std::sqrt(2.0)) + 0.005);
  // Loops 2.25 mm apart on a 20 mm square, at 0.225, 2.475, 4.725, 6.975 and 9.225 mm from the
  // border (the last one 1.55 mm wide), joined into one path by four crossings.
  CHECK(fps.size() == 1);
  // No point nearer the border than the outermost loop; a few on it (its sides).
  int outer = 0;
  for (const auto& q : fps[0].pts) {
    const double x = geo::to_mm(q.X), y = geo::to_mm(q.Y);
    const double e = std::min({x, 20 - x, y, 20 - y});
    CHECK(e >= 0.225 - 0.01);
    if (e < 0.225 + 0.01) ++outer;
  }
  CHECK(outer >= 4);
  CHECK(length_mm(fps) == doctest::Approx(4 * (19.55 + 15.05 + 10.55 + 6.05 + 1.55) + 4 * 2.25).epsilon(0.02));
}


namespace {
// A circle of `n` points, counter-clockwise (clockwise with ccw false).
geo::Ring disc(double cx, double cy, double r, int n, bool ccw = true) {
  geo::Ring ring;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n * (ccw ? 1 : -1);
    ring.push_back(geo::to_point(cx + r * std::cos(a), cy + r * std::sin(a)));
  }
  return ring;
}
}  // namespace

// Concentric loops go inward until the region is too narrow for the next one; the parts of a
// region that the next step would shrink to nothing are left out before it (a disc of radius
// below the pitch, an annulus, with its hole), which must not change the loops of the others:
// the loops over a region of several parts are those of each part alone. Parts: a 40 mm frame
// round a 16 mm hole, in the frame a 1.3 mm hole; in the hole, a disc of 3 mm (loops at 2.775
// and 0.525 mm); above the frame, an annulus 2 to 0.8 mm (one loop round it, two rings; at the
// next step its outer ring is too thin, and its hole, left alone, would be the region's
// outermost ring, which would turn the whole list the other way round: offset's orientation).
TEST_CASE("infill patterns: concentric loops of a region's parts are those of each part alone") {
  const std::vector<geo::Rings> parts{
      {test::rect(0, 0, 40, 40), test::rect(12, 12, 28, 28, false), disc(6, 6, 1.3, 64, false)},
      {disc(16, 16, 3, 128)},
      {disc(20, 44, 2.0, 96), disc(20, 44, 0.8, 64, false)},
  };
  geo::Rings all;
  double alone_len = 0;
  size_t alone_pts = 0;
  for (const auto& part : parts) {
    auto fps = pattern_fill(fill_shape(part, geo::EdgeKind::Real), spec_of(InfillPattern::Concentric));
    REQUIRE(!fps.empty());
    CHECK(all_inside(fps, part, 0.001));
    alone_len += length_mm(fps);
    for (const auto& fp : fps) alone_pts += fp.pts.size();
    all.insert(all.end(), part.begin(), part.end());
  }
  auto fps = pattern_fill(fill_shape(all, geo::EdgeKind::Real), spec_of(InfillPattern::Concentric));
  CHECK(all_inside(fps, all, 0.001));
  size_t pts = 0;
  for (const auto& fp : fps) pts += fp.pts.size();
  CHECK(pts == alone_pts);
  CHECK(length_mm(fps) == doctest::Approx(alone_len).epsilon(1e-5));
  // The disc's two loops and nothing else inside 2.9 mm of its centre.
  double r_min = 1e9;
  int on_inner = 0;
  for (const auto& fp : fps)
    for (const auto& q : fp.pts) {
      const double r = std::hypot(geo::to_mm(q.X) - 16, geo::to_mm(q.Y) - 16);
      r_min = std::min(r_min, r);
      if (std::abs(r - 0.525) < 0.03) ++on_inner;
    }
  CHECK(r_min == doctest::Approx(0.525).epsilon(0.05));
  CHECK(on_inner >= 3);
}

// Honeycomb keeps PrusaSlicer's meaning of the density (FillHoneycomb): hexagons whose opposite
// sides are 2·spacing/ρ apart (side a = 2·spacing/(√3·ρ)), each wave of the pattern repeating
// every three sides, its plateaus one spacing from the next wave's and run on by half a spacing
// / √3 at each end, so that its slopes keep the hexagon's 60°. Their doubled shared sides lay
// ρ(4 − ρ)/3 of plastic: on a 60 mm square at 20 %, 0.2533 × area / spacing of line.
TEST_CASE("infill patterns: honeycomb's hexagons are PrusaSlicer's at the density") {
  for (double density : {0.1, 0.2, 0.5, 0.8}) {
    CAPTURE(density);
    PatternSpec s = spec_of(InfillPattern::Honeycomb, density);
    s.angle_deg = 0;  // waves along x
    const geo::Rings waves = pattern_lines(s, 0, 0, 60, 60);
    REQUIRE(waves.size() >= 2);
    const geo::Ring& w = waves[0];
    REQUIRE(w.size() >= 8);
    const double side = 2 * kSpacing / (std::sqrt(3.0) * density), e = 0.5 * kSpacing / std::sqrt(3.0);
    // A wave's points: plateau start, plateau end, slope, plateau, slope: x steps a + 2e, a/2 − 2e.
    const double steps[2] = {side + 2 * e, 0.5 * side - 2 * e};
    for (size_t i = 0; i + 1 < 8; ++i) {
      const double dx = std::abs(geo::to_mm(w[i + 1].X - w[i].X));
      CHECK(dx == doctest::Approx(steps[i % 2]).epsilon(1e-3));
    }
    // The slope rises the hexagon's half height less one spacing (the doubled sides), at 60°
    // from the plateaus' normal: rise = √3 × run.
    const double h = side * std::sqrt(3.0) / 2;
    const double rise = std::abs(geo::to_mm(w[2].Y - w[1].Y)), run = std::abs(geo::to_mm(w[2].X - w[1].X));
    CHECK(rise == doctest::Approx(h - kSpacing).epsilon(1e-3));
    CHECK(rise == doctest::Approx(std::sqrt(3.0) * run).epsilon(1e-3));
    CHECK(plastic_fraction(InfillPattern::Honeycomb, density) == doctest::Approx(density * (4 - density) / 3));
  }
  // The plastic on a square away from its border: the unlinked lines over 60 mm at 20 %.
  const geo::Rings sq{test::rect(0, 0, 60, 60)};
  PatternSpec s = spec_of(InfillPattern::Honeycomb, 0.2);
  s.link_max_mm = 0;
  const double extruded = length_mm(pattern_fill(fill_shape(sq, geo::EdgeKind::Real), s)) * kSpacing;
  CHECK(extruded == doctest::Approx(0.2 * 3.8 / 3 * 3600).epsilon(0.02));
  CHECK(plastic_fraction(InfillPattern::Honeycomb, 1.0) == doctest::Approx(1.0));
  CHECK(plastic_fraction(InfillPattern::Honeycomb, 0.0) == 0);
  CHECK(plastic_fraction(InfillPattern::Grid, 1.5) == 1);
}
