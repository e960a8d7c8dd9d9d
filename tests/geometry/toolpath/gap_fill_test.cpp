// Gap fill and variable-width walls: beads along the medial axis of what the loops leave, on
// constructed shapes (bars of 0.6 and 1.2 mm, a wedge, a tube) and on random thin shapes.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "fixtures.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/flow.h"
#include "geometry/toolpath/perimeters.h"

using namespace tranche;
using namespace tranche::toolpath;
using doctest::Approx;

namespace {

const double kExtra = 0.2 * (1 - M_PI / 4);  // a bead's width beyond its spacing at h = 0.2

double len_mm(const geo::Point& a, const geo::Point& b) {
  return std::hypot(geo::to_mm(b.X - a.X), geo::to_mm(b.Y - a.Y));
}

// Plastic of the beads (mm³ at h = 0.2), their stadium cross-section times their length.
double bead_volume(const std::vector<VarBead>& beads, double h = 0.2) {
  double v = 0;
  for (const auto& b : beads)
    for (size_t i = 0; i + 1 < b.pts.size(); ++i) v += len_mm(b.pts[i], b.pts[i + 1]) * bead_area_mm2(b.widths[i], h);
  return v;
}

double loop_volume(const Perimeters& per, const PerimeterSpec& spec) {
  double v = 0;
  for (const auto& l : per.loops)
    v += geo::length_mm(l.ring) * bead_area_mm2(spec.widths[static_cast<size_t>(l.depth)], spec.height);
  return v;
}

PerimeterSpec variable_spec() {
  PerimeterSpec s;
  s.mode = WallMode::Variable;
  return s;
}

geo::Ring circle(double cx, double cy, double r, int n, bool ccw = true) {
  geo::Ring out;
  for (int i = 0; i < n; ++i) {
    double a = 2 * M_PI * i / n * (ccw ? 1 : -1);
    out.push_back(geo::to_point(cx + r * std::cos(a), cy + r * std::sin(a)));
  }
  return out;
}

void check_beads_sane(const std::vector<VarBead>& beads, const PerimeterSpec& spec) {
  for (const auto& b : beads) {
    REQUIRE(b.pts.size() >= 2);
    REQUIRE(b.widths.size() + 1 == b.pts.size());
    for (size_t i = 0; i + 1 < b.pts.size(); ++i) {
      CHECK(b.pts[i] != b.pts[i + 1]);  // no zero-length move
      REQUIRE(std::isfinite(b.widths[i]));
      CHECK(b.widths[i] >= spec.min_bead_width - 1e-6);
      CHECK(b.widths[i] <= spec.max_bead_width + 1e-6);
    }
  }
}

}  // namespace

TEST_CASE("gap fill: a 0.6 mm wall is one 0.6 mm bead along its middle, not a loop overlapping itself") {
  geo::Rings bar{test::rect(0, 0, 20, 0.6)};
  for (const PerimeterSpec& spec : {PerimeterSpec{}, variable_spec()}) {
    auto per = make_perimeters(bar, spec);
    CHECK(per.loops.empty());
    CHECK(per.fill_region.empty());
    REQUIRE(per.beads.size() == 1);
    check_beads_sane(per.beads, spec);
    const auto& b = per.beads[0];
    for (const auto& p : b.pts) CHECK(geo::to_mm(p.Y) == Approx(0.3).epsilon(1e-4));
    for (float w : b.widths) CHECK(w == Approx(0.6 + kExtra).epsilon(1e-4));
    const double x0 = geo::to_mm(std::min(b.pts.front().X, b.pts.back().X));
    CHECK(x0 == Approx(0.3 - 0.3 * (1 - M_PI / 4)).epsilon(1e-3));
    // The axis stops 0.3 mm from either end; the bead goes on 0.3·(1 − π/4) mm beyond it, so that
    // its footprint, round ends included, has the wall's area.
    CHECK(bead_volume(per.beads) == Approx(0.6 * (19.4 + 0.6 * (1 - M_PI / 4)) * 0.2).epsilon(1e-3));
  }
}

TEST_CASE("gap fill: a wedge is walled to its tip, the bead widening with the wedge") {
  // 0 to 3 mm over 20 mm (walls up to 0.8 mm wide: classic's gap fill reaches from the tip to
  // where the loops start).
  geo::Rings wedge{geo::Ring{geo::to_point(0, 0), geo::to_point(20, -1.5), geo::to_point(20, 1.5)}};
  auto per = make_perimeters(wedge, PerimeterSpec{});
  REQUIRE(!per.beads.empty());
  check_beads_sane(per.beads, PerimeterSpec{});
  double min_x = 1e9;
  for (const auto& b : per.beads)
    for (const auto& p : b.pts) min_x = std::min(min_x, geo::to_mm(p.X));
  // The bead starts where the wedge is min_bead_width (0.1 mm) wide: x = 0.1 / 0.15 ≈ 0.67 mm.
  CHECK(min_x < 0.8);
  // Along the tip's bead the width follows the wedge: 2·x·sin(half angle) + the stadium's extra.
  const double sin_half = std::sin(std::atan(1.5 / 20));
  for (const auto& b : per.beads)
    for (size_t i = 0; i + 1 < b.pts.size(); ++i) {
      const double x = 0.5 * (geo::to_mm(b.pts[i].X) + geo::to_mm(b.pts[i + 1].X));
      if (std::abs(geo::to_mm(b.pts[i].Y)) > 1e-3 || x > 5) continue;
      CHECK(b.widths[i] == Approx(2 * x * sin_half + kExtra).epsilon(0.02));
    }
  // Loops and beads together lay about the wedge's plastic.
  const double v = loop_volume(per, PerimeterSpec{}) + bead_volume(per.beads);
  const double fill = area_mm2(offset(per.fill_region, 0.5 * bead_spacing_mm(0.45, 0.2))) * 0.2;
  CHECK((v + fill) / (30 * 0.2) == Approx(1.0).epsilon(0.06));
}

TEST_CASE("gap fill: a 1.2 mm wall, classic: one loop and a bead in the gap between its sides") {
  geo::Rings bar{test::rect(0, 0, 20, 1.2)};
  PerimeterSpec spec;
  auto per = make_perimeters(bar, spec);
  REQUIRE(per.loops.size() == 1);
  CHECK(per.loops[0].depth == 0);
  REQUIRE(!per.beads.empty());
  check_beads_sane(per.beads, spec);
  // The loop's beads own 0.225 + 0.205 mm on each side: the gap is 1.2 − 0.86 = 0.34 mm.
  const double gap = 1.2 - 2 * (0.225 + 0.5 * bead_spacing_mm(0.45, 0.2));
  bool middle = false;
  for (const auto& b : per.beads)
    for (size_t i = 0; i + 1 < b.pts.size(); ++i)
      if (std::abs(geo::to_mm(b.pts[i].Y) - 0.6) < 1e-3 && geo::to_mm(b.pts[i].X + b.pts[i + 1].X) / 2 > 2 &&
          geo::to_mm(b.pts[i].X + b.pts[i + 1].X) / 2 < 18) {
        CHECK(b.widths[i] == Approx(gap + kExtra).epsilon(0.01));
        middle = true;
      }
  CHECK(middle);
  CHECK((loop_volume(per, spec) + bead_volume(per.beads)) / (1.2 * 20 * 0.2) == Approx(1.0).epsilon(0.05));
}

TEST_CASE("variable walls: a 1.2 mm wall is two 0.6 mm beads side by side, not overlapping") {
  geo::Rings bar{test::rect(0, 0, 20, 1.2)};
  PerimeterSpec spec = variable_spec();
  auto per = make_perimeters(bar, spec);
  CHECK(per.loops.empty());
  REQUIRE(per.beads.size() == 2);
  check_beads_sane(per.beads, spec);
  std::vector<double> ys;
  for (const auto& b : per.beads) {
    ys.push_back(geo::to_mm(b.pts[0].Y));
    for (const auto& p : b.pts) CHECK(geo::to_mm(p.Y) == Approx(ys.back()).epsilon(1e-4));
    for (float w : b.widths) CHECK(w == Approx(0.6 + kExtra).epsilon(1e-3));
  }
  std::sort(ys.begin(), ys.end());
  CHECK(ys[0] == Approx(0.3).epsilon(1e-3));
  CHECK(ys[1] == Approx(0.9).epsilon(1e-3));
  CHECK(bead_volume(per.beads) / (1.2 * 20 * 0.2) == Approx(1.0).epsilon(0.05));
}

TEST_CASE("variable walls: a wide island keeps its classic loops and fill") {
  geo::Rings sq{test::rect(0, 0, 20, 20)};
  auto classic = make_perimeters(sq, PerimeterSpec{});
  auto variable = make_perimeters(sq, variable_spec());
  REQUIRE(classic.loops.size() == variable.loops.size());
  for (size_t i = 0; i < classic.loops.size(); ++i) CHECK(classic.loops[i].ring == variable.loops[i].ring);
  CHECK(variable.beads.empty());
  CHECK(area_mm2(variable.fill_region) == Approx(area_mm2(classic.fill_region)));
}

TEST_CASE("gap fill: a tube with a 0.8 mm wall") {
  geo::Rings tube{circle(0, 0, 5, 200), circle(0, 0, 4.2, 200, false)};
  const double solid = (M_PI * 25 - M_PI * 4.2 * 4.2) * 0.2;
  SUBCASE("classic: one closed bead as wide as max_bead_width allows") {
    auto per = make_perimeters(tube, PerimeterSpec{});
    CHECK(per.loops.empty());
    REQUIRE(per.beads.size() == 1);
    CHECK(per.beads[0].pts.front() == per.beads[0].pts.back());
    check_beads_sane(per.beads, PerimeterSpec{});
    CHECK(bead_volume(per.beads) / solid == Approx(0.947).epsilon(0.01));  // 0.8 − extra of 0.8
  }
  SUBCASE("variable: two beads of 0.4 mm") {
    auto per = make_perimeters(tube, variable_spec());
    CHECK(per.loops.empty());
    REQUIRE(per.beads.size() == 2);
    check_beads_sane(per.beads, variable_spec());
    CHECK(bead_volume(per.beads) / solid == Approx(1.0).epsilon(0.01));
  }
}

TEST_CASE("gap fill: a part whose axis is only corners (a square, a disc) gets a closed bead") {
  // A 1.5 mm pillar with variable walls (too thin for two loops), a 0.8 mm one and a 0.8 mm disc
  // with classic walls (too thin for one): every branch of their axis runs into a corner.
  struct Case {
    geo::Rings island;
    PerimeterSpec spec;
    double r;  // 2·area / perimeter
  };
  for (const Case& c : {Case{{test::rect(0, 0, 1.5, 1.5)}, variable_spec(), 0.75},
                        Case{{test::rect(0, 0, 0.8, 0.8)}, PerimeterSpec{}, 0.4},
                        Case{{circle(0, 0, 0.4, 64)}, PerimeterSpec{}, 0.4}}) {
    auto per = make_perimeters(c.island, c.spec);
    CHECK(per.loops.empty());
    REQUIRE(per.beads.size() == 1);
    check_beads_sane(per.beads, c.spec);
    const auto& b = per.beads[0];
    CHECK(b.pts.front() == b.pts.back());
    // (of the part no loop covers, opened: about the island's)
    for (float w : b.widths) CHECK(w == Approx(std::min(c.r + kExtra, c.spec.max_bead_width)).epsilon(0.03));
    // Half the radius in from the border: the bead's band reaches the border and the centre.
    const double a = area_mm2(c.island);
    CHECK(bead_volume(per.beads) / (a * 0.2) == Approx(1.0).epsilon(0.2));
  }
}

TEST_CASE("gap fill: degenerate islands give no bead or a sane one, never a crash") {
  for (const PerimeterSpec& spec : {PerimeterSpec{}, variable_spec()}) {
    CHECK(make_perimeters({}, spec).beads.empty());
    CHECK(make_perimeters({test::rect(0, 0, 0.05, 0.05)}, spec).beads.empty());  // sub-nozzle speck
    CHECK(make_perimeters({test::rect(0, 0, 10, 0.05)}, spec).beads.empty());    // needle below min width
    // Two squares touching at a corner (self-touching after offsets).
    auto per = make_perimeters({test::rect(0, 0, 0.5, 0.5), test::rect(0.5, 0.5, 1, 1)}, spec);
    check_beads_sane(per.beads, spec);
    // Collinear points, duplicate points.
    geo::Ring dup{geo::to_point(0, 0), geo::to_point(5, 0), geo::to_point(5, 0), geo::to_point(10, 0),
                  geo::to_point(10, 0.5), geo::to_point(0, 0.5), geo::to_point(0, 0.5)};
    per = make_perimeters({dup}, spec);
    check_beads_sane(per.beads, spec);
    CHECK(per.beads.size() == 1);
  }
}

// The area a bead owns: each piece a stadium as wide as the bead's spacing (w − h·(1 − π/4)).
geo::Rings footprint(const VarBead& b) {
  geo::Rings out;
  for (size_t i = 0; i + 1 < b.pts.size(); ++i) {
    ClipperLib::ClipperOffset co(2.0, 5000);
    co.AddPath({b.pts[i], b.pts[i + 1]}, ClipperLib::jtRound, ClipperLib::etOpenRound);
    geo::Rings piece;
    co.Execute(piece, 0.5 * (b.widths[i] - kExtra) * geo::kUnitsPerMm);
    out = union_of(out, piece);
  }
  return out;
}

TEST_CASE("gap fill: random thin shapes give sane beads that cover them without overlapping") {
  // Unions of random bars (0.15 to 2 mm wide, any direction) and small stars: thin walls, their
  // junctions, wedges and gaps between loops.
  std::mt19937_64 rng(1414);
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  int with_beads = 0;
  double worst_cover = 1, worst_overlap = 0, worst_outside = 0;
  for (int round = 0; round < 120; ++round) {
    geo::Rings parts;
    for (int i = std::uniform_int_distribution<int>(1, 5)(rng); i > 0; --i) {
      const double cx = uni(-5, 5), cy = uni(-5, 5), len = uni(1, 10), w = uni(0.15, 2), a = uni(0, M_PI);
      const double ux = std::cos(a), uy = std::sin(a);
      geo::Ring r;
      for (auto [s, t] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
        r.push_back(geo::to_point(cx + s * ux * len / 2 - t * uy * w / 2, cy + s * uy * len / 2 + t * ux * w / 2));
      parts.push_back(r);
    }
    if (round % 4 == 0) {
      geo::Ring star;
      const int n = std::uniform_int_distribution<int>(3, 9)(rng);
      for (int k = 0; k < 2 * n; ++k) {
        const double rr = k % 2 ? uni(0.2, 1) : uni(2, 5), t = M_PI * k / n;
        star.push_back(geo::to_point(rr * std::cos(t), rr * std::sin(t)));
      }
      parts.push_back(star);
    }
    const geo::Rings island = union_of(parts);
    const double area = area_mm2(island);
    for (const PerimeterSpec& spec : {PerimeterSpec{}, variable_spec()}) {
      auto per = make_perimeters(island, spec);
      check_beads_sane(per.beads, spec);
      if (!per.beads.empty()) ++with_beads;
      // Every bead point lies in the island.
      for (const auto& b : per.beads)
        for (const auto& p : b.pts) {
          int winding = 0;
          bool on = false;
          for (const auto& r : island) {
            int at = ClipperLib::PointInPolygon(p, r);
            on = on || at == -1;
            if (at == 1) winding += ClipperLib::Orientation(r) ? 1 : -1;
          }
          CHECK((on || winding > 0));
        }
      // What each owns: a loop the band one spacing wide around it (its outer side: half its
      // width, to the outline), the fill its region grown by half a fill spacing, a bead its
      // footprint. Their union covers the island but for the parts narrower than min_bead_width
      // and the square corners round bead ends leave; their sum exceeds the union only where
      // beads meet at a junction or a change of bead count, and loops and fill overlap by
      // infill_overlap.
      std::vector<geo::Rings> owned;
      for (const auto& l : per.loops)
        owned.push_back(buffer_loops({l.ring}, 0.5 * bead_spacing_mm(spec.widths[static_cast<size_t>(l.depth)], 0.2)));
      owned.push_back(offset(per.fill_region, 0.5 * bead_spacing_mm(0.45, 0.2)));
      for (const auto& b : per.beads) owned.push_back(footprint(b));
      geo::Rings all;
      double sum = 0;
      for (const auto& o : owned) {
        all = union_of(all, o);
        sum += area_mm2(o);
      }
      const double cover = area_mm2(intersection(all, island)) / area;
      const double outside = area_mm2(difference(all, island)) / area;
      const double overlap = (sum - area_mm2(all)) / area;
      worst_cover = std::min(worst_cover, cover);
      worst_outside = std::max(worst_outside, outside);
      worst_overlap = std::max(worst_overlap, overlap);
    }
  }
  CHECK(with_beads > 100);
  MESSAGE("worst: cover " << worst_cover << ", outside " << worst_outside << ", overlap " << worst_overlap);
  // Measured: cover 0.86 (a blob 0.75 mm wide and 1.8 long between two loops: its short axis
  // leaves the corners), outside 0.034, overlap 0.26 (variable walls: beads of a changing count
  // and of three arms meeting at a star's centre).
  CHECK(worst_cover > 0.85);
  CHECK(worst_outside < 0.05);
  CHECK(worst_overlap < 0.3);
}

TEST_CASE("gap fill: uncovered counts overlapping covered areas listed side by side as their union") {
  // The loops' reach and the fill's overlap; make_perimeters lists them without uniting them
  // first. A 10 × 4 mm island, two overlapping bars and a disc-like square crossing both.
  const geo::Rings island{test::rect(0, 0, 10, 4)};
  const geo::Rings a{test::rect(-1, -1, 6, 2.5)}, b{test::rect(4, 1, 11, 5)}, c{test::rect(2, 0.5, 8, 3.5)};
  geo::Rings side_by_side = a;
  side_by_side.insert(side_by_side.end(), b.begin(), b.end());
  side_by_side.insert(side_by_side.end(), c.begin(), c.end());
  const geo::Rings united = union_of(union_of(a, b), c);
  const geo::Rings got = uncovered(island, side_by_side, 0.1), want = uncovered(island, united, 0.1);
  CHECK(area_mm2(want) == Approx(2 * 1.5 + 4 * 1).epsilon(1e-3));  // what the test looks at is there
  CHECK(area_mm2(got) == Approx(area_mm2(want)).epsilon(1e-9));
  CHECK(area_mm2(difference(got, want)) < 1e-9);
  CHECK(area_mm2(difference(want, got)) < 1e-9);
}
