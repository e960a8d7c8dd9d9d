// End to end: `tranche slice drawing.svg` (flat drawings, layer stacks from --export-svg, edited
// stacks) and --fill-angle-script through run_slice.
#include <doctest/doctest.h>

#include <pugixml.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "geometry/fillangle/fill_angle.h"
#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "apps/slice_command.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using tranche::pipeline::OverlapMode;
using tranche::pipeline::SliceOptions;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

std::string write(const test::TempDir& dir, const std::string& name, const std::string& text) {
  std::string path = (dir / name).string();
  std::ofstream(path) << text;
  return path;
}

std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// The layer lines of a tranche-layers JSON file: everything after the header (which names the source).
std::vector<std::string> layer_lines(const std::string& path) {
  auto l = lines(path);
  auto first =
      std::find_if(l.begin(), l.end(), [](const std::string& s) { return contains(s, "\"index\""); });
  return {first, l.end()};
}

size_t count(const std::vector<std::string>& ls, const std::string& part) {
  return static_cast<size_t>(
      std::count_if(ls.begin(), ls.end(), [&](const std::string& s) { return contains(s, part); }));
}

Result<pipeline::SliceSummary> run(SliceOptions o, Report& report) {
  o.quiet = true;
  return tranche::app::slice(o, report);
}

const std::string kDrawing =
    R"(<svg xmlns="http://www.w3.org/2000/svg" width="40mm" height="20mm" viewBox="0 0 40 20">
  <rect width="40" height="20" fill="black"/>
  <circle cx="10" cy="10" r="5" fill="white"/>
  <rect x="25" y="5" width="10" height="10" fill="#fff"/>
</svg>
)";

}  // namespace

TEST_CASE("slicing a flat SVG drawing") {
  test::TempDir dir("svg-pipeline");
  SliceOptions o;
  o.model = write(dir, "drawing.svg", kDrawing);
  o.export_layers = (dir / "out.json").string();
  Report report;
  SUBCASE("ten layers by default, additive: the full plate on each") {
    auto r = run(o, report);
    REQUIRE_MESSAGE(r.ok(), r.error().to_string());
    CHECK(r->layers == 10);
    CHECK(r->triangles == 0);
    auto ls = layer_lines(o.export_layers);
    CHECK(count(ls, "\"area\": 800, \"islands\"") == 10);
    CHECK(count(ls, "\"z_top\": 2,") == 1);  // the top of layer 9: 10 x 0.2 mm
  }
  SUBCASE("subtractive, by height") {
    o.overlap = OverlapMode::Subtractive;
    o.svg_height_mm = 1;
    auto r = run(o, report);
    REQUIRE_MESSAGE(r.ok(), r.error().to_string());
    CHECK(r->layers == 5);
    auto ls = layer_lines(o.export_layers);
    CHECK(count(ls, "\"holes\": [[") == 5);  // one island per layer, with two holes
    CHECK(count(ls, "\"area\": 800") == 0);
  }
  SUBCASE("a given layer count and a coarser tolerance") {
    o.svg_layers = 3;
    o.svg_tolerance_mm = 0.5;
    o.overlap = OverlapMode::Subtractive;
    o.background = "black";  // the black plate erases nothing below it; white adds
    auto r = run(o, report);
    REQUIRE_MESSAGE(r.ok(), r.error().to_string());
    CHECK(r->layers == 3);
    CHECK(count(layer_lines(o.export_layers), "\"outer\"") == 6);  // a disc and a square per layer
  }
  // Heights come from the cascade as for an STL: --set layer_height was ignored for drawings.
  SUBCASE("layer heights from the cascade, by layer count") {
    o.svg_layers = 4;
    o.sets = {{"layer_height", "0.1"}};
    auto r = run(o, report);
    REQUIRE_MESSAGE(r.ok(), r.error().to_string());
    CHECK(r->layers == 4);
    auto ls = layer_lines(o.export_layers);
    CHECK(count(ls, "\"z_top\": 0.1,") == 1);  // --set layer_height wins on layer 0 too, as for an STL
    CHECK(count(ls, "\"z_top\": 0.4,") == 1);
  }
  SUBCASE("layer heights from the cascade, by height") {
    o.svg_height_mm = 1;
    o.sets = {{"layer_height", "0.1"}};
    auto r = run(o, report);
    REQUIRE_MESSAGE(r.ok(), r.error().to_string());
    CHECK(r->layers == 10);
    CHECK(count(layer_lines(o.export_layers), "\"z_top\": 1,") == 1);
  }
}

TEST_CASE("bad SVG input fails with the file's location and writes nothing") {
  test::TempDir dir("svg-pipeline");
  SliceOptions o;
  o.model =
      write(dir, "bad.svg", "<svg xmlns='http://www.w3.org/2000/svg'>\n<path d='M 0 0 L 1'/>\n</svg>\n");
  o.export_layers = (dir / "out.json").string();
  o.export_svg = (dir / "out.svg").string();
  Report report;
  auto r = run(o, report);
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().where == o.model + ":2:19");
  CHECK(contains(r.error().message, "expected a number for 'L'"));
  CHECK_FALSE(std::filesystem::exists(o.export_layers));
  CHECK_FALSE(std::filesystem::exists(o.export_svg));
}

TEST_CASE("round trip: STL -> --export-svg -> edited in an editor -> slice the SVG: the same islands") {
  test::TempDir dir("svg-pipeline");
  geo::Mesh mesh = geo::plate_with_holes(30, 20, 3, 3, 2, 3, 32);
  geo::append(mesh, geo::translated(geo::cylinder(4, 2, 40), {40, 10, 0}));
  std::string stl = (dir / "model.stl").string();
  REQUIRE(geo::write_stl_binary(stl, mesh).ok());

  SliceOptions a;
  a.model = stl;
  a.export_svg = (dir / "layers.svg").string();
  a.export_layers = (dir / "stl.json").string();
  Report report;
  auto ra = run(a, report);
  REQUIRE_MESSAGE(ra.ok(), ra.error().to_string());

  // An editor's save: reformatted, a layer moved on the sheet, its namespace prefix renamed,
  // and editor metadata added. None of it changes the geometry.
  pugi::xml_document doc;
  REQUIRE(doc.load_file(a.export_svg.c_str()));
  pugi::xml_node root = doc.child("svg");
  root.attribute("xmlns:tranche").set_name("xmlns:tl");
  std::vector<pugi::xml_node> all{root};
  for (size_t i = 0; i < all.size(); ++i) {
    for (pugi::xml_attribute at : all[i].attributes()) {
      std::string name = at.name();
      if (name.rfind("tranche:", 0) == 0) at.set_name(("tl:" + name.substr(8)).c_str());
    }
    for (pugi::xml_node c : all[i].children())
      if (c.type() == pugi::node_element) all.push_back(c);
  }
  root.append_attribute("xmlns:inkscape").set_value("http://www.inkscape.org/namespaces/inkscape");
  root.append_attribute("inkscape:version").set_value("1.2");
  root.child("g").attribute("transform").set_value("translate(500 -20)");
  std::string edited = (dir / "edited.svg").string();
  REQUIRE(doc.save_file(edited.c_str(), "    "));

  SliceOptions b;
  b.model = edited;
  b.export_layers = (dir / "svg.json").string();
  Report rb_report;
  auto rb = run(b, rb_report);
  REQUIRE_MESSAGE(rb.ok(), rb.error().to_string());
  CHECK(rb->layers == ra->layers);
  CHECK(rb_report.empty());
  auto la = layer_lines(a.export_layers), lb = layer_lines(b.export_layers);
  REQUIRE(la.size() == lb.size());
  CHECK(count(la, "\"outer\"") > 0);
  for (size_t i = 0; i < la.size(); ++i) {
    CAPTURE(i);
    CHECK(la[i] == lb[i]);
  }
}

TEST_CASE("--fill-angle-script through run_slice") {
  test::TempDir dir("svg-pipeline");
  SliceOptions o;
  o.model = write(dir, "drawing.svg", kDrawing);
  o.export_layers = (dir / "out.json").string();
  if (!geo::FillAngleScript::available()) {
    o.fill_angle_script = write(dir, "a.py", "def fill_angle(ctx): return 0\n");
    Report report;
    auto r = run(o, report);
    REQUIRE_FALSE(r.ok());
    CHECK(contains(r.error().message, "built without Python"));
    return;
  }
  SUBCASE("a working script") {
    o.fill_angle_script = write(dir, "ok.py", "def fill_angle(ctx):\n    return 15 * ctx.layer_index\n");
    Report report;
    auto r = run(o, report);
    REQUIRE_MESSAGE(r.ok(), r.error().to_string());
    CHECK(report.count("not-implemented") == 0);
  }
  SUBCASE("a raising script stops the run with the traceback and writes nothing") {
    o.fill_angle_script =
        write(dir, "raise.py",
              "def fill_angle(ctx):\n    if ctx.layer_index == 4:\n        raise RuntimeError('no')\n"
              "    return 0\n");
    Report report;
    auto r = run(o, report);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().where == o.fill_angle_script + ":3");
    CHECK(contains(r.error().message, "on layer 4, island 0"));
    CHECK(contains(r.error().message, "RuntimeError: no"));
    CHECK_FALSE(std::filesystem::exists(o.export_layers));
  }
  SUBCASE("a syntax error fails before slicing") {
    o.fill_angle_script = write(dir, "syntax.py", "def fill_angle(ctx):\nreturn 1\n");
    o.model = (dir / "missing.svg").string();  // never reached
    Report report;
    auto r = run(o, report);
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().where == o.fill_angle_script + ":2:1");
    CHECK(contains(r.error().message, "syntax error"));
  }
}

TEST_CASE("a drawing is centred on the bed like a lone model, wherever it sits on its page") {
  test::TempDir dir("svg-centre");
  SliceOptions o;
  o.model = write(dir, "corner.svg",
                  R"(<svg xmlns="http://www.w3.org/2000/svg" width="210mm" height="297mm" viewBox="0 0 210 297">
  <rect x="0" y="277" width="20" height="20" fill="black"/></svg>)");
  o.output_gcode = (dir / "corner.gcode").string();
  o.sets = {{"skirt_loops", "0"}};
  Report report;
  auto r = run(o, report);
  REQUIRE_MESSAGE(r.ok(), r.error().to_string());
  std::ifstream in(o.output_gcode);
  std::string line;
  double lo = 1e9, hi = -1e9;
  bool layers = false;
  while (std::getline(in, line)) {
    if (line.rfind(";LAYER:0", 0) == 0) layers = true;
    if (layers && line == ";TYPE:Custom") break;  // the end G-code (it parks the head)
    if (!layers || line.rfind("G1 X", 0) != 0) continue;
    const double x = std::stod(line.substr(4));
    lo = std::min(lo, x), hi = std::max(hi, x);
  }
  CHECK(0.5 * (lo + hi) == doctest::Approx(100).epsilon(0.01));
  CHECK(hi - lo < 21);
}
