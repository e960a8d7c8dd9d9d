// toolpath::offset against the exact offset (exact_region.h), on shapes where the trimmed curve
// gives up and the union cleans the curve built with detours: stars whose tips carry hairline
// loops and returns, combs with teeth and gaps down to a micrometre, outlines with µm edges,
// self-touching rings, plates with star-shaped holes. ClipperOffset is run beside it to say where
// the two disagree and which is right.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <numbers>
#include <sstream>
#include <string>

#include "exact_region.h"
#include "fixtures.h"
#include "geometry/toolpath/clip.h"

using namespace tranche;
using namespace tranche::toolpath;

namespace {

geo::Point pt(double x, double y) { return geo::Point(geo::to_units(x), geo::to_units(y)); }

geo::Rings clipper_offset(const geo::Rings& region, double mm) {
  geo::Rings out;
  ClipperLib::ClipperOffset co(2.0, 5000);
  co.AddPaths(region, ClipperLib::jtRound, ClipperLib::etClosedPolygon);
  co.Execute(out, mm * geo::kUnitsPerMm);
  return out;
}

// Sample points over the offset's box and in a disc round every vertex of the region (where the
// joins are), judged against the exact offset. The band: both offsets' arcs are chords of up to
// 1.5 steps of the arc tolerance (5 µm), which cut in by up to 2.25 times it (the step count
// rounded), and grown inputs move by 1 µm.
test::OffsetCheck judge(const test::ExactRegion& exact, const geo::Rings& region, const geo::Rings& computed,
                        double mm, int grid = 4096, int per_vertex = 6) {
  constexpr double band = 0.0125;
  geo::BBox2 box = bbox(region);
  const geo::coord_t grow = geo::to_units(std::max(mm, 0.0) + 0.05);
  box.min_x -= grow, box.min_y -= grow, box.max_x += grow, box.max_y += grow;
  test::OffsetCheck c = test::check_offset(exact, computed, mm, box, grid, 99, band);
  test::Lcg rnd{7};
  const double reach = (std::abs(mm) + 0.03) * geo::kUnitsPerMm;
  for (const auto& r : region)
    for (const auto& v : r)
      for (int k = 0; k < per_vertex; ++k) {
        const double a = 2 * std::numbers::pi * rnd(), rr = reach * std::sqrt(rnd());
        const double x = std::floor(double(v.X) + rr * std::cos(a)) + 0.5;
        const double y = std::floor(double(v.Y) + rr * std::sin(a)) + 0.5;
        bool clear = false;
        const bool want = exact.in_offset(x, y, mm * geo::kUnitsPerMm, band * geo::kUnitsPerMm, clear);
        if (!clear) continue;
        ++c.decided;
        const bool got = test::ExactRegion::winding_in(computed, x, y) != 0;
        if (want && !got) ++c.missing;
        if (got && !want) ++c.extra;
      }
  return c;
}

// A star of `m` points; its tips (every `every`-th) carry `tip` (0 none, 1 a hairline loop
// turning the region's way, 2 one turning the other way, 3 a return of no width, 4 a return
// `w` wide at its end, 5 one back to `w` beside the tip), `len` long.
geo::Ring star(int m, double r0, double r1, int every, int tip, double len, double w) {
  geo::Ring s;
  for (int i = 0; i < 2 * m; ++i) {
    const double t = std::numbers::pi * i / m, rr = i % 2 ? r1 : r0;
    const geo::Point v = pt(rr * std::cos(t), rr * std::sin(t));
    s.push_back(v);
    if (i % 2 || (i / 2) % every || tip == 0) continue;
    // Along the tip's direction, slightly off it.
    const double c = std::cos(t + 0.3), sn = std::sin(t + 0.3);
    const double nx = -sn, ny = c;
    auto at = [&](double along, double side) {
      return geo::Point(v.X + geo::to_units(along * c + side * nx), v.Y + geo::to_units(along * sn + side * ny));
    };
    switch (tip) {
      case 1:  // a small triangle from the tip, counter-clockwise
        s.push_back(at(len, -0.4 * len));
        s.push_back(at(len, 0.4 * len));
        s.push_back(v);
        break;
      case 2:
        s.push_back(at(len, 0.4 * len));
        s.push_back(at(len, -0.4 * len));
        s.push_back(v);
        break;
      case 3:
        s.push_back(at(len, 0));
        s.push_back(v);
        break;
      case 4:
        s.push_back(at(len, 0));
        s.push_back(at(len, w));
        break;
      case 5:  // out and back to `w` beside the tip
        s.push_back(at(len, 0));
        s.push_back(at(0, w));
        break;
    }
  }
  return s;
}

geo::Ring comb(int teeth, double w, double g, double depth) {
  geo::Ring c{pt(0, 0)};
  double x = 0;
  for (int i = 0; i < teeth; ++i) {
    c.push_back(pt(x, depth + 2));
    c.push_back(pt(x + w, depth + 2));
    c.push_back(pt(x + w, 2));
    c.push_back(pt(x + w + g, 2));
    x += w + g;
  }
  c.push_back(pt(x, depth + 2));
  c.push_back(pt(x + w, depth + 2));
  c.push_back(pt(x + w, 0));
  return c;
}

struct Case {
  std::string kind;
  geo::Rings region;
  // Outside what offset() is given (what a union gives), listed but not judged:
  // - a loop turning against its ring's way (a hole touching the outline from outside, winding
  //   -1): both offsets' curves go round its vertex the wrong way and lose area there, read under
  //   non-zero fill or positive;
  // - a slit of no width between edges that are not consecutive (a keyhole's): no point of the
  //   region lies beside it on either side, so the exact offset has no slit; both offsets take
  //   its edges as the border (shrinking opens it into a channel).
  bool judged = true;
};

std::vector<Case> shapes(test::Lcg& rnd, int count) {
  std::vector<Case> out;
  for (int k = 0; k < count; ++k) {
    const int family = k % 7;
    if (family == 0 || family == 1) {
      const int tip = 1 + static_cast<int>(5 * rnd());
      const double len = std::pow(10, -3 + 2.5 * rnd());  // 1 µm .. 0.3 mm
      const double w = std::pow(10, -4 + 3 * rnd());      // 0.1 µm .. 0.1 mm
      const char* names[] = {"", "star tip loop", "star tip loop reversed", "star tip return", "star tip hairline",
                             "star tip hairline return"};
      out.push_back({names[tip], {star(5 + static_cast<int>(10 * rnd()), 2 + 6 * rnd(), 0.5 + 1.5 * rnd(),
                                       1 + static_cast<int>(3 * rnd()), tip, len, w)},
                     tip != 2});
    } else if (family == 2) {
      const double w = std::pow(10, -3 + 3.3 * rnd()), g = std::pow(10, -3 + 3.3 * rnd());
      out.push_back({"comb", {comb(3 + static_cast<int>(6 * rnd()), w, g, 0.5 + 5 * rnd())}});
    } else if (family == 3) {  // a blob with µm edges: vertices in pairs a few µm apart, jittered
      geo::Ring b;
      const int n = 20 + static_cast<int>(200 * rnd());
      const double r = 1 + 8 * rnd();
      for (int i = 0; i < n; ++i) {
        const double t = 2 * std::numbers::pi * i / n, rr = r * (1 + 0.2 * std::sin(3 * t));
        const geo::Point v = pt(rr * std::cos(t), rr * std::sin(t));
        b.push_back(v);
        if (rnd() < 0.5) {
          const double jx = (rnd() - 0.5) * 0.004, jy = (rnd() - 0.5) * 0.004;
          b.push_back(geo::Point(v.X + geo::to_units(jx), v.Y + geo::to_units(jy)));
        }
      }
      out.push_back({"um edges", toolpath::union_of({b})});
    } else if (family == 4) {  // rings touching themselves: two squares meeting at a corner or along a side
      const double s = 1 + 5 * rnd(), e = std::pow(10, -3 + 3 * rnd());
      geo::Ring eight{pt(0, 0), pt(s, 0), pt(s, s), pt(2 * s, s), pt(2 * s, 2 * s), pt(s, 2 * s), pt(s, s), pt(0, s)};
      if (rnd() < 0.5) {  // a keyhole: the outline runs into a hole along a slit of no width
        eight = {pt(0, 0), pt(3 * s, 0), pt(3 * s, 3 * s), pt(1.5 * s, 3 * s), pt(1.5 * s, 2 * s), pt(2 * s, 2 * s),
                 pt(2 * s, s), pt(s, s), pt(s, 2 * s), pt(1.5 * s, 2 * s), pt(1.5 * s, 3 * s), pt(0, 3 * s)};
        if (rnd() < 0.5) {  // the slit widening to e where it meets the hole
          eight[4].X += geo::to_units(e), eight[9].X -= geo::to_units(e);
          out.push_back({"keyhole", {eight}});
        } else {
          out.push_back({"keyhole, slit of no width", {eight}, false});
        }
      } else {
        out.push_back({"touching", {eight}});
      }
    } else if (family == 5) {  // a plate with star-shaped holes whose tips carry hairlines (grown, they close)
      geo::Rings plate{test::rect(-12, -12, 12, 12)};
      const int holes = 1 + static_cast<int>(3 * rnd());
      for (int h = 0; h < holes; ++h) {
        const int tips[] = {1, 3, 4, 5};  // not 2: reversed, its loop would turn the plate's way
        const int m = 4 + static_cast<int>(6 * rnd());
        const double r0 = 1 + 3 * rnd(), r1 = 0.2 + 0.8 * rnd();
        const int tip = tips[static_cast<int>(4 * rnd())];
        const double len = std::pow(10, -3 + 2.5 * rnd()), w = std::pow(10, -4 + 3 * rnd());
        geo::Ring hole = star(m, r0, r1, 1, tip, len, w);
        const geo::Point at = pt(-6 + 12 * (h % 2), -6 + 12 * (h / 2));
        for (auto& q : hole) q.X += at.X, q.Y += at.Y;
        ClipperLib::ReversePath(hole);
        plate.push_back(hole);
      }
      out.push_back({"plate with star holes", plate});
    } else {  // random polygons, united (self-crossings become touching rings)
      geo::Ring r;
      const int m = 5 + static_cast<int>(20 * rnd());
      for (int i = 0; i < m; ++i) r.push_back(pt(20 * rnd(), 20 * rnd()));
      out.push_back({"random united", toolpath::union_of({r})});
    }
  }
  return out;
}

int sweep_size() {
  const char* s = std::getenv("TRANCHE_OFFSET_SWEEP");
  return s ? std::max(1, std::atoi(s)) : 120;
}

// A ring written as "x,y x,y ..." in model units.
geo::Ring ring_of(const char* txt) {
  geo::Ring ring;
  std::istringstream in(txt);
  long long x = 0, y = 0;
  char comma = 0;
  while (in >> x >> comma >> y) ring.emplace_back(x, y);
  return ring;
}

}  // namespace

TEST_CASE("exact region: the sampler's own answers on shapes whose offsets are known") {
  // A square 10 mm: grown by 1 its area is 100 + 40 + π, shrunk by 1 it is 64.
  const geo::Rings sq{test::rect(0, 0, 10, 10)};
  const test::ExactRegion ex(sq);
  CHECK(ex.boundary_pieces() == 4);
  bool clear = false;
  CHECK(ex.in_offset(10.5e6, 5e6, 1e6, 8e3, clear));
  CHECK(clear);
  CHECK_FALSE(ex.in_offset(10.9e6 + 5e4, 10.9e6, 1e6, 8e3, clear));  // beyond the corner's arc
  CHECK(clear);
  CHECK_FALSE(ex.in_offset(0.5e6, 5e6, -1e6, 8e3, clear));
  CHECK(ex.in_offset(1.5e6, 5e6, -1e6, 8e3, clear));
  // A square offset by hand with round corners agrees at every decided sample; one 0.3 mm too
  // small does not.
  geo::Rings grown{{}};
  for (int i = 0; i < 400; ++i) {
    const double t = 2 * std::numbers::pi * i / 400;
    const double cx = std::cos(t) >= 0 ? 10 : 0, cy = std::sin(t) >= 0 ? 10 : 0;
    grown[0].push_back(pt(cx + std::cos(t), cy + std::sin(t)));
  }
  CHECK(judge(ex, sq, grown, 1.0).wrong_mm2() == 0);
  CHECK(judge(ex, sq, offset(grown, -0.3), 1.0).missing > 100);
  // A spike of no width (out and back along itself) is no part of the region; a loop 20 µm
  // across at the end of one is.
  const geo::Rings spike{{pt(0, 0), pt(4, 0), pt(4, 4), pt(2, 4), pt(2, 6), pt(2, 4), pt(0, 4)}};
  const test::ExactRegion sp(spike);
  CHECK_FALSE(sp.in_offset(2e6, 5.5e6, 1e6, 8e3, clear));
  CHECK(clear);
  const geo::Rings loop{{pt(0, 0), pt(4, 0), pt(4, 4), pt(2, 4), pt(2, 6), pt(2.02, 6.02), pt(1.98, 6.02), pt(2, 6),
                         pt(2, 4), pt(0, 4)}};
  const test::ExactRegion lp(loop);
  CHECK(lp.in_offset(2e6, 6.5e6, 1e6, 8e3, clear));
  CHECK(clear);
  CHECK_FALSE(lp.in_offset(2e6, 6.5e6, -1e6, 8e3, clear));
}

TEST_CASE("clip: offsets against the exact offset, on shapes that go through the union") {
  // TRANCHE_OFFSET_SWEEP=N offsets N shapes (14 distances each) and lists, by kind of shape,
  // where ours or ClipperOffset's is wrong.
  test::Lcg rnd{2024};
  const int n = sweep_size();
  const std::vector<Case> cases = shapes(rnd, n);
  struct Tally {
    int offsets = 0, united = 0, disagree = 0, ours_wrong = 0, theirs_wrong = 0;
    double ours_mm2 = 0, theirs_mm2 = 0;
  };
  std::map<std::string, Tally> tally;
  for (size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    const test::ExactRegion exact(c.region);
    for (double mm : {0.02, 0.05, 0.2, 0.45, 1.0, 1.5, 2.0}) {
      for (double d : {mm, -mm}) {
        bool as_built = false;
        const geo::Rings ours = offset(c.region, d, as_built);
        const geo::Rings theirs = clipper_offset(c.region, d);
        Tally& t = tally[c.kind + (d > 0 ? ", grown" : ", shrunk")];
        ++t.offsets;
        t.united += !as_built;
        const geo::Rings diff = union_of(difference(ours, theirs), difference(theirs, ours));
        const bool disagree = area_mm2(offset_open(diff, -0.01, 0.01)) > 1e-6;
        t.disagree += disagree;
        const test::OffsetCheck o = judge(exact, c.region, ours, d);
        // Where the two agree (their difference opened by 10 µm is empty), ClipperOffset's is
        // judged as ours is.
        const test::OffsetCheck th = disagree ? judge(exact, c.region, theirs, d) : o;
        if (o.missing + o.extra > 0) ++t.ours_wrong, t.ours_mm2 = std::max(t.ours_mm2, o.wrong_mm2());
        if (th.missing + th.extra > 0) ++t.theirs_wrong, t.theirs_mm2 = std::max(t.theirs_mm2, th.wrong_mm2());
        const std::string how = as_built ? " as built" : " united";
        INFO("shape " << k << " (" << c.kind << ") offset " << d << how << ": ours "
                      << area_mm2(ours) << " mm², " << o.missing << " missing and " << o.extra << " extra of "
                      << o.decided << " samples; ClipperOffset " << area_mm2(theirs) << " mm², " << th.missing
                      << " missing, " << th.extra << " extra");
        if (!c.judged) continue;
        CHECK(o.missing == 0);
        CHECK(o.extra == 0);
      }
    }
  }
  std::ostringstream table;
  table << "kind | offsets | united | disagree | ours wrong (worst mm²) | ClipperOffset wrong (worst mm²)\n";
  for (const auto& [kind, t] : tally)
    table << kind << " | " << t.offsets << " | " << t.united << " | " << t.disagree << " | " << t.ours_wrong << " ("
          << t.ours_mm2 << ") | " << t.theirs_wrong << " (" << t.theirs_mm2 << ")\n";
  MESSAGE(table.str());
}

TEST_CASE("clip: a tip carrying a hairline of a few µm grows with its whole round cap") {
  // A triangle's tip goes on 3 µm and back, 7.5° off its incoming edge: the tip's first vertex
  // lies 0.4 µm off the chord to the hairline's end. The input's simplification (0.5 µm) dropped it,
  // the ring crossed itself at the tip, turning round it clockwise, and the curve built with
  // detours had no cap there: grown by 1.5 mm, 3 mm² short (ClipperOffset, which does not
  // simplify, was right).
  const geo::Point tip = pt(2, 10);
  const double len = std::hypot(2.0, 10.0), a = std::atan2(10.0, -2.0) + 0.13;  // the incoming edge, turned
  const geo::Point end(tip.X + geo::to_units(0.003 * std::cos(a)), tip.Y + geo::to_units(0.003 * std::sin(a)));
  // Back to 0.1 µm beside the tip: a hairline, not a spike of no width (which is dropped first).
  const geo::Point back(tip.X - 100, tip.Y);
  const geo::Rings region{{pt(0, 0), pt(4, 0), tip, end, back}};
  const test::ExactRegion exact(region);
  for (double d : {0.45, 1.5, 2.0}) {
    INFO("grown by " << d);
    const geo::Rings ours = offset(region, d);
    const test::OffsetCheck c = judge(exact, region, ours, d, 16384, 24);
    CHECK(c.missing == 0);
    CHECK(c.extra == 0);
    // The triangle grown, give or take the spike (3 µm by 2d) and the arcs' chords.
    const double perimeter = 4 + 2 * len;
    const double grown = 20 + perimeter * d + std::numbers::pi * d * d;
    CHECK(std::abs(area_mm2(ours) - grown) < 0.003 * 2 * d + 2 * std::numbers::pi * d * 0.005);
  }
}

TEST_CASE("clip: a star's tip with a hairline loop, as a union left it, grown as the exact offset") {
  // The ring the stress run found 0.4 mm² short (grown by 1.5 mm): star tips with loops 20 µm
  // across touching them at a vertex, and spikes of a few µm.
  const char* txt =
      "992982,-3778325 1005700,-3759210 1343725,-3632420 1368878,-3583979 1410497,-3264161 2754075,-4388050 "
      "1194123,-1729470 1235774,-1720168 2708937,-3018056 2743324,-2976938 2400219,-2273518 4625386,-3278883 "
      "2856191,-1609693 4969553,-2061482 1587896,-386484 3194259,-557567 2487182,-212302 2512069,-199128 "
      "5987391,341435 2264202,459448 2297823,476928 5349719,1651502 3515666,1252258 2852019,1575690 "
      "1428371,958265 1445696,994325 3787465,3314777 1418879,1458013 2194223,2660117 1592889,2465829 "
      "1778091,3963755 1079088,3494309 1055166,4340446 1070857,4378005 1054519,4363343 1055166,4340446 "
      "443341,2875896 -208164,5836065 -269379,2338135 -827607,3671102 -1003850,3057380 -1696145,3761168 "
      "-1712826,3801412 -1724687,3790184 -1696145,3761168 -620147,1165303 -1725388,2526541 -1723177,2582840 "
      "-1763819,2573874 -1725388,2526541 -1747244,1969954 -2956486,2801095 -2951449,2848958 -2976900,2815126 "
      "-2956486,2801095 -3028974,2112358 -4386258,2276698 -1506578,615386 -3304372,797320 -1440064,267071 "
      "-3407120,120563 -1404162,-41788 -5833817,-1005256 -3265288,-844683 -3239812,-838455 -3594870,-1539486 "
      "-1815315,-1020236 -4491035,-3050093 -4537689,-3076409 -4553487,-3097471 -4491035,-3050093 "
      "-2629767,-2000234 -3279469,-3354007 -2344139,-3064636 -2595117,-3868696 -2595316,-3868965 "
      "-2601135,-3887976 -2595117,-3868696 -525067,-1072073 -481135,-1022352 -1314772,-4556239 "
      "-1003063,-3711635 -992838,-3686302 -715931,-4538020 36254,-2580053 757556,-5709608";
  const geo::Ring ring = ring_of(txt);
  REQUIRE(ring.size() == 86);
  const geo::Rings region{ring};
  const test::ExactRegion exact(region);
  for (double d : {0.45, 1.5, -0.2}) {
    INFO("offset " << d);
    const test::OffsetCheck c = judge(exact, region, offset(region, d), d, 16384, 24);
    CHECK(c.missing == 0);
    CHECK(c.extra == 0);
  }
}

TEST_CASE("clip: a spike of no width is no part of the region: not grown into a stadium, no channel when shrunk") {
  // Out along a line and back along it: no point beside it is in the region. ClipperOffset (and
  // our curve before) went round it, growing a stadium 1 mm long out of the square's side, and
  // shrinking opened one pointing in into a channel.
  const geo::Rings out{{pt(0, 0), pt(10, 0), pt(10, 5), pt(11, 5.2), pt(10.5, 5.1), pt(10, 5), pt(10, 10), pt(0, 10)}};
  const geo::Rings in{{pt(0, 0), pt(10, 0), pt(10, 5), pt(8, 5), pt(10, 5), pt(10, 10), pt(0, 10)}};
  for (const bool outwards : {true, false}) {
    const geo::Rings& region = outwards ? out : in;
    const test::ExactRegion exact(region);
    for (double d : {0.2, 0.45, -0.2, -0.45}) {
      const std::string where = outwards ? "out" : "in";
      INFO("spike " << where << ", offset " << d);
      const geo::Rings ours = offset(region, d);
      const test::OffsetCheck c = judge(exact, region, ours, d, 16384, 24);
      CHECK(c.missing == 0);
      CHECK(c.extra == 0);
      // The square's offset, to the arcs' chords (within 5 µm along the corners' arcs).
      const double sq = d > 0 ? 100 + 40 * d + std::numbers::pi * d * d : (10 + 2 * d) * (10 + 2 * d);
      CHECK(std::abs(area_mm2(ours) - sq) < 2 * std::numbers::pi * std::abs(d) * 0.005 + 1e-6);
    }
  }
}

TEST_CASE("clip: a star with arms narrower than twice the distance shrinks to nothing, no loop left") {
  // The sweep's shape: eleven arms 1.2 mm wide at their root, each tip carrying a flag 8 µm wide.
  // Shrunk by 1.5 mm nothing is left; the trimmed curve was simple and kept a triangle of 0.2 mm²
  // where none of its segments is on the offset (ClipperOffset was right). On the Stanford bunny
  // with concentric infill such loops were printed (a loop 2 mm across on layer 187).
  const char* txt =
      "6725061,0 6799948,23165 6797582,30812 574084,168566 5657481,3635842 5707956,3695817 5701831,3700971 "
      "391817,452180 2793691,6117331 2803728,6195073 2795789,6196098 85150,592230 -957076,6656610 -990663,6727438 "
      "-997896,6724008 -248551,544251 -4403978,5082462 -4470525,5123888 -4474756,5117092 -503339,323476 "
      "-6452649,1894669 -6531029,1893540 -6530913,1885536 -598320,0 -6452649,-1894669 -6517976,-1937994 "
      "-6513552,-1944665 -503339,-323476 -4403978,-5082462 -4435511,-5154228 -4428183,-5157448 -248551,-544251 "
      "-957076,-6656610 -944804,-6734031 -936898,-6732778 85150,-592230 2793691,-6117331 2845872,-6175827 "
      "2851845,-6170499 391817,-452180 5657481,-3635842 5733004,-3656841 5735148,-3649129 574084,-168566";
  const geo::Ring ring = ring_of(txt);
  REQUIRE(ring.size() == 44);
  const geo::Rings region{ring};
  const test::ExactRegion exact(region);
  for (double d : {-0.3, -0.6, -1.0, -1.5, -2.0}) {
    INFO("shrunk by " << -d);
    const geo::Rings ours = offset(region, d);
    const test::OffsetCheck c = judge(exact, region, ours, d, 16384, 24);
    CHECK(c.missing == 0);
    CHECK(c.extra == 0);
    if (d <= -1.0) CHECK(ours.empty());  // the arms meet 0.6 mm from the centre: nothing is 1 mm inside
  }
}
