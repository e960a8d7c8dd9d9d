// The --fill-angle-script hook: loading, calling, the context a script sees, and every error.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <thread>

#include "geometry/fillangle/fill_angle.h"
#include "tests/support/fixtures.h"

using namespace tranche;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Writes `source` to NAME in `dir` and returns its path.
std::string write(const tranche::test::TempDir& dir, const std::string& name, const std::string& source) {
  std::string path = (dir / name).string();
  std::ofstream(path) << source;
  return path;
}

geo::Polygon square(double x0, double y0, double size) {
  geo::Polygon p;
  p.outer = {geo::to_point(x0, y0), geo::to_point(x0 + size, y0), geo::to_point(x0 + size, y0 + size),
             geo::to_point(x0, y0 + size)};
  return p;
}

// Three layers: one island, then two (the second with a hole), then one.
std::vector<geo::Layer> layers() {
  std::vector<geo::Layer> ls(3);
  for (int i = 0; i < 3; ++i) {
    ls[static_cast<size_t>(i)].index = i;
    ls[static_cast<size_t>(i)].z_bottom = 0.2 * i;
    ls[static_cast<size_t>(i)].z_top = 0.2 * (i + 1);
  }
  auto add = [](geo::Layer& l, geo::Polygon p) {
    l.islands.push_back({p, geo::area_mm2(p)});
  };
  add(ls[0], square(0, 0, 10));
  add(ls[1], square(0, 0, 10));
  geo::Polygon holed = square(20, 0, 10);
  holed.holes.push_back(
      {geo::to_point(22, 2), geo::to_point(22, 4), geo::to_point(24, 4), geo::to_point(24, 2)});
  add(ls[1], holed);
  add(ls[2], square(1, 2, 3));
  return ls;
}

// Loads `source` as a script and returns the angle for island `island` of layer `layer`.
Result<double> angle_of(const std::string& source, int layer = 1, int island = 1) {
  tranche::test::TempDir dir("fill-angle");
  auto script = geo::FillAngleScript::load(write(dir, "angle.py", source));
  if (!script) return script.error();
  auto ls = layers();
  geo::FillAngleContext c;
  c.layer_index = layer;
  c.layer_count = static_cast<int>(ls.size());
  const geo::Layer& l = ls[static_cast<size_t>(layer)];
  c.z = l.z_top;
  c.z_bottom = l.z_bottom;
  c.island_index = island;
  c.island_count = static_cast<int>(l.islands.size());
  c.area = l.islands[static_cast<size_t>(island)].area_mm2;
  c.shape = &l.islands[static_cast<size_t>(island)].shape;
  c.default_angle = layer % 2 == 0 ? 45 : 135;  // as the cascade gives it (see "as a layer of the cascade")
  return (*script)->angle(c);
}

// The script's angles over `ls`, as a layer of a cascade of defaults only.
Result<std::unique_ptr<geo::ScriptAngles>> angles(geo::FillAngleScript& script, const std::vector<geo::Layer>& ls) {
  static auto cascade = ctx::Cascade::create({});
  return geo::ScriptAngles::compute(script, ls, **cascade, ctx::Context(), ctx::PropertyValues::schema_defaults());
}

}  // namespace

TEST_CASE("fill-angle script: a layer of the cascade between the built-in defaults and the rules") {
  if (!geo::FillAngleScript::available()) return;
  tranche::test::TempDir dir("fill-angle");
  // The default it sees is the cascade's (45° / 135°), and its angle is what rules then override.
  auto script = geo::FillAngleScript::load(
      write(dir, "d.py", "def fill_angle(ctx):\n    return ctx.default_angle + ctx.island_index\n"));
  REQUIRE(script.ok());
  auto ls = layers();
  auto a = angles(**script, ls);
  REQUIRE_MESSAGE(a.ok(), a.error().to_string());
  CHECK((*a)->angle(0, 0) == 45);
  CHECK((*a)->angle(1, 0) == 135);
  CHECK((*a)->angle(1, 1) == 136);
  CHECK((*a)->angle(2, 0) == 45);
  auto cascade = ctx::Cascade::create({});
  REQUIRE(cascade.ok());
  (*cascade)->set_middle(a->get());
  ctx::Context c;
  c.set(schema::FieldId::LayerIndex, 1);
  c.set(schema::FieldId::IslandIndex, 1);
  auto props = ctx::PropertyValues::schema_defaults();
  REQUIRE((*cascade)->decide(schema::Stage::Island, c, props).ok());
  CHECK(props[schema::PropId::FillAngle] == 136);
  CHECK((*a)->varies_at(schema::Stage::Island) == schema::Level::Island);
  CHECK((*a)->varies_at(schema::Stage::Piece) == schema::Level::Print);
  auto over = ctx::Cascade::create({{"fill_angle", "10"}});  // --set sits above the script
  REQUIRE(over.ok());
  (*over)->set_middle(a->get());
  props = ctx::PropertyValues::schema_defaults();
  REQUIRE((*over)->decide(schema::Stage::Island, c, props).ok());
  CHECK(props[schema::PropId::FillAngle] == 10);
}

TEST_CASE("fill-angle script: a missing file is an error naming it") {
  auto s = geo::FillAngleScript::load("/nonexistent/angle.py");
  REQUIRE_FALSE(s.ok());
  CHECK(s.error().where == "/nonexistent/angle.py");
  CHECK(contains(s.error().message, "cannot open"));
}

TEST_CASE("fill-angle script: built with Python") {
  // The build embeds Python whenever pybind11 is found; a build without it must say so instead.
  if (!geo::FillAngleScript::available()) {
    tranche::test::TempDir dir("fill-angle");
    auto s = geo::FillAngleScript::load(write(dir, "a.py", "def fill_angle(ctx): return 0\n"));
    REQUIRE_FALSE(s.ok());
    CHECK(contains(s.error().message, "built without Python"));
    return;
  }
  SUBCASE("a constant, for every island of every layer") {
    tranche::test::TempDir dir("fill-angle");
    auto script = geo::FillAngleScript::load(write(dir, "const.py", "def fill_angle(ctx):\n    return 30\n"));
    REQUIRE_MESSAGE(script.ok(), script.error().to_string());
    auto ls = layers();
    auto a = angles(**script, ls);
    REQUIRE(a.ok());
    for (size_t l = 0; l < ls.size(); ++l)
      for (size_t i = 0; i < ls[l].islands.size(); ++i) CHECK((*a)->angle(l, i) == 30);
  }
  SUBCASE("one using the layer index and the default") {
    tranche::test::TempDir dir("fill-angle");
    auto script = geo::FillAngleScript::load(write(
        dir, "helicoid.py", "def fill_angle(ctx):\n    return 15.0 * ctx.layer_index + ctx.default_angle\n"));
    REQUIRE(script.ok());
    auto ls = layers();
    auto a = angles(**script, ls);
    REQUIRE(a.ok());
    CHECK((*a)->angle(0, 0) == 45);
    CHECK((*a)->angle(1, 0) == 150);
    CHECK((*a)->angle(1, 1) == 150);
    CHECK((*a)->angle(2, 0) == 75);
  }
  SUBCASE("the context fields") {
    // Layer 1, island 1: the square (20, 0)-(30, 10) with a 2 x 2 hole; z from 0.2 to 0.4.
    struct Case {
      const char* expr;
      double want;
    };
    for (Case c : {Case{"ctx.layer_index", 1},
                   Case{"ctx.layer_count", 3},
                   Case{"ctx.z", 0.4},
                   Case{"ctx.z_bottom", 0.2},
                   Case{"ctx.layer_height", 0.2},
                   Case{"ctx.island_index", 1},
                   Case{"ctx.island_count", 2},
                   Case{"ctx.area", 96},
                   Case{"ctx.bbox[0]", 20},
                   Case{"ctx.bbox[1]", 0},
                   Case{"ctx.bbox[2]", 30},
                   Case{"ctx.bbox[3]", 10},
                   Case{"len(ctx.outer)", 4},
                   Case{"ctx.outer[1][0]", 30},
                   Case{"ctx.outer[2][1]", 10},
                   Case{"len(ctx.holes)", 1},
                   Case{"len(ctx.holes[0])", 4},
                   Case{"ctx.holes[0][2][0]", 24},
                   Case{"ctx.default_angle", 135},
                   Case{"isinstance(ctx.layer_index, int) and isinstance(ctx.z, float)", 1}}) {
      CAPTURE(c.expr);
      auto a = angle_of(std::string("def fill_angle(ctx):\n    return float(") + c.expr + ")\n");
      REQUIRE_MESSAGE(a.ok(), a.error().to_string());
      CHECK(*a == doctest::Approx(c.want));
    }
    // The outer ring is counter-clockwise (positive shoelace area), the hole clockwise.
    auto orient = angle_of(
        "def area(r):\n"
        "    return sum(r[i][0] * r[(i + 1) % len(r)][1] - r[(i + 1) % len(r)][0] * r[i][1] for i in "
        "range(len(r))) / 2\n"
        "def fill_angle(ctx):\n"
        "    return area(ctx.outer) + area(ctx.holes[0])\n");
    REQUIRE(orient.ok());
    CHECK(*orient == doctest::Approx(96));
  }
  SUBCASE("numbers of other numeric types, negative and large angles are accepted") {
    CHECK(*angle_of("import fractions\ndef fill_angle(ctx):\n    return fractions.Fraction(1, 4)\n") == 0.25);
    CHECK(*angle_of("def fill_angle(ctx):\n    return -720\n") == -720);
  }
  SUBCASE("a script may import modules beside it") {
    tranche::test::TempDir dir("fill-angle");
    write(dir, "helper_mod_xyz.py", "ANGLE = 12.5\n");
    auto script = geo::FillAngleScript::load(write(
        dir, "main.py", "import helper_mod_xyz\ndef fill_angle(ctx):\n    return helper_mod_xyz.ANGLE\n"));
    REQUIRE_MESSAGE(script.ok(), script.error().to_string());
    auto ls = layers();
    auto a = angles(**script, ls);
    REQUIRE(a.ok());
    CHECK((*a)->angle(2, 0) == 12.5);
  }
  SUBCASE("an exception gives the traceback, the script line and the island") {
    tranche::test::TempDir dir("fill-angle");
    std::string path =
        write(dir, "raise.py",
              "def helper(x):\n    return x / 0\n\ndef fill_angle(ctx):\n    return helper(ctx.area)\n");
    auto script = geo::FillAngleScript::load(path);
    REQUIRE(script.ok());
    auto ls = layers();
    auto s = angles(**script, ls);
    REQUIRE_FALSE(s.ok());
    CHECK(s.error().where == path + ":2");  // the innermost frame in the script
    CHECK(contains(s.error().message, "raised an exception on layer 0, island 0"));
    CHECK(contains(s.error().message, "Traceback (most recent call last)"));
    CHECK(contains(s.error().message, "line 5, in fill_angle"));
    CHECK(contains(s.error().message, "ZeroDivisionError: float division by zero"));
  }
  SUBCASE("a wrong return type, NaN or infinity is an error naming the island") {
    struct Case {
      const char* ret;
      const char* part;
    };
    for (Case c : {Case{"'45'", "returned str '45' on layer 1, island 1: it must return a number"},
                   Case{"None", "returned NoneType None"}, Case{"True", "returned bool True"},
                   Case{"[45]", "returned list [45]"},
                   Case{"float('nan')",
                        "returned nan on layer 1, island 1: it must "
                        "return a finite number"},
                   Case{"float('inf')", "returned inf"}, Case{"10 ** 400", "int too large"}}) {
      CAPTURE(c.ret);
      auto a = angle_of(std::string("def fill_angle(ctx):\n    return ") + c.ret + "\n");
      REQUIRE_FALSE(a.ok());
      CHECK_MESSAGE(contains(a.error().message, c.part), a.error().message);
    }
  }
  SUBCASE("a missing function, or one that is not callable") {
    auto a = angle_of("def fill_anglez(ctx):\n    return 1\n");
    REQUIRE_FALSE(a.ok());
    CHECK(contains(a.error().message, "defines no function fill_angle(ctx)"));
    a = angle_of("fill_angle = 45\n");
    REQUIRE_FALSE(a.ok());
    CHECK(contains(a.error().message, "fill_angle is not a function (its type is int)"));
  }
  SUBCASE("a syntax error is reported at file:line:col") {
    tranche::test::TempDir dir("fill-angle");
    std::string path =
        write(dir, "bad.py", "# a comment\ndef fill_angle(ctx):\n    return (ctx.layer_index +\n");
    auto s = geo::FillAngleScript::load(path);
    REQUIRE_FALSE(s.ok());
    CHECK(contains(s.error().where, path + ":3:"));
    CHECK(contains(s.error().message, "syntax error"));
    path = write(dir, "bad2.py", "def fill_angle(ctx)\n    return 1\n");
    s = geo::FillAngleScript::load(path);
    REQUIRE_FALSE(s.ok());
    CHECK(s.error().where == path + ":1:20");
    CHECK(contains(s.error().message, "syntax error: expected ':'"));
    CHECK(contains(s.error().message, "def fill_angle(ctx)\n                       ^"));
  }
  SUBCASE("an exception while loading the script") {
    tranche::test::TempDir dir("fill-angle");
    std::string path =
        write(dir, "load.py", "import no_such_module_tranche\ndef fill_angle(ctx):\n    return 1\n");
    auto s = geo::FillAngleScript::load(path);
    REQUIRE_FALSE(s.ok());
    CHECK(s.error().where == path + ":1");
    CHECK(contains(s.error().message, "failed while loading"));
    CHECK(contains(s.error().message, "ModuleNotFoundError: No module named 'no_such_module_tranche'"));
  }
  SUBCASE("calls from several threads at once are safe") {
    tranche::test::TempDir dir("fill-angle");
    auto script = geo::FillAngleScript::load(write(
        dir, "threads.py", "def fill_angle(ctx):\n    return ctx.layer_index * 1000 + ctx.island_index\n"));
    REQUIRE(script.ok());
    geo::FillAngleScript& sc = **script;
    geo::Polygon sq = square(0, 0, 1);
    std::vector<int> bad(4, 0);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
      threads.emplace_back([&, t] {
        for (int k = 0; k < 200; ++k) {
          geo::FillAngleContext c;
          c.layer_index = t, c.island_index = k, c.shape = &sq;
          auto a = sc.angle(c);
          if (!a || *a != t * 1000 + k) ++bad[static_cast<size_t>(t)];
        }
      });
    for (auto& th : threads) th.join();
    CHECK(bad == std::vector<int>(4, 0));
  }
}

TEST_CASE("fill-angle script: vertices in the middle of straight edges are left out of ctx.outer") {
  if (!geo::FillAngleScript::available()) return;
  // A 30 × 5 mm bar turned 30°, as a mesh slices it: each long edge has an extra vertex (where a
  // side triangle's diagonal meets it), off the exact line by integer rounding only.
  const double a = 30 * 3.14159265358979323846 / 180, c = std::cos(a), s = std::sin(a);
  auto at = [&](double x, double y) { return geo::to_point(x * c - y * s, x * s + y * c); };
  geo::Polygon bar;
  bar.outer = {at(0, 0), at(1.5, 0), at(30, 0), at(30, 0.25), at(30, 5), at(28.5, 5), at(0, 5), at(0, 4.75)};
  geo::Layer layer;
  layer.index = 0;
  layer.z_top = 0.2;
  layer.islands.push_back({bar, geo::area_mm2(bar)});
  tranche::test::TempDir dir("fill-angle");
  auto script = geo::FillAngleScript::load(write(dir, "n.py", "def fill_angle(ctx):\n    return len(ctx.outer)\n"));
  REQUIRE(script.ok());
  geo::FillAngleContext ctx;
  ctx.layer_count = 1;
  ctx.island_count = 1;
  ctx.shape = &layer.islands[0].shape;
  auto n = (*script)->angle(ctx);
  REQUIRE(n.ok());
  CHECK(*n == 4);
}

TEST_CASE("fill-angle script: a call that runs too long is stopped, naming the layer and island") {
  if (!geo::FillAngleScript::available()) return;
  tranche::test::TempDir dir("fill-angle-timeout");
  auto script = geo::FillAngleScript::load(
      write(dir, "slow.py", "def fill_angle(ctx):\n    if ctx.layer_index == 2:\n        while True: pass\n    return 10\n"),
      0.3);
  REQUIRE(script.ok());
  auto ls = layers();
  geo::FillAngleContext c;
  c.layer_count = 3;
  c.layer_index = 0;
  c.shape = &ls[0].islands[0].shape;
  auto fast = (*script)->angle(c);
  REQUIRE(fast.ok());
  CHECK(*fast == 10);
  c.layer_index = 2;
  c.island_index = 0;
  const auto start = std::chrono::steady_clock::now();
  auto slow = (*script)->angle(c);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  REQUIRE_FALSE(slow.ok());
  CHECK(contains(slow.error().message, "took longer than 0.3 s on layer 2, island 0 (--script-timeout)"));
  CHECK(s < 2);
  // The script stays usable: the next call works, and no TimeoutError is left pending.
  c.layer_index = 1;
  auto after = (*script)->angle(c);
  REQUIRE_MESSAGE(after.ok(), after.error().to_string());
  CHECK(*after == 10);
}

TEST_CASE("fill-angle script: a top level that runs too long is stopped") {
  if (!geo::FillAngleScript::available()) return;
  tranche::test::TempDir dir("fill-angle-timeout");
  auto script = geo::FillAngleScript::load(write(dir, "loop.py", "while True:\n    pass\n"), 0.2);
  REQUIRE_FALSE(script.ok());
  CHECK(contains(script.error().message, "the script's top level took longer than 0.2 s"));
}
