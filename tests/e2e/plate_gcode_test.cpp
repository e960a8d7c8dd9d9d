// End to end: plates of several models, 3MF and OBJ input, and the bed check, through
// `tranche slice` (app::slice) to G-code; and the command line's spellings (parse_slice_args).
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "apps/slice_args.h"
#include "apps/slice_command.h"
#include "gcode_reader.h"
#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "geometry/plate/threemf_write.h"
#include "plate_helpers.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::test::plate_e2e;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> words(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

}  // namespace

TEST_CASE("plate e2e: two models are arranged on the bed and print apart") {
  test::TempDir dir("plate-two");
  plate::PlateOptions p;
  p.files = {(dir / "block.stl").string(), (dir / "pin.stl").string()};
  REQUIRE(geo::write_stl_binary(p.files[0], geo::box({30, 20, 4})).ok());
  REQUIRE(geo::write_stl_binary(p.files[1], geo::cylinder(8, 4, 48)).ok());
  Report report;
  auto r = app::slice(options(dir), p, report);
  REQUIRE_MESSAGE(r.ok(), r.error().to_string());
  const test::Gcode g = test::read_gcode((dir / "plate.gcode").string());
  const auto objects = parts(g, 3);
  REQUIRE(objects.size() == 2);
  const Box &a = objects[0], &b = objects[1];
  // Apart by about the spacing (6 mm, less the widths of the outer walls).
  const double gap = std::max({b.min_x - a.max_x, a.min_x - b.max_x, b.min_y - a.max_y, a.min_y - b.max_y});
  CHECK(gap > 4.5);
  for (const Box& o : objects) {
    CHECK(o.min_x > 0);
    CHECK(o.max_x < 200);
    CHECK(o.min_y > 0);
    CHECK(o.max_y < 200);
  }
  CHECK(((a.w() == doctest::Approx(30).epsilon(0.02) && b.w() == doctest::Approx(16).epsilon(0.03)) ||
         (b.w() == doctest::Approx(30).epsilon(0.02) && a.w() == doctest::Approx(16).epsilon(0.03))));
  // The header names the model files.
  CHECK(g.contains(fmt::format("; model: {} + {}\n", p.files[0], p.files[1])));
}

TEST_CASE("plate e2e: a 3MF's build items are sliced where their transforms put them") {
  test::TempDir dir("plate-3mf");
  // An L: a bar 40 × 10 along x with a nub at its +x end towards +y. Turned a quarter
  // counter-clockwise, the bar runs along y and the nub, at its +y end, points towards -x.
  geo::Mesh l = geo::box({40, 10, 3});
  geo::append(l, geo::box({10, 10, 3}, {30, 10, 0}));
  Eigen::Affine3d turned = Eigen::Translation3d(60, 80, 0) * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ());
  Eigen::Affine3d beside = Eigen::Affine3d(Eigen::Translation3d(120, 80, 0));
  const std::string file = (dir / "job.3mf").string();
  REQUIRE(plate::write_3mf(file, {object("L", l, turned), object("cube", geo::box({10, 10, 3}), beside)}).ok());
  plate::PlateOptions p;
  p.files = {file};
  Report report;
  auto r = app::slice(options(dir), p, report);
  REQUIRE_MESSAGE(r.ok(), r.error().to_string());
  const auto objects = parts(test::read_gcode((dir / "plate.gcode").string()), 2);
  REQUIRE(objects.size() == 2);
  const Box &L = objects[0], &cube = objects[1];
  CHECK(L.w() == doctest::Approx(20).epsilon(0.05));  // turned: 20 wide (bar and nub), 40 long in y
  CHECK(L.h() == doctest::Approx(40).epsilon(0.03));
  CHECK(cube.w() == doctest::Approx(10).epsilon(0.05));
  // Each where its build item's transform puts it on the bed: the L turned about its origin at
  // (60, 80) spans x 40..60 (the nub at 40..50 towards -x) and y 80..120; the cube x 120..130,
  // y 80..90 (the walls' extrusions lie half a width inside the outline).
  const double in = 0.25;
  CHECK(L.min_x == doctest::Approx(40 + in).epsilon(0.004));
  CHECK(L.max_x == doctest::Approx(60 - in).epsilon(0.004));
  CHECK(L.min_y == doctest::Approx(80 + in).epsilon(0.004));
  CHECK(L.max_y == doctest::Approx(120 - in).epsilon(0.004));
  CHECK(cube.min_x == doctest::Approx(120 + in).epsilon(0.004));
  CHECK(cube.max_y == doctest::Approx(90 - in).epsilon(0.004));
  // The nub: the L's extrusions in its top 10 mm reach 10 mm further towards -x than the bar below.
  const test::Gcode g = test::read_gcode((dir / "plate.gcode").string());
  double top_min_x = 1e300, low_min_x = 1e300;
  for (const auto& m : g.moves) {
    if (m.layer != 2 || m.de <= 0 || m.type == "Skirt/Brim" || m.x > L.max_x + 1) continue;
    if (m.y > L.max_y - 9) top_min_x = std::min(top_min_x, m.x);
    if (m.y < L.max_y - 11) low_min_x = std::min(low_min_x, m.x);
  }
  CHECK(low_min_x - top_min_x == doctest::Approx(10).epsilon(0.1));
}

TEST_CASE("plate e2e: a model larger than the bed is refused and nothing is written") {
  test::TempDir dir("plate-off-bed");
  const std::string model = (dir / "wide.stl").string();
  REQUIRE(geo::write_stl_binary(model, geo::box({256, 40, 3})).ok());
  pipeline::SliceOptions o = options(dir);
  o.model = model;
  o.export_svg = (dir / "layers.svg").string();
  Report report;
  auto r = app::slice(o, report);
  REQUIRE_FALSE(r.ok());
  CHECK(has(r.error().message, "'wide' is off the bed by 28.0 mm on the left and 28.0 mm on the right"));
  CHECK(has(r.error().message, "--scale 0.78 fits"));
  CHECK_FALSE(fs::exists(dir / "plate.gcode"));
  CHECK_FALSE(fs::exists(dir / "layers.svg"));

  plate::PlateOptions p;
  p.files = {model};
  p.allow_off_bed = true;
  auto anyway = app::slice(o, p, report);
  REQUIRE_MESSAGE(anyway.ok(), anyway.error().to_string());
  CHECK(report.count("plate-off-bed") == 1);
  CHECK(fs::exists(dir / "plate.gcode"));
}

TEST_CASE("plate e2e: every move of every layer is checked against the bed, the skirt's too") {
  test::TempDir dir("plate-skirt-off");
  const std::string model = (dir / "big.stl").string();
  REQUIRE(geo::write_stl_binary(model, geo::box({190, 190, 1})).ok());
  pipeline::SliceOptions o = options(dir);
  o.model = model;
  o.sets = {{"skirt_loops", "1"}, {"skirt_distance", "6"}};  // the object fits; its skirt does not
  Report report;
  auto r = app::slice(o, report);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().where == "layer 0 (z 0.20 mm)");
  CHECK(has(r.error().message, "mm outside the bed (0 to 200 x 0 to 200 mm)"));
  CHECK(has(r.error().message, "--allow-off-bed"));
  CHECK_FALSE(fs::exists(dir / "plate.gcode"));
  o.allow_off_bed = true;
  plate::PlateOptions p;
  p.files = {model};
  p.allow_off_bed = true;
  auto anyway = app::slice(o, p, report);
  REQUIRE_MESSAGE(anyway.ok(), anyway.error().to_string());
  CHECK(report.count("off-bed") == 1);
  CHECK(fs::exists(dir / "plate.gcode"));
}

TEST_CASE("plate e2e: a delta's round bed centred on 0: the model lands on 0, 0") {
  test::TempDir dir("plate-delta");
  const std::string model = (dir / "cube.stl").string();
  REQUIRE(geo::write_stl_binary(model, geo::box({20, 20, 2})).ok());
  pipeline::SliceOptions o = options(dir);
  o.model = model;
  o.sets = {{"bed_shape", "circular"}, {"bed_size_x", "180"}, {"bed_origin_x", "-90"}, {"bed_origin_y", "-90"},
            {"skirt_loops", "0"}};
  Report report;
  auto r = app::slice(o, report);
  REQUIRE_MESSAGE(r.ok(), r.error().to_string());
  auto g = test::read_gcode(o.output_gcode);
  auto ps = parts(g, 1);
  REQUIRE(ps.size() == 1);
  CHECK(0.5 * (ps[0].min_x + ps[0].max_x) == doctest::Approx(0).epsilon(0.01));
  CHECK(0.5 * (ps[0].min_y + ps[0].max_y) == doctest::Approx(0).epsilon(0.01));
  // A cube that fits the bed's square but not its circle is refused.
  REQUIRE(geo::write_stl_binary(model, geo::box({150, 150, 2})).ok());
  CHECK_FALSE(app::slice(o, report).ok());
}

namespace {
// Two boxes, 6 and 4 mm tall, arranged 50 mm apart: the plate the sequential tests print.
struct TwoBoxes {
  plate::PlateOptions p;
  pipeline::SliceOptions o;
};
TwoBoxes two_boxes(const test::TempDir& dir, std::vector<std::pair<std::string, std::string>> sets) {
  TwoBoxes t;
  t.p.files = {(dir / "tall.stl").string(), (dir / "low.stl").string()};
  REQUIRE(geo::write_stl_binary(t.p.files[0], geo::box({15, 15, 6})).ok());
  REQUIRE(geo::write_stl_binary(t.p.files[1], geo::box({15, 15, 4})).ok());
  t.p.arrange = plate::ArrangeMode::Always;
  t.p.spacing_mm = 50;
  t.o = options(dir);
  t.o.model = t.p.files[0];
  t.o.sets = std::move(sets);
  return t;
}
}  // namespace

TEST_CASE("plate e2e: print_order = sequential prints each object whole, lowest first, rising between them") {
  test::TempDir dir("plate-sequential");
  auto [p, o] = two_boxes(dir, {{"print_order", "sequential"}, {"skirt_loops", "0"}});
  Report report;
  auto r = app::slice(o, p, report);
  REQUIRE_MESSAGE(r.ok(), r.error().to_string());
  auto g = test::read_gcode(o.output_gcode);
  // z climbs to the low object's top, falls back to the first layer, then climbs to the tall one's.
  std::vector<double> z;
  for (const auto& line : g.lines)
    if (line.rfind(";Z:", 0) == 0) z.push_back(std::stod(line.substr(3)));
  REQUIRE(z.size() == 20 + 30);
  CHECK(z[19] == doctest::Approx(4));
  CHECK(z[20] == doctest::Approx(0.2));
  CHECK(z.back() == doctest::Approx(6));
  // Between them the head rises above the low object before it crosses.
  CHECK(g.contains("; next object: up, across, then down at its first point\nG92 E0\nG1 E-0.8 F2100\nG1 Z5 F9000\n"));
  // Each object's extrusions are all on one side of the object change: the low one's before it.
  size_t change = 0;
  for (size_t k = 0; k < g.lines.size(); ++k)
    if (g.lines[k].rfind("; next object", 0) == 0) change = k;
  REQUIRE(change > 0);
  Box before, after;
  for (const auto& m : g.moves)
    if (m.has_xy && m.de > 0) (m.line < change ? before : after).add(m.x, m.y);
  CHECK(before.w() < 16);  // one 15 mm object each
  CHECK(after.w() < 16);
  CHECK(std::abs(0.5 * (before.min_x + before.max_x) - 0.5 * (after.min_x + after.max_x)) > 50);
  // Too close for the head's reach: refused, naming both.
  p.spacing_mm = 6;
  auto close = app::slice(o, p, report);
  REQUIRE_FALSE(close.ok());
  CHECK(has(close.error().message, "'tall' and 'low' are"));
  CHECK(has(close.error().message, "extruder_clearance_radius"));
  // Lower than the gantry, but the low one is not: refused.
  p.spacing_mm = 50;
  o.sets.push_back({"extruder_clearance_height", "3"});
  auto gantry = app::slice(o, p, report);
  REQUIRE_FALSE(gantry.ok());
  CHECK(has(gantry.error().message, "'low' is 4.0 mm tall and 'tall' is printed after it"));
}

TEST_CASE("plate e2e: OBJ input, copies and a turn") {
  test::TempDir dir("plate-obj");
  std::ofstream(dir / "bar.obj") << "v 0 0 0\nv 30 0 0\nv 30 8 0\nv 0 8 0\nv 0 0 3\nv 30 0 3\nv 30 8 3\nv 0 8 3\n"
                                    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";
  plate::PlateOptions p;
  p.files = {(dir / "bar.obj").string()};
  p.copies = {{"", 3}};
  p.rotate = {{"", 90}};
  Report report;
  auto r = app::slice(options(dir), p, report);
  REQUIRE_MESSAGE(r.ok(), r.error().to_string());
  const auto objects = parts(test::read_gcode((dir / "plate.gcode").string()), 2);
  REQUIRE(objects.size() == 3);
  for (const Box& b : objects) {
    CHECK(b.w() == doctest::Approx(8).epsilon(0.08));
    CHECK(b.h() == doctest::Approx(30).epsilon(0.03));
  }
}

TEST_CASE("plate e2e: the content decides: a 3MF named .svg is a plate, not a drawing") {
  test::TempDir dir("plate-named");
  const std::string file = (dir / "looks-like-a-drawing.svg").string();
  REQUIRE(plate::write_3mf(file, {object("cube", geo::box({10, 10, 3}), Eigen::Affine3d(Eigen::Translation3d(50, 50, 0)))})
              .ok());
  pipeline::SliceOptions o = options(dir);
  o.model = file;
  Report report;
  auto r = app::slice(o, report);
  REQUIRE_MESSAGE(r.ok(), r.error().to_string());
  const auto objects = parts(test::read_gcode((dir / "plate.gcode").string()), 2);
  REQUIRE(objects.size() == 1);
  CHECK(objects[0].w() == doctest::Approx(10).epsilon(0.05));
}

TEST_CASE("command line: every spelling of tranche slice, old and new") {
  auto parse = [](const std::string& args) { return app::parse_slice_args(words(args), false); };
  auto a = parse("m.stl -o out.gcode --rules a.rules --rules b.rules --printer ender3 --material petg --stdlib s "
                 "--set layer_height=0.15 --set speed=40 --export-svg l.svg --export-layers l.json --overlap boolean "
                 "--fill-angle-script f.py --svg-layers 4 --svg-height 3 --svg-tolerance 0.02 --background black "
                 "--strict -q");
  REQUIRE_MESSAGE(a.ok(), a.error().to_string());
  const auto& s = a->slice;
  CHECK(s.model == "m.stl");
  CHECK(s.output_gcode == "out.gcode");
  CHECK(s.rules == std::vector<std::string>{"a.rules", "b.rules"});
  CHECK(s.printer == "ender3");
  CHECK(s.material == "petg");
  CHECK(s.stdlib_dir == "s");
  CHECK(s.sets.size() == 2);
  CHECK(s.sets[1].second == "40");
  CHECK(s.export_svg == "l.svg");
  CHECK(s.export_layers == "l.json");
  CHECK(s.overlap == pipeline::OverlapMode::Boolean);
  CHECK(s.fill_angle_script == "f.py");
  CHECK(s.svg_layers == 4);
  CHECK(s.svg_height_mm == 3);
  CHECK(s.svg_tolerance_mm == 0.02);
  CHECK(s.background == "black");
  CHECK(s.strict);
  CHECK(s.quiet);
  CHECK(parse("--output x.gcode --quiet m.stl")->slice.output_gcode == "x.gcode");
  CHECK(parse("m.stl -o a -o b")->slice.output_gcode == "b");  // the last one wins, as before
  CHECK(parse("-h")->help);
  auto limits = parse("m.stl --max-memory 500 --max-gcode-size 10 --script-timeout 0.5");
  REQUIRE_MESSAGE(limits.ok(), limits.error().to_string());
  CHECK(limits->max_memory_mb == 500);
  CHECK(limits->slice.max_gcode_mb == 10);
  CHECK(limits->slice.script_timeout_s == 0.5);
  CHECK(parse("m.stl")->slice.max_gcode_mb == 2048);

  auto p = parse("a.stl b.3mf c.obj --copies 2 --scale lid=1,1,2 --scale 50% --rotate -90 --rotate-x lid=90 "
                 "--rotate-y 2=45 --lay-flat --scale-to-fit --move -10,5 --center lid=100,80 --arrange --spacing 3 "
                 "--allow-off-bed");
  REQUIRE_MESSAGE(p.ok(), p.error().to_string());
  const auto& q = p->plate;
  CHECK(q.files == std::vector<std::string>{"a.stl", "b.3mf", "c.obj"});
  CHECK(q.copies[0].value == 2);
  CHECK(q.scale[0].selector == "lid");
  CHECK(q.scale[0].value.z() == 2);
  CHECK(q.scale[1].value.x() == 0.5);
  CHECK(q.rotate[0].value == -90);
  CHECK(q.rotate_y[0].selector == "2");
  CHECK(q.move[0].value.x() == -10);
  CHECK(q.center[0].selector == "lid");
  CHECK(q.lay_flat);
  CHECK(q.scale_to_fit);
  CHECK(q.arrange == plate::ArrangeMode::Always);
  CHECK(q.spacing_mm == 3);
  CHECK(q.allow_off_bed);
  CHECK(parse("a.stl --no-arrange")->plate.arrange == plate::ArrangeMode::Never);
}

TEST_CASE("command line: usage errors say what an option needs") {
  auto error = [](const std::string& args) {
    auto r = app::parse_slice_args(words(args), true);
    REQUIRE_FALSE(r.ok());
    return r.error().message;
  };
  CHECK(error("") == "missing MODEL");
  CHECK(error("m.stl -o") == "--output needs a file name");
  CHECK(error("m.stl --rules") == "--rules needs a file name");
  CHECK(error("m.stl --bogus") == "unknown option '--bogus'");
  CHECK(error("m.stl --set speed") == "--set needs KEY=VALUE, got 'speed'");
  CHECK(error("m.stl --overlap sideways") == "--overlap must be additive, boolean or subtractive, not 'sideways'");
  CHECK(error("m.stl --svg-layers 0") == "--svg-layers needs a positive number, not '0'");
  CHECK(error("m.stl --svg-layers 2.5") == "--svg-layers needs a whole number of layers, not '2.5'");
  CHECK(error("m.stl --svg-layers 1000000000") == "--svg-layers takes at most 100000 layers, not '1000000000'");
  CHECK(error("m.stl --svg-height 1e9") == "--svg-height takes at most 100000 mm, not '1e9'");
  CHECK(error("m.stl --max-gcode-size -1") == "--max-gcode-size needs a whole number of MB, not '-1'");
  CHECK(error("m.stl --max-memory 10") == "--max-memory takes 64 to 1073741824 MB, not '10'");
  CHECK(error("m.stl --max-memory lots") == "--max-memory needs a whole number of MB, not 'lots'");
  CHECK(error("m.stl --script-timeout 0") == "--script-timeout needs a number of seconds from 0.001 to 86400, not '0'");
  CHECK(has(error("m.stl --scale 0"), "--scale factors must be positive"));
  CHECK(has(error("m.stl --rotate quarter"), "--rotate needs an angle in degrees"));
  CHECK(has(error("m.stl --move 10"), "--move needs X,Y in mm"));
  CHECK(has(error("m.stl --copies 0"), "--copies needs a whole number from 1 to 1000"));
  CHECK(has(error("m.stl --spacing -1"), "--spacing needs a distance in mm"));
  CHECK(error("m.stl --arrange --no-arrange") == "--arrange and --no-arrange contradict each other");
}

TEST_CASE("plate e2e: a raft under a sequential plate is refused before any file is written") {
  test::TempDir dir("plate-sequential-raft");
  auto [p, o] = two_boxes(dir, {{"print_order", "sequential"}, {"raft_layers", "2"}});
  Report report;
  auto r = app::slice(o, p, report);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().message.find("raft_layers and print_order = sequential") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(o.output_gcode));
}
