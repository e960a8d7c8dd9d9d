// Convex hulls, arrangement on the bed, and the bed check's messages.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "geometry/plate/arrange.h"
#include "geometry/plate/bed.h"
#include "geometry/plate/hull.h"

using namespace tranche;
using namespace tranche::plate;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

Convex rect(double x0, double y0, double w, double h) { return {{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + h}, {x0, y0 + h}}; }

Convex polygon(Vec2 c, double r, int n, double phase = 0) {
  Convex p;
  for (int i = 0; i < n; ++i)
    p.push_back(c + r * Vec2(std::cos(phase + 2 * M_PI * i / n), std::sin(phase + 2 * M_PI * i / n)));
  return p;
}

Convex moved(Convex c, const Vec2& by) {
  for (auto& p : c) p += by;
  return c;
}

// The distance between two convex polygons (0 when they touch or overlap), by the Minkowski
// difference: the origin's distance from it.
double gap(const Convex& a, const Convex& b) {
  const Convex d = minkowski_sum(a, negated(b));
  if (inside_or_on(d, Vec2::Zero(), 0)) return 0;
  double best = 1e300;
  for (size_t i = 0; i < d.size(); ++i) {
    const Vec2 p = d[i], q = d[(i + 1) % d.size()], e = q - p;
    const double t = std::clamp(-p.dot(e) / e.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p + t * e).norm());
  }
  return best;
}

void check_layout(const std::vector<ArrangeItem>& items, const Arrangement& a, const Bed& bed, double spacing) {
  std::vector<Convex> at;
  for (size_t i = 0; i < items.size(); ++i) at.push_back(moved(items[i].hull, a.moves[i]));
  const Convex outline = bed.outline();
  for (size_t i = 0; i < at.size(); ++i) {
    if (std::find(a.unfit.begin(), a.unfit.end(), i) != a.unfit.end()) continue;
    for (const Vec2& p : at[i]) CHECK_MESSAGE(inside_or_on(outline, p, 1e-6), "item " << i << " off the bed");
    for (size_t j = i + 1; j < at.size(); ++j)
      if (std::find(a.unfit.begin(), a.unfit.end(), j) == a.unfit.end())
        CHECK_MESSAGE(gap(at[i], at[j]) >= spacing - 1e-3, "items " << i << " and " << j << " too close");
  }
}

}  // namespace

TEST_CASE("hull: hull, area, Minkowski sum, circumscription") {
  const Convex h = convex_hull({{0, 0}, {4, 0}, {4, 3}, {0, 3}, {2, 1}, {4, 1.5}});
  CHECK(h.size() == 4);
  CHECK(area(h) == doctest::Approx(12));
  const Convex s = minkowski_sum(rect(0, 0, 4, 3), rect(10, 10, 1, 2));
  CHECK(area(s) == doctest::Approx(5 * 5));
  CHECK(bounds(s).min.x() == doctest::Approx(10));
  const Convex round = polygon({0, 0}, 10, 200);
  const Convex c = circumscribe(round, 48);
  CHECK(c.size() <= 48);
  for (const Vec2& p : round) CHECK(inside_or_on(c, p, 1e-9));
  CHECK(area(c) < area(round) * 1.01);
  CHECK(area(inflated(rect(0, 0, 10, 10), 1)) > 140);
  CHECK(strictly_inside(rect(0, 0, 1, 1), {0.5, 0.5}, 1e-9));
  CHECK_FALSE(strictly_inside(rect(0, 0, 1, 1), {1, 0.5}, 1e-9));
}

TEST_CASE("arrange: objects go on the bed, apart by the spacing, the pile centred") {
  Bed bed;  // 200 × 200
  const std::vector<ArrangeItem> items = {{rect(0, 0, 40, 20)}, {rect(0, 0, 40, 20)}, {polygon({0, 0}, 15, 40)}};
  const Arrangement a = arrange(items, bed, 6);
  CHECK(a.unfit.empty());
  check_layout(items, a, bed, 6);
  Box2 pile;
  for (size_t i = 0; i < items.size(); ++i) pile.add(bounds(moved(items[i].hull, a.moves[i])));
  CHECK(pile.center().x() == doctest::Approx(100).epsilon(1e-6));
  CHECK(pile.center().y() == doctest::Approx(100).epsilon(1e-6));
  CHECK(pile.size().x() < 100);  // packed, not spread over the bed
  CHECK(pile.size().y() < 100);
}

TEST_CASE("arrange: many random objects, a fixed one in the way, and a round bed") {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> size(5, 30), angle(0, M_PI);
  std::vector<ArrangeItem> items;
  for (int i = 0; i < 40; ++i)
    items.push_back({i % 2 ? rect(0, 0, size(rng), size(rng)) : polygon({50, 50}, size(rng) / 2, 3 + i % 7, angle(rng))});
  Bed bed;
  bed.size_x_mm = 250;
  bed.size_y_mm = 210;
  items.push_back({rect(100, 90, 50, 30), true});
  const Arrangement a = arrange(items, bed, 4);
  CHECK(a.unfit.empty());
  CHECK(a.moves.back() == Vec2::Zero());
  check_layout(items, a, bed, 4);

  Bed round;
  round.shape = Bed::Shape::Circle;
  round.size_x_mm = round.size_y_mm = 180;
  round.origin_x_mm = round.origin_y_mm = -90;
  items.pop_back();
  items.resize(20);
  const Arrangement r = arrange(items, round, 4);
  CHECK(r.unfit.empty());
  check_layout(items, r, round, 4);
}

TEST_CASE("arrange: what does not fit is listed, the rest still placed") {
  Bed bed;
  std::vector<ArrangeItem> items(4, ArrangeItem{rect(0, 0, 100, 100)});
  items.push_back({rect(0, 0, 300, 10)});
  const Arrangement a = arrange(items, bed, 6);
  // 100 + 6 + 100 > 200: one of the squares fits, the others and the long bar do not.
  CHECK(a.unfit.size() == 4);
  CHECK(std::find(a.unfit.begin(), a.unfit.end(), 4) != a.unfit.end());
  check_layout(items, a, bed, 6);
}

TEST_CASE("arrange: arranged objects keep the bed's margin (the skirt's reach) from its edges") {
  Bed bed;  // 200 x 200
  bed.margin_mm = 5;
  // A fixed object near the front-left corner pushes the others towards the edges.
  std::vector<ArrangeItem> items = {{rect(6, 6, 60, 60), true}};
  for (int i = 0; i < 6; ++i) items.push_back({rect(0, 0, 50, 40), false});
  const Arrangement a = arrange(items, bed, 6);
  REQUIRE(a.unfit.empty());
  for (size_t i = 1; i < items.size(); ++i) {
    const Box2 b = bounds(moved(items[i].hull, a.moves[i]));
    CHECK(b.min.x() >= 5 - 1e-6);
    CHECK(b.min.y() >= 5 - 1e-6);
    CHECK(b.max.x() <= 195 + 1e-6);
    CHECK(b.max.y() <= 195 + 1e-6);
  }
  // Without the margin the same plate goes right up to an edge.
  bed.margin_mm = 0;
  const Arrangement edge = arrange(items, bed, 6);
  double nearest = 1e300;
  for (size_t i = 1; i < items.size(); ++i) {
    const Box2 b = bounds(moved(items[i].hull, edge.moves[i]));
    nearest = std::min({nearest, b.min.x(), b.min.y(), 200 - b.max.x(), 200 - b.max.y()});
  }
  CHECK(nearest < 5);
}

TEST_CASE("bed check: off the bed by how much, where, and what to do") {
  Bed bed;  // 200 × 200 at (0, 0)
  SUBCASE("larger than the bed") {
    const Status s = check_on_bed(bed, {{"'big'", rect(-28, 50, 256, 40), 10}});
    REQUIRE_FALSE(s.ok());
    const std::string m = s.error().message;
    CHECK(has(m, "'big' is off the bed by 28.0 mm on the left and 28.0 mm on the right"));
    CHECK(has(m, "larger than the bed"));
    CHECK(has(m, "--scale 0.78 fits"));
    CHECK(has(m, "--allow-off-bed"));
  }
  SUBCASE("beside the bed") {
    const Status s = check_on_bed(bed, {{"'a'", rect(190, 195, 20, 20), 10}, {"'b'", rect(10, 10, 5, 5), 10}});
    REQUIRE_FALSE(s.ok());
    CHECK(has(s.error().message, "'a' is off the bed by 10.0 mm on the right and 15.0 mm at the back"));
    CHECK(has(s.error().message, "--arrange"));
    CHECK_FALSE(has(s.error().message, "'b'"));
  }
  SUBCASE("too tall") {
    bed.max_height_mm = 210;
    const Status s = check_on_bed(bed, {{"'tower'", rect(50, 50, 10, 10), 250}});
    REQUIRE_FALSE(s.ok());
    CHECK(has(s.error().message, "'tower' is 250.0 mm high, 40.0 mm more than the printer reaches (210 mm)"));
    CHECK(has(s.error().message, "--scale 0.84"));
  }
  SUBCASE("a round bed") {
    bed.shape = Bed::Shape::Circle;
    bed.origin_x_mm = bed.origin_y_mm = -100;
    CHECK(check_on_bed(bed, {{"'in'", polygon({0, 0}, 99.9, 30), 5}}).ok());
    const Status s = check_on_bed(bed, {{"'out'", rect(80, 0, 30, 10), 5}});
    REQUIRE_FALSE(s.ok());
    CHECK(has(s.error().message, "beyond the edge of the round bed (radius 100 mm)"));
  }
  SUBCASE("on the bed, edges included") { CHECK(check_on_bed(bed, {{"'x'", rect(0, 0, 200, 200), 1}}).ok()); }
}
