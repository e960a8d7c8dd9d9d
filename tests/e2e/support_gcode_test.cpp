// End to end: support material and the brim on the G-code of constructed models with
// overhangs (a mushroom, a stem with a ledge under a cap), steered by --set and by rules.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>

#include "apps/slice_command.h"
#include "gcode_reader.h"
#include "mesh_run.h"
#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "tests/support/fixtures.h"

using namespace tranche;

namespace {

using Run = test::MeshRun;

Run run(const test::TempDir& dir, const std::string& name, const geo::Mesh& mesh, const test::Sets& sets,
        const std::string& rules = "", bool strict = false) {
  return test::slice_mesh(dir, name, mesh, sets, rules, strict);
}

// A 4 mm square stem 10 mm high under a 20 mm square cap 2 mm thick: centred on the bed (100, 100).
geo::Mesh mushroom() {
  geo::Mesh m = geo::box({4, 4, 10}, {8, 8, 0});
  geo::append(m, geo::box({20, 20, 2}, {0, 0, 10}));
  return m;
}

bool extrudes(const test::Move& m) { return m.has_xy && m.de > 0; }
bool is_support(const test::Move& m) { return m.type.rfind("Support material", 0) == 0; }

// Distance from (x, y) to the axis-aligned rectangle [x0, x1] x [y0, y1] (0 inside).
double to_rect(double x, double y, double x0, double y0, double x1, double y1) {
  double dx = std::max({x0 - x, 0.0, x - x1}), dy = std::max({y0 - y, 0.0, y - y1});
  return std::hypot(dx, dy);
}

bool has_warning(const Run& r, const std::string& code) {
  return std::any_of(r.warnings.begin(), r.warnings.end(), [&](const Warning& w) { return w.code == code; });
}

}  // namespace

TEST_CASE("support: a mushroom's cap stands on support, kept off the stem and below the cap") {
  test::TempDir dir("support-mushroom");
  Run r = run(dir, "m", mushroom(), {{"support", "normal"}});
  REQUIRE_MESSAGE(r.result.ok(), (r.result.ok() ? "" : r.result.error().to_string()));
  CHECK(r.g.contains(";TYPE:Support material\n"));
  CHECK(r.g.contains(";TYPE:Support material interface\n"));
  CHECK_FALSE(has_warning(r, "unsupported-overhang"));
  int support_moves = 0, interface_moves = 0;
  double top = 0;
  for (const auto& m : r.g.moves) {
    if (!extrudes(m) || !is_support(m)) continue;
    ++support_moves;
    if (m.type == "Support material interface") ++interface_moves;
    const double z = r.g.layer_z.at(m.layer);
    top = std::max(top, z);
    // The stem is x, y in [98, 102]: beads keep the 0.5 mm xy gap (less half a bead).
    for (auto [x, y] : {std::pair{m.x0, m.y0}, {m.x, m.y}}) {
      CHECK(to_rect(x, y, 98, 98, 102, 102) >= 0.5 - 0.225 - 1e-3);
      CHECK(to_rect(x, y, 90, 90, 110, 110) <= 1e-3);  // under the cap, nowhere else
    }
  }
  CHECK(support_moves > 100);
  CHECK(interface_moves > 20);
  // One layer of air (support_z_gap 0.2 mm) under the cap's bottom at z = 10.
  CHECK(top == doctest::Approx(9.8));
  // The support starts on the bed.
  bool on_bed = false;
  for (const auto& m : r.g.moves) on_bed |= extrudes(m) && is_support(m) && m.layer == 0;
  CHECK(on_bed);
}

TEST_CASE("support: off by default, the overhang is said once; --strict refuses it") {
  test::TempDir dir("support-off");
  Run r = run(dir, "m", mushroom(), {});
  REQUIRE(r.result.ok());
  CHECK_FALSE(r.g.contains(";TYPE:Support material"));
  REQUIRE(has_warning(r, "unsupported-overhang"));
  for (const auto& w : r.warnings)
    if (w.code == "unsupported-overhang") {
      CHECK(w.message.find("printed in the air") != std::string::npos);
      CHECK(w.message.find("support = normal") != std::string::npos);
      CHECK(w.where.find("layer 50") != std::string::npos);  // the cap's first layer
    }
  Run s = run(dir, "s", mushroom(), {}, "", true);
  REQUIRE_FALSE(s.result.ok());
  CHECK(s.result.error().message.find("overhang printed in the air") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir / "s.gcode"));
}

TEST_CASE("support: a rule blocks support below a height, another turns it on (blockers and enforcers as rules)") {
  test::TempDir dir("support-rules");
  // A ledge 6 mm long at z 3..4 on the stem's -x side, under the cap.
  geo::Mesh m = mushroom();
  geo::append(m, geo::box({6, 4, 1}, {2, 8, 3}));
  auto under_ledge = [](const test::Move& mv) {  // the middle of the move under the ledge: x 92..98, y 98..102
    return to_rect(0.5 * (mv.x0 + mv.x), 0.5 * (mv.y0 + mv.y), 92, 98, 98, 102) == 0;
  };
  const std::string rules = R"(
rule "support on" { support = normal }
rule "no support below 5 mm" when layer.z_bottom < 5 mm { support = none }
)";
  Run blocked = run(dir, "b", m, {}, rules);
  REQUIRE_MESSAGE(blocked.result.ok(), (blocked.result.ok() ? "" : blocked.result.error().to_string()));
  Run all = run(dir, "a", m, {{"support", "normal"}});
  REQUIRE(all.result.ok());
  auto count = [&](const Run& r, bool low) {
    int n = 0;
    for (const auto& mv : r.g.moves)
      if (extrudes(mv) && is_support(mv) && under_ledge(mv) && (r.g.layer_z.at(mv.layer) < 2.9) == low) ++n;
    return n;
  };
  CHECK(count(all, true) > 10);     // support under the ledge when nothing blocks it
  CHECK(count(blocked, true) == 0);  // blocked: the ledge (z 3) is below 5 mm
  CHECK(count(blocked, false) > 10);  // the cap's column still stands on the ledge
  CHECK(has_warning(blocked, "unsupported-overhang"));  // the blocked ledge is said
}

TEST_CASE("support: speed and kind reachable by rules like any path") {
  test::TempDir dir("support-speed");
  Run r = run(dir, "m", mushroom(), {{"support", "normal"}, {"min_layer_time", "0"}},
              "rule \"slow support\" when path.kind == support and layer.index > 0 { speed = 17 mm/s }\n"
              "rule \"sparse support\" when island.support { support_density = 10% }\n");
  REQUIRE(r.result.ok());
  int slow = 0, other = 0;
  for (const auto& m : r.g.moves)
    if (extrudes(m) && m.type == "Support material" && m.layer > 0) (std::abs(m.f - 17 * 60) < 1 ? slow : other)++;
  CHECK(slow > 50);
  CHECK(other == 0);
}

TEST_CASE("brim: loops on the first layer round the part, the skirt outside them") {
  test::TempDir dir("brim");
  Run r = run(dir, "b", geo::box({10, 10, 2}), {{"brim_width", "3"}, {"skirt_loops", "1"}});
  REQUIRE(r.result.ok());
  CHECK(r.g.contains(";TYPE:Skirt/Brim\n"));
  double brim_far = 0, skirt_near = 1e9;
  int brim_moves = 0;
  for (const auto& m : r.g.moves) {
    if (!extrudes(m) || m.layer != 0 || m.type != "Skirt/Brim") continue;
    const double d = to_rect(m.x, m.y, 95, 95, 105, 105);
    if (d < 4) brim_far = std::max(brim_far, d), ++brim_moves;
    else skirt_near = std::min(skirt_near, d);
  }
  CHECK(brim_moves > 20);
  CHECK(brim_far == doctest::Approx(3).epsilon(0.1));  // 3 mm of brim
  CHECK(skirt_near >= 3 + 3 - 0.3);                    // the skirt 3 mm beyond the brim
  Run none = run(dir, "n", geo::box({10, 10, 2}), {});
  REQUIRE(none.result.ok());
  CHECK_FALSE(none.g.contains(";TYPE:Skirt/Brim"));
}

TEST_CASE("support: tree branches hold the cap with far less plastic than columns, clear of the stem") {
  test::TempDir dir("support-tree");
  Run normal = run(dir, "n", mushroom(), {{"support", "normal"}});
  Run tree = run(dir, "t", mushroom(), {{"support", "tree"}});
  REQUIRE_MESSAGE(tree.result.ok(), (tree.result.ok() ? "" : tree.result.error().to_string()));
  REQUIRE(normal.result.ok());
  auto plastic = [](const Run& r) {
    double e = 0;
    for (const auto& m : r.g.moves)
      if (extrudes(m) && m.type == "Support material") e += m.de;
    return e;
  };
  CHECK(plastic(tree) > 0);
  CHECK(plastic(tree) < 0.6 * plastic(normal));
  CHECK(tree.g.contains(";TYPE:Support material interface\n"));
  bool on_bed = false;
  double top = 0;
  for (const auto& m : tree.g.moves) {
    if (!extrudes(m) || !is_support(m)) continue;
    on_bed |= m.layer == 0;
    top = std::max(top, tree.g.layer_z.at(m.layer));
    CHECK(to_rect(m.x, m.y, 98, 98, 102, 102) >= 0.5 - 0.225 - 1e-3);
  }
  CHECK(on_bed);
  CHECK(top == doctest::Approx(9.8));
  CHECK_FALSE(has_warning(tree, "unsupported-overhang"));
}

TEST_CASE("support: an overhang less than the z gap above the bed is said as such: support cannot fit under it") {
  test::TempDir dir("support-near-bed");
  geo::Mesh m = geo::box({4, 4, 0.2}, {8, 8, 0});  // one layer of stem
  geo::append(m, geo::box({20, 20, 2}, {0, 0, 0.2}));
  for (const char* style : {"none", "normal"}) {
    Run r = run(dir, style, m, {{"support", style}});
    REQUIRE(r.result.ok());
    CHECK(has_warning(r, "overhang-near-bed"));
    CHECK_FALSE(has_warning(r, "unsupported-overhang"));  // support would not help: not suggested
    for (const auto& w : r.warnings)
      if (w.code == "overhang-near-bed") CHECK(w.message.find("no support fits under it") != std::string::npos);
    CHECK_FALSE(r.g.contains(";TYPE:Support material"));
  }
  // The rule the warning gives lets support touch the overhang: it stands on the bed under it,
  // and nothing is said.
  Run w = run(dir, "touch", m, {{"support", "normal"}});
  REQUIRE(w.result.ok());
  std::string rule;
  for (const auto& x : w.warnings)
    if (x.code == "overhang-near-bed") {
      const size_t from = x.message.find("rule when"), to = x.message.find('}', from);
      REQUIRE(to != std::string::npos);
      rule = x.message.substr(from, to + 1 - from);
      CHECK(x.message.find("support-touching-near-bed") != std::string::npos);
    }
  REQUIRE(rule == "rule when layer.z_bottom < 0.4 mm { support_z_gap = 0 mm }");
  Run t = run(dir, "touched", m, {{"support", "normal"}}, rule + "\n");
  REQUIRE_MESSAGE(t.result.ok(), (t.result.ok() ? "" : t.result.error().to_string()));
  CHECK_FALSE(has_warning(t, "overhang-near-bed"));
  bool under = false;
  for (const auto& mv : t.g.moves)
    under |= extrudes(mv) && is_support(mv) && mv.layer == 0;
  CHECK(under);
}

TEST_CASE("raft: layers of support under the whole first layer, the part a gap above them, the skirt round it") {
  test::TempDir dir("raft");
  // A 10 mm cube (x, y in [95, 105] on the bed): three raft layers of 0.2 mm, 0.1 mm of air.
  Run r = run(dir, "c", geo::box({10, 10, 10}, {0, 0, 0}), {{"raft_layers", "3"}, {"skirt_loops", "1"}});
  REQUIRE_MESSAGE(r.result.ok(), (r.result.ok() ? "" : r.result.error().to_string()));
  int first_part_layer = -1;
  double reach = 0;  // how far the raft's beads go past the cube
  for (const auto& m : r.g.moves) {
    if (!extrudes(m)) continue;
    if (is_support(m)) {
      CHECK(m.layer < 3);  // nothing holds the cube but the raft
      reach = std::max(reach, to_rect(m.x, m.y, 95, 95, 105, 105));
      CHECK(to_rect(m.x, m.y, 95, 95, 105, 105) <= 1.5 + 1e-3);  // raft_expansion
    } else if (m.type != "Skirt/Brim" && first_part_layer < 0) {
      first_part_layer = m.layer;
    }
  }
  CHECK(reach > 1.0);
  REQUIRE(first_part_layer == 3);
  CHECK(r.g.layer_z.at(0) == doctest::Approx(0.2));
  CHECK(r.g.layer_z.at(2) == doctest::Approx(0.6));
  CHECK(r.g.layer_z.at(3) == doctest::Approx(0.9));  // 0.6 + raft_z_gap 0.1 + the cube's first 0.2
  // The first and top raft layers dense (interface), the one between sparse.
  auto kinds_on = [&](int layer) {
    std::set<std::string> kinds;
    for (const auto& m : r.g.moves)
      if (extrudes(m) && m.layer == layer && is_support(m)) kinds.insert(m.type);
    return kinds;
  };
  CHECK(kinds_on(0) == std::set<std::string>{"Support material interface"});
  CHECK(kinds_on(1) == std::set<std::string>{"Support material"});
  CHECK(kinds_on(2) == std::set<std::string>{"Support material interface"});
  // The skirt goes round the raft, not through it.
  for (const auto& m : r.g.moves)
    if (extrudes(m) && m.type == "Skirt/Brim") CHECK(to_rect(m.x, m.y, 95, 95, 105, 105) > 1.5);
  // The part's overhang test skips its first layer: it lies on the raft, not in the air.
  CHECK_FALSE(has_warning(r, "unsupported-overhang"));
}

TEST_CASE("raft: support columns stand on it, and it reaches past them") {
  test::TempDir dir("raft-support");
  Run r = run(dir, "m", mushroom(), {{"raft_layers", "2"}, {"support", "normal"}});
  REQUIRE_MESSAGE(r.result.ok(), (r.result.ok() ? "" : r.result.error().to_string()));
  double raft_top = r.g.layer_z.at(1), column_bottom = 1e9;
  for (const auto& m : r.g.moves)
    if (extrudes(m) && is_support(m) && m.layer >= 2) column_bottom = std::min(column_bottom, r.g.layer_z.at(m.layer));
  CHECK(raft_top == doctest::Approx(0.4));
  CHECK(column_bottom == doctest::Approx(0.4 + 0.1 + 0.2));  // the columns start on the raft's next layer
  // The raft covers the cap's footprint: the columns' (x, y in [90, 110]) and more.
  double x_min = 1e9, x_max = -1e9;
  for (const auto& m : r.g.moves)
    if (extrudes(m) && m.layer == 0) x_min = std::min(x_min, m.x), x_max = std::max(x_max, m.x);
  CHECK(x_min < 90);
  CHECK(x_max > 110);
}

TEST_CASE("support: steps narrowing upwards say no overhang, the same steps widening say each step's") {
  // Squares of 20, 16, 12 and 8 mm, 1 mm tall each, stacked: narrowing, every layer lies wholly
  // on the one below (the overhang test answers that without growing the layer below or a
  // difference); widening, each step's first layer leans 2 mm out all round. The amounts are
  // what the overhang test said before it skipped the covered islands (18 mm² a step: the
  // 1.8 mm rings less what their lines bridge).
  auto steps = [](bool narrowing) {
    geo::Mesh m;
    for (int k = 0; k < 4; ++k) {
      const double s = narrowing ? 20 - 4 * k : 8 + 4 * k;
      geo::append(m, geo::box({s, s, 1}, {(20 - s) / 2, (20 - s) / 2, static_cast<double>(k)}));
    }
    return m;
  };
  test::TempDir dir("support-steps");
  Run up = run(dir, "narrowing", steps(true), {});
  REQUIRE(up.result.ok());
  CHECK_FALSE(has_warning(up, "unsupported-overhang"));
  Run out = run(dir, "widening", steps(false), {});
  REQUIRE(out.result.ok());
  REQUIRE(has_warning(out, "unsupported-overhang"));
  for (const auto& w : out.warnings)
    if (w.code == "unsupported-overhang") {
      CHECK(w.message.find("18 mm² of overhang printed in the air here, 53 mm² on 3 layers in all") !=
            std::string::npos);
    }
}
