#include <doctest/doctest.h>

#include <algorithm>

#include "tests/geometry/support/project_input.h"
#include "tests/geometry/toolpath/fixtures.h"
#include "geometry/support/support.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/relations.h"

using namespace tranche;
using namespace tranche::support;
using doctest::Approx;
using test::rect;

namespace {

// A mushroom: a 4 mm stem (layers 0..9) under a 12 mm cap (layers 10..14), 0.2 mm layers.
std::vector<geo::Layer> mushroom() { return test::mushroom_stack(10, 5, rect(4, 4, 8, 8), rect(0, 0, 12, 12)); }

geo::Rings cap_overhang() { return toolpath::difference({rect(0, 0, 12, 12)}, toolpath::offset({rect(4, 4, 8, 8)}, 0.2)); }


double area(const geo::Rings& r) { return toolpath::area_mm2(r); }

}  // namespace

TEST_CASE("support: a column under a mushroom's cap, down to the bed, interface at its top") {
  auto layers = mushroom();
  ProjectInput in = test::project_input(layers);
  in.contacts[8].push_back({cap_overhang(), 2, false});  // layer 10's overhang, one layer of air below it
  ProjectResult r = project(in);
  REQUIRE(r.layers.size() == 15);
  for (size_t k = 9; k < 15; ++k) CHECK(r.layers[k].area_mm2 == 0);  // the z gap, and the cap itself
  // Interface on layers 7 and 8, base below.
  CHECK(area(r.layers[8].interface) > 100);
  CHECK(area(r.layers[7].interface) > 100);
  CHECK(r.layers[8].base.empty());
  CHECK(r.layers[6].interface.empty());
  CHECK(area(r.layers[0].base) > 100);
  // The column: the cap's footprint less the stem grown by the xy gap (5 x 5 mm).
  CHECK(r.layers[0].area_mm2 == Approx(144 - 25).epsilon(0.01));
  // Never within the xy gap of the part.
  for (const auto& s : r.layers)
    CHECK(area(toolpath::intersection(s.base, toolpath::offset({rect(4, 4, 8, 8)}, 0.49))) < 1e-6);
  CHECK(r.off_bed_mm2 == 0);
  CHECK(r.blocked_mm2 == 0);
}

TEST_CASE("support: a column stands on the part's top with a gap, or not at all on bed only") {
  // A 10 mm block (layers 0..4), air above its right half up to a shelf at layers 10..12.
  auto layers = test::stack(13, 0.2, geo::Polygon{rect(0, 0, 10, 10), {}});
  for (size_t k = 5; k < 10; ++k) layers[k].islands[0].shape.outer = rect(0, 0, 5, 10);
  for (size_t k = 10; k < 13; ++k) layers[k].islands[0].shape.outer = rect(0, 0, 10, 10);
  geo::Rings shelf = toolpath::difference({rect(0, 0, 10, 10)}, toolpath::offset({rect(0, 0, 5, 10)}, 0.2));
  {
    ProjectInput in = test::project_input(layers);
    in.contacts[8].push_back({shelf, 2, false});
    ProjectResult r = project(in);
    CHECK(r.layers[8].area_mm2 > 10);
    CHECK(r.layers[6].area_mm2 > 10);
    CHECK(r.layers[5].area_mm2 == 0);  // right on the block's top: the bottom gap
    for (size_t k = 0; k < 5; ++k) CHECK(r.layers[k].area_mm2 == 0);  // inside the block: none
  }
  {
    ProjectInput in = test::project_input(layers);
    in.contacts[8].push_back({shelf, 2, true});
    ProjectResult r = project(in);
    for (const auto& s : r.layers) CHECK(s.area_mm2 == 0);
    CHECK(r.blocked_mm2 == Approx(area(shelf)).epsilon(1e-3));
  }
}

TEST_CASE("support: nothing under the part of the layer right above, but under a contact that touches it") {
  // A 0.6 mm speck of the part on layer 9, too small to be an overhang of its own, inside the
  // cap's overhang: layer 8, where the cap's contact is placed, leaves it air (it was printed
  // under it, the speck lying on the support); layer 7 does not.
  auto layers = mushroom();
  layers[9].islands.push_back(geo::Island{geo::Polygon{rect(1, 1, 1.6, 1.6), {}}});
  ProjectInput in = test::project_input(layers);
  in.contacts[8].push_back({cap_overhang(), 2, false});
  ProjectResult r = project(in);
  const geo::Rings speck{rect(1, 1, 1.6, 1.6)};
  auto under = [&](const ProjectResult& p, size_t k) {
    return area(toolpath::intersection(toolpath::union_of(p.layers[k].base, p.layers[k].interface), speck));
  };
  CHECK(under(r, 8) < 1e-9);
  CHECK(under(r, 7) == Approx(0.36).epsilon(0.01));
  CHECK(area(r.layers[8].interface) > 100);
  // A contact with no gap (support_z_gap 0) holds the layer right above it: the cap on layer 10,
  // touched from layer 9 (less layer 9's keep-out: the stem and the speck grown by the xy gap).
  ProjectInput touching = test::project_input(layers);
  touching.contacts[9].push_back({cap_overhang(), 2, false, true});
  CHECK(area(project(touching).layers[9].interface) ==
        Approx(area(toolpath::difference(cap_overhang(), touching.keep_out[9]))).epsilon(0.01));
  ProjectInput gap = test::project_input(layers);
  gap.contacts[9].push_back({cap_overhang(), 2, false, false});  // the same, not said to touch: the cap cuts it
  CHECK(area(project(gap).layers[9].interface) < 1e-9);
}

TEST_CASE("support: off the bed it is cut, and said") {
  auto layers = mushroom();
  ProjectInput in = test::project_input(layers);
  in.contacts[8].push_back({cap_overhang(), 2, false});
  in.bed = bed_region(false, 0, 0, 6, 200, geo::Point(0, 0));  // a bed ending at x = 6 mm
  ProjectResult r = project(in);
  CHECK(r.off_bed_mm2 > 50);  // the cap's overhang beyond x = 6: about 6 x 12 mm less the stem's gap
  for (const auto& s : r.layers) {
    for (const auto* rs : {&s.base, &s.interface})
      for (const auto& ring : *rs)
        for (const auto& p : ring) CHECK(geo::to_mm(p.X) <= 6.0 + 1e-6);
  }
}

TEST_CASE("support: bed_region in model units, rectangle and circle") {
  auto rect_bed = bed_region(false, 0, 0, 200, 100, geo::to_point(100, 50));
  CHECK(toolpath::area_mm2(rect_bed) == Approx(20000));
  CHECK(geo::to_mm(toolpath::bbox(rect_bed).min_x) == Approx(-100));
  auto round = bed_region(true, -100, -100, 100, 100, geo::Point(0, 0));
  CHECK(toolpath::area_mm2(round) == Approx(3.14159 * 100 * 100).epsilon(0.002));
}

namespace {

// project() as it was before its column loop was made cheaper (one union, one difference with
// every ring of the column, the whole column clipped to the bed at each contact; the keep-out and
// the bottom gap cut one after the other), kept here as the reference its results must equal.
// Rings start at their lowest vertex before the print simplification, as project() does.
ProjectResult reference_project(const ProjectInput& in) {
  const size_t n = in.layers.size();
  std::vector<geo::Rings> material(n);
  for (size_t k = 0; k < n; ++k) material[k] = toolpath::material(in.layers[k]);
  std::vector<geo::Rings> foot(n);
  geo::Rings acc;
  for (size_t k = 0; k < n; ++k) foot[k] = acc = toolpath::simplify(toolpath::union_of(acc, material[k]), 12500);
  ProjectResult res;
  res.layers.resize(n);
  std::vector<geo::Rings> iface_src(n), columns(n), touch(n);
  geo::Rings column;
  for (size_t k = n; k-- > 0;) {
    bool added = false;
    for (const Contact& c : in.contacts[k]) {
      geo::Rings r = toolpath::simplify(c.region, 12500);
      if (c.bed_only) {
        geo::Rings kept = toolpath::difference(r, foot[k]);
        res.blocked_mm2 += std::max(0.0, area(r) - area(kept));
        r = kept;
      }
      if (r.empty()) continue;
      if (c.touching) touch[k].insert(touch[k].end(), r.begin(), r.end());
      if (in.columns) column.insert(column.end(), r.begin(), r.end()), added = true;
      for (int j = 0; j < c.interface_layers && static_cast<int>(k) - j >= 0; ++j)
        iface_src[k - size_t(j)].insert(iface_src[k - size_t(j)].end(), r.begin(), r.end());
    }
    if (!in.columns) column = iface_src[k], added = true;
    if (column.empty()) continue;
    if (added) column = toolpath::union_of(column);
    if (geo::Rings part = toolpath::near(material[k], toolpath::bbox(column)); !part.empty())
      column = toolpath::difference(column, part);
    if (added && !in.bed.empty()) {
      geo::Rings on = toolpath::intersection(column, in.bed);
      res.off_bed_mm2 += std::max(0.0, area(column) - area(on));
      column = on;
    }
    columns[k] = column;
  }
  const double w = in.min_width_mm, speck = w * w * geo::kUnitsPerMm * geo::kUnitsPerMm;
  auto drop = [&](geo::Rings r) {
    std::erase_if(r, [&](const geo::Ring& x) { return std::abs(ClipperLib::Area(x)) < speck; });
    return r;
  };
  for (size_t k = 0; k < n; ++k) {
    if (columns[k].empty()) continue;
    geo::Rings col = columns[k];
    for (geo::Ring& ring : col)
      std::rotate(ring.begin(), std::min_element(ring.begin(), ring.end(), [](const geo::Point& a, const geo::Point& b) {
                    return a.Y != b.Y ? a.Y < b.Y : a.X < b.X;
                  }), ring.end());
    const geo::BBox2 box = toolpath::bbox(columns[k]);
    const geo::Rings& keep = !in.keep_out[k].empty() ? in.keep_out[k] : material[k];
    geo::Rings printed = toolpath::difference(toolpath::simplify(col, 50000), toolpath::near(keep, box));
    for (int g = 1; g <= in.bottom_gap_layers && static_cast<int>(k) - g >= 0; ++g)
      printed = toolpath::difference(printed, toolpath::near(material[k - size_t(g)], box));
    if (k + 1 < n)  // nor under the part right above, but where a contact touches it
      printed = toolpath::difference(printed, toolpath::difference(toolpath::near(material[k + 1], box), touch[k]));
    geo::Rings iface;
    if (!iface_src[k].empty()) {
      const double m = 0.5 * in.merge_mm;
      iface = toolpath::intersection(
          printed, toolpath::offset_coarse(toolpath::offset_coarse(toolpath::union_of(iface_src[k]), m), -m));
    }
    SupportLayer& out = res.layers[k];
    out.interface = drop(iface);
    out.base = drop(toolpath::difference(printed, toolpath::offset_coarse(out.interface, 1.2 * 0.05)));
    out.area_mm2 = area(out.base) + area(out.interface);
  }
  return res;
}

double xor_area(const geo::Rings& a, const geo::Rings& b) {
  return area(toolpath::difference(a, b)) + area(toolpath::difference(b, a));
}

void check_same(const ProjectInput& in) {
  const ProjectResult got = project(in), want = reference_project(in);
  REQUIRE(got.layers.size() == want.layers.size());
  double total = 0;
  for (size_t k = 0; k < got.layers.size(); ++k) {
    CAPTURE(k);
    CHECK(xor_area(got.layers[k].base, want.layers[k].base) < 1e-9);
    CHECK(xor_area(got.layers[k].interface, want.layers[k].interface) < 1e-9);
    CHECK(got.layers[k].area_mm2 == Approx(want.layers[k].area_mm2).epsilon(1e-9));
    total += want.layers[k].area_mm2;
  }
  CHECK(total > 0);  // the fixture has support to compare
  CHECK(got.off_bed_mm2 == Approx(want.off_bed_mm2).epsilon(1e-6));
  CHECK(got.blocked_mm2 == Approx(want.blocked_mm2).epsilon(1e-6));
}


}  // namespace

TEST_CASE("support: the columns' loop gives the regions of the plain one (union, cut, bed clip at every layer)") {
  SUBCASE("mushroom, on the bed and off its edge") {
    auto layers = mushroom();
    ProjectInput in = test::project_input(layers);
    in.contacts[8].push_back({cap_overhang(), 2, false});
    check_same(in);
    in.bed = bed_region(false, 0, 0, 6, 200, geo::Point(0, 0));  // a bed ending at x = 6 mm: cut
    check_same(in);
    in.bed = bed_region(true, -50, -50, 50, 50, geo::Point(0, 0));  // a round bed holding it all
    check_same(in);
  }
  SUBCASE("round cap on a round stem, two contacts on different layers, a bottom gap") {
    // A 3 mm stem (layers 0..9), a 10 mm disc (10..12), a 16 mm ring round a 6 mm hole (15..17).
    auto layers = test::stack(18, 0.2, geo::Polygon{test::circle(0, 0, 1.5, 90), {}});
    for (size_t k = 10; k < 13; ++k) layers[k].islands[0].shape.outer = test::circle(0, 0, 5, 90);
    for (size_t k = 13; k < 15; ++k) layers[k].islands[0].shape.outer = test::circle(0, 0, 1.5, 90);
    for (size_t k = 15; k < 18; ++k) layers[k].islands[0].shape = geo::Polygon{test::circle(0.3, 0.1, 8, 90), {test::circle(0.3, 0.1, 3, 60)}};
    ProjectInput in = test::project_input(layers);
    in.contacts[8].push_back({toolpath::difference({test::circle(0, 0, 5, 90)}, toolpath::offset({test::circle(0, 0, 1.5, 90)}, 0.2)), 2, false});
    in.contacts[13].push_back(
        {toolpath::difference(toolpath::difference({test::circle(0.3, 0.1, 8, 90)}, {test::circle(0.3, 0.1, 3, 60)}), {test::circle(0, 0, 1.7, 90)}), 3,
         false});
    in.bottom_gap_layers = 1;
    in.bed = bed_region(false, -100, -100, 100, 100, geo::Point(0, 0));
    check_same(in);
    in.contacts[13].back().bed_only = true;  // the ring stands over the disc: cut where it lies above it
    check_same(in);
    in.columns = false;  // the interfaces alone (tree support)
    check_same(in);
  }
  SUBCASE("a column the print simplification makes cross itself, next to one the part cuts") {
    // Column A's left side bulges out by 40 µm, less than the 50 µm simplification, round the tip
    // of a hole 20 µm inside it: simplified, the tip sticks out of the side. Only column B meets
    // the part; A is set aside, and the print's boolean must still clean it.
    auto layers = test::stack(6, 0.2, geo::Polygon{rect(28, 4, 33, 8), {}});
    ProjectInput in = test::project_input(layers);
    const geo::Ring a = {geo::to_point(0, 0), geo::to_point(10, 0), geo::to_point(10, 12), geo::to_point(0, 12),
                         geo::to_point(-0.04, 6)};
    const geo::Ring tip = {geo::to_point(-0.02, 6), geo::to_point(1, 7), geo::to_point(1, 5)};
    in.contacts[5].push_back({{a, tip, rect(20, 0, 30, 12)}, 2, false});
    const geo::Rings simplified = toolpath::simplify(geo::Rings{a, tip}, 50000);
    REQUIRE(simplified.size() == 2);
    REQUIRE(simplified[0].size() == 4);  // the bulge is gone, the tip is not
    REQUIRE(!toolpath::is_clean_region(simplified));
    check_same(in);
  }
}

namespace {

// A random region as a boolean leaves it: a few discs and boxes, less smaller discs (holes),
// with islands back inside some holes; within the square [0, 20] mm.
geo::Rings random_region(test::Lcg& rnd, int most) {
  geo::Rings add, cut, back;
  const int n = 1 + static_cast<int>(rnd() * most);
  for (int i = 0; i < n; ++i) {
    const double x = 20 * rnd(), y = 20 * rnd(), r = 0.3 + 5 * rnd();
    add.push_back(rnd() < 0.5 ? test::circle(x, y, r, 7 + static_cast<int>(40 * rnd())) : rect(x - r, y - r, x + r, y + r * (0.2 + rnd())));
  }
  for (int i = 0; i < static_cast<int>(rnd() * 4); ++i) {
    const double x = 20 * rnd(), y = 20 * rnd(), r = 0.5 + 2 * rnd();
    cut.push_back(test::circle(x, y, r, 24));
    if (rnd() < 0.5) back.push_back(test::circle(x, y, 0.4 * r, 12));
  }
  return toolpath::union_of(toolpath::difference(toolpath::union_of(add), cut), back);
}

// Signed area of the rings as they are (a ring counted twice, or a hole outside its outer, shows).
double ring_area(const geo::Rings& r) {
  double a = 0;
  for (const geo::Ring& ring : r) a += ClipperLib::Area(ring);
  return a * geo::kMmPerUnit * geo::kMmPerUnit;
}

// How many rings of `got` are rings of `a` as they were (set aside: a boolean would have started
// them elsewhere or dropped a vertex).
size_t kept_as_is(const geo::Rings& got, const geo::Rings& a) {
  size_t n = 0;
  for (const geo::Ring& g : got) n += std::find(a.begin(), a.end(), g) != a.end();
  return n;
}

}  // namespace

TEST_CASE("support: difference_local, intersection_local and union_local give the plain booleans' regions") {
  // Clipper finds crossings at the heights of every vertex it is given, so the rings set aside
  // move its roundings of the others by a nanometre here and there: a sliver of 1 nm along 10 mm.
  constexpr double kRounding = 1e-5;  // mm²
  test::Lcg rnd{12};
  size_t cases = 0, mixed = 0;
  for (int trial = 0; trial < 400; ++trial) {
    CAPTURE(trial);
    const geo::Rings a = random_region(rnd, 6);
    geo::Rings b = random_region(rnd, 3);
    // The union's second operand: several regions laid over each other (contacts).
    geo::Rings many = b;
    for (int j = 0; j < 3; ++j) {
      geo::Rings more = random_region(rnd, 2);
      many.insert(many.end(), more.begin(), more.end());
    }
    if (a.empty() || b.empty()) continue;
    ++cases;
    const geo::Rings diff = difference_local(a, b), want_diff = toolpath::difference(a, b);
    const geo::Rings meet = intersection_local(a, b), want_meet = toolpath::intersection(a, b);
    const geo::Rings uni = union_local(a, many), want_uni = toolpath::union_of(a, many);
    // The columns' step: the contacts added and the part cut in one boolean.
    const geo::Rings part = random_region(rnd, 2);
    const geo::Rings step = union_difference_local(a, many, part), want_step = toolpath::difference(want_uni, part);
    CHECK(xor_area(step, want_step) < kRounding);
    CHECK(ring_area(step) == Approx(area(want_step)).epsilon(1e-7));
    CHECK(xor_area(diff, want_diff) < kRounding);
    CHECK(xor_area(meet, want_meet) < kRounding);
    CHECK(xor_area(uni, want_uni) < kRounding);
    CHECK(ring_area(diff) == Approx(area(want_diff)).epsilon(1e-7));
    CHECK(ring_area(meet) == Approx(area(want_meet)).epsilon(1e-7));
    CHECK(ring_area(uni) == Approx(area(want_uni)).epsilon(1e-7));
    // The results are regions as a boolean leaves them: the next boolean can take them so.
    CHECK(xor_area(difference_local(uni, b), toolpath::difference(uni, b)) < kRounding);
    CHECK(ring_area(difference_local(uni, b)) == Approx(area(toolpath::difference(uni, b))).epsilon(1e-7));
    const size_t kept = kept_as_is(diff, a);
    mixed += kept > 0 && kept < diff.size();
  }
  CHECK(cases > 300);
  CHECK(mixed > 50);  // rings set aside next to rings cut, not only one or the other
}

TEST_CASE("support: the local booleans on rings that touch, and on rings in each other's holes") {
  const geo::Rings two = {rect(0, 0, 10, 10), rect(20, 0, 30, 10)};
  SUBCASE("b touches both squares along an edge: nothing is cut") {
    const geo::Rings b = {rect(10, 2, 20, 8)};
    CHECK(xor_area(difference_local(two, b), two) < 1e-12);
    CHECK(area(intersection_local(two, b)) == Approx(0));
    CHECK(area(union_local(two, b)) == Approx(260));
    CHECK(ring_area(union_local(two, b)) == Approx(260));
  }
  SUBCASE("b in a hole of a, and a square of a in a hole of b") {
    const geo::Rings framed = toolpath::difference({rect(-5, -5, 15, 15)}, {rect(-2, -2, 12, 12)});
    const geo::Rings a = toolpath::union_of(framed, {rect(40, 0, 50, 10)});
    const geo::Rings b = toolpath::difference({rect(35, -5, 55, 15)}, {rect(38, -2, 52, 12)});
    CHECK(xor_area(difference_local(a, {rect(2, 2, 8, 8)}), a) < 1e-12);
    CHECK(xor_area(difference_local(a, b), a) < 1e-12);
    CHECK(area(intersection_local(a, b)) == Approx(0));
    CHECK(ring_area(union_local(a, b)) == Approx(area(a) + area(b)));
    // b covering the square of a whole, and a's hole holding b whole.
    CHECK(area(difference_local(a, {rect(39, -1, 51, 11)})) == Approx(area(framed)));
    CHECK(ring_area(union_local(a, {rect(1, 1, 9, 9)})) == Approx(area(a) + 64));
  }
}
