// End to end: generated meshes through `tranche slice` (run_slice) to G-code, checked as a
// printer would see it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <fstream>
#include <set>

#include "gcode_reader.h"
#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "apps/slice_command.h"
#include "geometry/slice/layer_heights.h"
#include "geometry/slice/simple_islands.h"
#include "geometry/slice/slicer.h"
#include "geometry/slice/topology.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/edge_grid.h"
#include "tests/support/fixtures.h"

using namespace tranche;
namespace fs = std::filesystem;

namespace {

struct Sliced {
  test::Gcode gcode;
  std::vector<geo::Layer> layers;  // the model's layers, for geometric checks
  geo::Point shift;                // model units -> bed units
};

std::string write_mesh(const test::TempDir& dir, const std::string& name, const geo::Mesh& mesh) {
  std::string path = (dir / name).string();
  REQUIRE(geo::write_stl_binary(path, mesh).ok());
  return path;
}

// Slices `mesh` with the given --set options into dir/NAME.gcode and re-slices the mesh the same
// way for the geometric checks.
Sliced slice(const test::TempDir& dir, const std::string& name, const geo::Mesh& mesh,
             std::vector<std::pair<std::string, std::string>> sets = {},
             const std::string& printer = "generic-marlin") {
  pipeline::SliceOptions o;
  o.quiet = true;
  o.printer = printer;
  o.model = write_mesh(dir, name + ".stl", mesh);
  o.output_gcode = (dir / (name + ".gcode")).string();
  o.sets = std::move(sets);
  Report report;
  auto r = app::slice(o, report);
  REQUIRE_MESSAGE(r.ok(), (r.ok() ? "" : r.error().to_string()));
  Sliced s;
  s.gcode = test::read_gcode(o.output_gcode);
  geo::Mesh m = mesh;
  auto b = m.bbox();
  m.transform(1.0, {0, 0, -b.min.z});
  auto layers = geo::plan_layer_heights(b.max.z - b.min.z, {});
  REQUIRE(layers.ok());
  Report r2;
  REQUIRE(geo::slice_mesh(m, geo::build_topology(m), *layers, {}, r2).ok());
  REQUIRE(geo::make_islands(*layers).ok());
  s.layers = std::move(*layers);
  s.shift = geo::Point(geo::to_units(100 - 0.5 * (b.min.x + b.max.x)),
                       geo::to_units(100 - 0.5 * (b.min.y + b.max.y)));
  return s;
}

geo::Rings material(const geo::Layer& l) {
  geo::Rings r;
  for (const auto& isl : l.islands) {
    r.push_back(isl.shape.outer);
    for (const auto& h : isl.shape.holes) r.push_back(h);
  }
  return r;
}

bool is_perimeter(const std::string& t) { return t == "External perimeter" || t == "Perimeter"; }

}  // namespace

SCENARIO("a box sliced with the defaults") {
  test::TempDir dir("e2e-box");
  GIVEN("a 20 × 20 × 10 mm box") {
    auto s = slice(dir, "box", geo::box({20, 20, 10}));
    const auto& g = s.gcode;
    THEN("it has one layer per 0.2 mm, announced in the header, at the right heights") {
      CHECK(g.layer_count_header == 50);
      CHECK(g.layer_z.size() == 50);
      CHECK(g.layer_z.at(0) == doctest::Approx(0.2));
      CHECK(g.layer_z.at(49) == doctest::Approx(10.0));
    }
    THEN("absolute E only grows within a layer, except retractions that are undone before extruding") {
      CHECK_FALSE(g.relative_e);
      double last = -1e9;
      int layer = -2;
      bool retracted = false;
      for (const auto& m : g.moves) {
        if (!m.has_e) continue;
        if (m.layer != layer) layer = m.layer, last = -1e9, retracted = false;
        if (!m.has_xy) {  // retraction or unretraction
          retracted = m.de < 0;
          continue;
        }
        CHECK_FALSE(retracted);
        CHECK(m.e >= last);
        last = m.e;
      }
    }
    THEN("every layer has its external perimeter, and the first and last layers are solid") {
      std::set<int> with_outer;
      for (const auto& m : g.moves)
        if (m.has_e && m.de > 0 && m.type == "External perimeter") with_outer.insert(m.layer);
      CHECK(with_outer.size() == 50);
      CHECK(g.contains(";TYPE:Top solid infill"));
      CHECK(g.contains(";TYPE:Internal infill"));
      CHECK(g.contains(";TYPE:Skirt/Brim"));  // skirt_loops = 1 by default
    }
    THEN("no extrusion leaves the part (its slice grown by half a bead)") {
      std::vector<toolpath::EdgeGrid> grids;
      for (const auto& l : s.layers) grids.emplace_back(toolpath::offset(material(l), 0.225 + 0.01));
      int outside = 0, checked = 0;
      for (const auto& m : g.moves) {
        if (!m.has_xy || m.de <= 0 || m.type == "Skirt/Brim" || m.layer < 0) continue;
        geo::Point p = geo::to_point(m.x, m.y);
        p.X -= s.shift.X;
        p.Y -= s.shift.Y;
        ++checked;
        if (!grids[static_cast<size_t>(m.layer)].inside(p)) ++outside;
      }
      CHECK(checked > 1000);
      CHECK(outside == 0);
    }
    THEN("the header's filament matches the moves") {
      auto at = g.text.rfind("; filament used [mm] = ");
      REQUIRE(at != std::string::npos);
      CHECK(std::stod(g.text.substr(at + 23)) == doctest::Approx(g.filament()).epsilon(1e-3));
    }
  }
}

SCENARIO("no extrusion move goes nowhere") {
  test::TempDir dir("e2e-zero");
  // The demo model had 188 moves to the point the nozzle was already at (as written, to the
  // micrometre): points closer than that in a path, or a path starting where the travel ended.
  auto s = slice(dir, "demo", geo::demo_model());
  int zero = 0, extrusions = 0;
  for (const auto& m : s.gcode.moves) {
    if (!m.has_xy || !m.has_e) continue;
    ++extrusions;
    if (m.x == m.x0 && m.y == m.y0) ++zero;
  }
  CHECK(extrusions > 10000);
  CHECK(zero == 0);
}

SCENARIO("perimeters follow real borders only") {
  test::TempDir dir("e2e-cuts");
  GIVEN("a plate with a grid of holes, whose fill is cut into many cells") {
    auto s = slice(dir, "plate", geo::plate_with_holes(40, 30, 2, 4, 3, 2.5, 32), {{"skirt_loops", "0"}});
    THEN("every perimeter move runs at one or two bead spacings from the outline or a hole") {
      const double s1 = 0.225, s2 = 0.225 + (0.45 - 0.2 * (1 - M_PI / 4));
      int far = 0, checked = 0;
      for (const auto& m : s.gcode.moves) {
        if (!m.has_xy || m.de <= 0 || !is_perimeter(m.type)) continue;
        geo::Point mid = geo::to_point(0.5 * (m.x0 + m.x) - geo::to_mm(s.shift.X),
                                       0.5 * (m.y0 + m.y) - geo::to_mm(s.shift.Y));
        const auto& layer = s.layers[static_cast<size_t>(m.layer)];
        double best = 1e9;
        for (const auto& r : material(layer))
          for (size_t i = 0; i < r.size(); ++i) {
            const auto &a = r[i], &b = r[(i + 1) % r.size()];
            double ax = geo::to_mm(a.X), ay = geo::to_mm(a.Y), bx = geo::to_mm(b.X), by = geo::to_mm(b.Y);
            double px = geo::to_mm(mid.X), py = geo::to_mm(mid.Y);
            double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
            double t = l2 > 0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / l2, 0.0, 1.0) : 0;
            best = std::min(best, std::hypot(px - ax - t * dx, py - ay - t * dy));
          }
        ++checked;
        bool on_loop = std::abs(best - s1) < 0.05 || std::abs(best - s2) < 0.05;
        if (!on_loop && best > s2 + 0.12) ++far;  // corners of the second loop are rounded a little
      }
      CHECK(checked > 500);
      CHECK(far == 0);
    }
    THEN("the fill has artificial cuts: more zig-zags than islands, yet no perimeter along them") {
      int fills = 0;
      for (size_t i = 1; i < s.gcode.moves.size(); ++i) {
        const auto& a = s.gcode.moves[i - 1];
        const auto& b = s.gcode.moves[i];
        if (b.de > 0 && b.has_xy && (b.type == "Internal infill" || b.type == "Solid infill") &&
            !(a.de > 0 && a.has_xy))
          ++fills;
      }
      CHECK(fills > static_cast<int>(s.layers.size()));
    }
  }
}

SCENARIO("print order: infill first, running into the inner perimeter; the outer one last") {
  test::TempDir dir("e2e-order");
  auto is_fill = [](const std::string& t) { return t.find("infill") != std::string::npos; };
  GIVEN("a 20 × 20 × 3 mm box with the defaults") {
    auto s = slice(dir, "box", geo::box({20, 20, 3}), {{"skirt_loops", "0"}});
    THEN("on every layer the infill comes first, the inner perimeter follows without a travel, "
         "and the outer perimeter ends the layer") {
      int layers = 0, linked = 0;
      std::map<int, std::vector<const test::Move*>> by_layer;
      for (const auto& m : s.gcode.moves)
        if (m.layer >= 0 && m.has_xy) by_layer[m.layer].push_back(&m);
      for (const auto& [layer, moves] : by_layer) {
        ++layers;
        std::string seen;  // kinds in print order: f(ill), p(erimeter), o(uter)
        bool travel_since_fill = false;
        for (const test::Move* m : moves) {
          if (m->de <= 0) {
            if (!seen.empty() && seen.back() == 'f') travel_since_fill = true;
            continue;
          }
          char k = is_fill(m->type) ? 'f' : m->type == "Perimeter" ? 'p' : 'o';
          if (k == 'p' && !seen.empty() && seen.back() == 'f' && !travel_since_fill) ++linked;
          if (seen.empty() || seen.back() != k) seen += k;
          if (k == 'f') travel_since_fill = false;
        }
        CHECK_MESSAGE(seen == "fpo", "layer ", layer);
      }
      CHECK(layers == 15);
      CHECK(linked == layers);
    }
  }
  GIVEN("the same box with infill_first = false") {
    auto s = slice(dir, "box2", geo::box({20, 20, 3}), {{"skirt_loops", "0"}, {"infill_first", "false"}});
    THEN("each layer starts with its perimeters, inner one first") {
      std::map<int, std::string> first;
      for (const auto& m : s.gcode.moves)
        if (m.layer >= 0 && m.has_xy && m.de > 0 && !first.count(m.layer)) first[m.layer] = m.type;
      CHECK(first.size() == 15);
      for (const auto& [layer, type] : first) CHECK_MESSAGE(type == "Perimeter", "layer ", layer);
    }
  }
  GIVEN("two boxes 10 mm apart") {
    geo::Mesh m = geo::box({20, 20, 2});
    geo::append(m, geo::translated(geo::box({20, 20, 2}), {30, 0, 0}));
    auto s = slice(dir, "two", m, {{"skirt_loops", "0"}});
    THEN("a layer starts on the box where the one below ended, so only the hop between the boxes "
         "retracts") {
      std::map<int, std::pair<double, double>> first_x, last_x;  // layer -> x of first / last extrusion
      int retractions = 0;
      for (const auto& mv : s.gcode.moves) {
        if (mv.layer < 0) continue;
        if (mv.has_e && !mv.has_xy && mv.de < 0) ++retractions;
        if (!mv.has_xy || mv.de <= 0) continue;
        if (!first_x.count(mv.layer)) first_x[mv.layer] = {mv.x, mv.y};
        last_x[mv.layer] = {mv.x, mv.y};
      }
      REQUIRE(first_x.size() == 10);
      for (int l = 1; l < 10; ++l) {
        bool left_before = last_x[l - 1].first < 100, left_now = first_x[l].first < 100;
        CHECK_MESSAGE(left_before == left_now, "layer ", l);
      }
      CHECK(retractions == 1 + 10);  // the arrival from the start G-code, then one hop per layer
    }
  }
}

SCENARIO("travels comb around holes instead of retracting") {
  test::TempDir dir("e2e-comb");
  GIVEN("a plate with a grid of holes, and no retraction forced by a travel's length") {
    auto s = slice(dir, "plate", geo::plate_with_holes(40, 30, 2, 4, 3, 2.5, 32),
                   {{"skirt_loops", "0"}, {"retract_long_travel", "1000"}});
    // Travels in order, each with whether the filament was retracted during it.
    struct Travel {
      test::Move m;
      bool retracted;
    };
    std::vector<Travel> travels;
    bool retracted = false;
    for (const auto& m : s.gcode.moves) {
      if (m.has_e && !m.has_xy) retracted = m.de < 0;
      if (m.has_xy && m.de <= 0 && m.layer >= 0 && m.type != "Custom") travels.push_back({m, retracted});
    }
    THEN("a travel that does not retract never leaves the part (its slice, grown by 10 µm)") {
      std::vector<toolpath::EdgeGrid> grids;
      for (const auto& l : s.layers) grids.emplace_back(toolpath::offset(material(l), 0.01));
      int leaving = 0, dry = 0;
      for (const auto& t : travels) {
        if (t.retracted) continue;
        ++dry;
        geo::Point a = geo::to_point(t.m.x0, t.m.y0), b = geo::to_point(t.m.x, t.m.y);
        a.X -= s.shift.X, a.Y -= s.shift.Y, b.X -= s.shift.X, b.Y -= s.shift.Y;
        if (grids[static_cast<size_t>(t.m.layer)].crosses(a, b)) ++leaving;
      }
      CHECK(dry > 100);
      CHECK(leaving == 0);
    }
    THEN("it never retracts: the plate is one island, so every travel is combed") {
      int retractions = 0;
      for (const auto& m : s.gcode.moves)
        if (m.layer >= 0 && m.type != "Custom" && m.has_e && !m.has_xy && m.de < 0) ++retractions;
      CHECK(retractions == 0);
    }
  }
}

SCENARIO("a solid zig-zag's connectors along the border lay half a bead") {
  test::TempDir dir("e2e-connectors");
  GIVEN("a 20 × 20 mm box, whose first layer is solid at 45° and whose walls run along x and y") {
    auto s = slice(dir, "box", geo::box({20, 20, 2}), {{"skirt_loops", "0"}});
    // E per mm of the first layer's solid moves: the lines run diagonally, the connectors that
    // join them run along the (axis-parallel) border, over the ends of the lines they join.
    double line_e = 0, line_mm = 0, conn_e = 0, conn_mm = 0;
    for (const auto& m : s.gcode.moves) {
      if (m.layer != 0 || !m.has_xy || m.de <= 0 || m.type != "Solid infill") continue;
      double dx = m.x - m.x0, dy = m.y - m.y0, len = std::hypot(dx, dy);
      if (len < 1e-3) continue;
      if (std::abs(std::abs(dx) - std::abs(dy)) < 0.02 * len) {
        line_e += m.de, line_mm += len;
      } else if (std::abs(dx) < 1e-3 || std::abs(dy) < 1e-3) {
        conn_e += m.de, conn_mm += len;
      }
    }
    THEN("a connector lays half the plastic per mm of a line") {
      REQUIRE(line_mm > 100);
      REQUIRE(conn_mm > 5);
      CHECK(conn_e / conn_mm == doctest::Approx(0.5 * line_e / line_mm).epsilon(0.03));
    }
  }
}

SCENARIO("--set changes what it should") {
  test::TempDir dir("e2e-set");
  const geo::Mesh cube = geo::box({15, 15, 4});
  auto base = slice(dir, "base", cube, {{"skirt_loops", "0"}});
  WHEN("layer_height is 0.1 mm, with twice the solid layers") {
    auto s =
        slice(dir, "fine", cube,
              {{"skirt_loops", "0"}, {"layer_height", "0.1mm"}, {"top_layers", "6"}, {"bottom_layers", "6"}});
    THEN("there are twice the layers and about the same plastic") {
      CHECK(s.gcode.layer_count_header == 40);
      CHECK(s.gcode.filament() == doctest::Approx(base.gcode.filament()).epsilon(0.06));
    }
  }
  WHEN("perimeters is 3") {
    auto s = slice(dir, "p3", cube, {{"skirt_loops", "0"}, {"perimeters", "3"}});
    THEN("each layer has three loops") {
      auto loops = [](const test::Gcode& g, int layer) {
        int n = 0;
        for (size_t i = 1; i < g.moves.size(); ++i)
          if (g.moves[i].layer == layer && is_perimeter(g.moves[i].type) && g.moves[i].de > 0 &&
              !(g.moves[i - 1].de > 0 && is_perimeter(g.moves[i - 1].type)))
            ++n;
        return n;
      };
      CHECK(loops(base.gcode, 10) == 2);
      CHECK(loops(s.gcode, 10) == 3);
    }
  }
  WHEN("infill_density is 50%") {
    auto s = slice(dir, "dense", cube, {{"skirt_loops", "0"}, {"infill_density", "50%"}});
    THEN("more plastic goes in") { CHECK(s.gcode.filament() > 1.15 * base.gcode.filament()); }
  }
  WHEN("speed is 33 mm/s and the fan 40%") {
    auto s = slice(dir, "slow", cube, {{"skirt_loops", "0"}, {"speed", "33"}, {"fan", "40%"}});
    THEN("every extrusion runs at F1980 and the fan at 40% (102/255)") {
      for (const auto& line : s.gcode.lines)
        if (line.rfind("G1 X", 0) == 0 && line.find(" E") != std::string::npos &&
            line.find(" F") != std::string::npos)
          CHECK(line.substr(line.find(" F")) == " F1980");
      CHECK(s.gcode.contains("M106 S102"));
      CHECK_FALSE(s.gcode.contains("M106 S255"));
    }
  }
  WHEN("the printer is a Klipper one and the temperatures change") {
    auto s = slice(dir, "klipper", cube, {{"skirt_loops", "0"}, {"nozzle_temp", "225C"}}, "klipper");
    THEN("the printer's start macro gets the new temperature") {
      CHECK(s.gcode.contains(";FLAVOR:Klipper"));
      CHECK(s.gcode.contains("PRINT_START BED=60 EXTRUDER=225"));
      CHECK(s.gcode.contains("PRINT_END"));
      CHECK_FALSE(s.gcode.contains("M109"));  // the macro heats
    }
  }
  WHEN("skirt_loops is 2") {
    auto s = slice(dir, "skirt", cube, {{"skirt_loops", "2"}});
    THEN("a skirt is printed, on the first layer only") {
      std::set<int> layers;
      for (const auto& m : s.gcode.moves)
        if (m.de > 0 && m.type == "Skirt/Brim") layers.insert(m.layer);
      CHECK(layers == std::set<int>{0});
    }
  }
}

SCENARIO("relative and absolute E describe the same extrusion") {
  test::TempDir dir("e2e-rel");
  const geo::Mesh part = geo::cylinder(8, 3, 48);
  auto abs = slice(dir, "abs", part);
  auto rel = slice(dir, "rel", part, {{"relative_e", "true"}});
  CHECK(rel.gcode.relative_e);
  CHECK(rel.gcode.contains("M83"));
  REQUIRE(abs.gcode.moves.size() == rel.gcode.moves.size());
  for (size_t i = 0; i < abs.gcode.moves.size(); ++i) {
    const auto &a = abs.gcode.moves[i], &r = rel.gcode.moves[i];
    CHECK(a.x == r.x);
    CHECK(a.y == r.y);
    if (a.has_e) CHECK(a.de == doctest::Approx(r.de).epsilon(1e-9));
  }
  CHECK(abs.gcode.filament() == doctest::Approx(rel.gcode.filament()).epsilon(1e-9));
}

SCENARIO("a failing write leaves no file behind") {
  test::TempDir dir("e2e-fail");
  // The end G-code fails (a division by zero at run time) after everything else is written.
  std::ofstream(dir / "late.rules")
      << "rule { after print { gcode \"M117 {1 mm / (print.height - print.height)}\" } }\n";
  pipeline::SliceOptions o;
  o.quiet = true;
  o.model = write_mesh(dir, "cube.stl", geo::box({10, 10, 2}));
  o.output_gcode = (dir / "out.gcode").string();
  o.rules = {(dir / "late.rules").string()};
  GIVEN("no earlier output") {
    Report report;
    auto r = app::slice(o, report);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().where.find("late.rules:1:") != std::string::npos);
    CHECK(r.error().message.find("division by zero") != std::string::npos);
    CHECK_FALSE(fs::exists(o.output_gcode));
  }
  GIVEN("an earlier output") {
    std::ofstream(o.output_gcode) << "; the previous print\n";
    Report report;
    REQUIRE_FALSE(app::slice(o, report).ok());
    std::ifstream in(o.output_gcode);
    std::string first;
    std::getline(in, first);
    CHECK(first == "; the previous print");  // untouched
  }
  int others = 0;
  for (const auto& e : fs::directory_iterator(dir.path())) {
    std::string n = e.path().filename().string();
    if (n != "late.rules" && n != "cube.stl" && n != "out.gcode") ++others;  // no temporaries
  }
  CHECK(others == 0);
}
