// The case analysis of one triangle against one plane, case by case.
#include <doctest/doctest.h>

#include "geometry/slice/slicer.h"

using namespace tranche::geo;

namespace {

using Tri = std::array<Vec3, 3>;

// Direction of the cut seen from above, as (dx, dy).
std::pair<double, double> direction(const TriangleCut& c) { return {c.to.x - c.from.x, c.to.y - c.from.y}; }

}  // namespace

SCENARIO("a triangle crossing the plane") {
  GIVEN("a wall facing -y (material at +y), counter-clockwise from outside") {
    Tri wall{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 0, 1}};
    auto cut = cut_triangle(wall, 0.5);
    REQUIRE(cut);
    THEN("the cut runs +x, keeping the material on its left") {
      CHECK(cut->from.kind == Crossing::Edge);
      CHECK(cut->to.kind == Crossing::Edge);
      CHECK(cut->from.index == 2);  // c -> a goes down through the plane
      CHECK(cut->to.index == 1);    // b -> c comes back up
      CHECK(cut->from.x == 0);
      CHECK(cut->to.x == 0.5);
      auto [dx, dy] = direction(*cut);
      CHECK(dx > 0);
      CHECK(dy == 0);
    }
  }
  GIVEN("the same wall turned inside out") {
    Tri flipped{Vec3{0, 0, 0}, Vec3{0, 0, 1}, Vec3{1, 0, 0}};
    auto cut = cut_triangle(flipped, 0.5);
    REQUIRE(cut);
    THEN("the cut runs the other way") { CHECK(direction(*cut).first < 0); }
  }
  GIVEN("a plane that misses the triangle") {
    Tri t{Vec3{0, 0, 1}, Vec3{1, 0, 2}, Vec3{0, 1, 3}};
    CHECK(!cut_triangle(t, 0.5));
    CHECK(!cut_triangle(t, 3.5));
  }
}

SCENARIO("all three vertices on the plane") {
  Tri flat{Vec3{0, 0, 2}, Vec3{1, 0, 2}, Vec3{0, 1, 2}};
  THEN("the triangle is skipped, whichever way it faces") {
    CHECK(!cut_triangle(flat, 2));
    CHECK(!cut_triangle({flat[0], flat[2], flat[1]}, 2));
  }
}

SCENARIO("an edge lying in the plane is counted exactly once") {
  // Two triangles share the edge (0,0,1)-(1,0,1); one has its third vertex below, one above.
  Vec3 p{0, 0, 1}, q{1, 0, 1};
  Tri lower{q, p, Vec3{0.5, 0, 0}};  // wall facing -y below the edge
  Tri upper{p, q, Vec3{0.5, 0, 2}};  // wall facing -y above the edge
  auto a = cut_triangle(lower, 1);
  auto b = cut_triangle(upper, 1);
  THEN("only the triangle below the edge keeps it, as the edge itself") {
    REQUIRE(a);
    CHECK(!b);
    CHECK(a->from.kind == Crossing::Vertex);
    CHECK(a->to.kind == Crossing::Vertex);
    CHECK(a->from.x == 0);  // from p to q: +x, material (+y) on the left
    CHECK(a->to.x == 1);
  }
  THEN("the same holds with the roles of the triangles' vertex order rotated") {
    auto c = cut_triangle({lower[1], lower[2], lower[0]}, 1);
    REQUIRE(c);
    CHECK(c->from.x == 0);
    CHECK(c->to.x == 1);
  }
}

SCENARIO("a single vertex on the plane") {
  GIVEN("the other two on opposite sides") {
    Tri t{Vec3{0, 0, 1}, Vec3{2, 0, 0}, Vec3{2, 0, 2}};  // faces -y
    auto cut = cut_triangle(t, 1);
    REQUIRE(cut);
    THEN("the segment runs from the vertex to the crossing of the opposite edge") {
      const Crossing& v = cut->from.kind == Crossing::Vertex ? cut->from : cut->to;
      const Crossing& e = cut->from.kind == Crossing::Vertex ? cut->to : cut->from;
      CHECK(v.kind == Crossing::Vertex);
      CHECK(v.index == 0);
      CHECK(e.kind == Crossing::Edge);
      CHECK(e.index == 1);
      CHECK(e.x == 2);
      CHECK(direction(*cut).first > 0);
    }
  }
  GIVEN("the other two both below") {
    Tri t{Vec3{0, 0, 1}, Vec3{2, 0, 0}, Vec3{2, 1, 0.5}};
    THEN("nothing: the triangle only touches the plane") { CHECK(!cut_triangle(t, 1)); }
  }
  GIVEN("the other two both above") {
    Tri t{Vec3{0, 0, 1}, Vec3{2, 0, 3}, Vec3{2, 1, 1.5}};
    THEN("nothing") { CHECK(!cut_triangle(t, 1)); }
  }
}

TEST_CASE("both triangles of an edge compute the bit-identical crossing") {
  // Awkward coordinates so that interpolating from either end would round differently.
  Vec3 lo{0.1234567, 7.654321, -0.3333}, hi{13.37, -2.718281828, 9.87654321};
  Vec3 left{-5.5, 3.3, 4.4}, right{8.1, 9.2, 2.2};
  Tri t1{lo, hi, left};   // edge lo -> hi
  Tri t2{hi, lo, right};  // the same edge, reversed
  for (double z : {0.1, 1.7, 2.2000001, 5.0, 9.5}) {
    auto a = cut_triangle(t1, z);
    auto b = cut_triangle(t2, z);
    REQUIRE(a);
    REQUIRE(b);
    const Crossing& ea = a->from.index == 0 ? a->from : a->to;
    const Crossing& eb = b->from.index == 0 ? b->from : b->to;
    REQUIRE(ea.kind == Crossing::Edge);
    REQUIRE(eb.kind == Crossing::Edge);
    CHECK(ea.x == eb.x);
    CHECK(ea.y == eb.y);
  }
}
