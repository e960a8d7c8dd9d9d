// The plate from files to bed coordinates: transforms, copies, lay-flat, placement, the check.
#include <doctest/doctest.h>

#include <fstream>

#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "geometry/plate/plate.h"
#include "geometry/plate/threemf_write.h"
#include "geometry/plate/transform.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::plate;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

struct Files {
  test::TempDir dir{"plate"};
  std::string stl(const std::string& name, const geo::Mesh& m) {
    const std::string p = (dir / (name + ".stl")).string();
    REQUIRE(geo::write_stl_binary(p, m).ok());
    return p;
  }
  std::string three_mf(const std::string& name, const std::vector<Object>& objects) {
    const std::string p = (dir / (name + ".3mf")).string();
    REQUIRE(write_3mf(p, objects).ok());
    return p;
  }
};

Object placed(const std::string& name, geo::Mesh mesh, const Eigen::Vector3d& at) {
  Object o;
  o.name = name;
  o.mesh = std::move(mesh);
  o.transform = Eigen::Translation3d(at);
  return o;
}

Plate build(PlateOptions opt, Report& report, const Bed& bed = {}) {
  auto plate = build_plate(opt, bed, report);
  REQUIRE_MESSAGE(plate.ok(), plate.error().to_string());
  return std::move(*plate);
}

std::string build_error(PlateOptions opt, const Bed& bed = {}) {
  Report report;
  auto plate = build_plate(opt, bed, report);
  REQUIRE_FALSE(plate.ok());
  return plate.error().to_string();
}

Eigen::Vector3d size(const Object& o) {
  const geo::BBox3 b = world_bbox(o);
  return {b.max.x - b.min.x, b.max.y - b.min.y, b.max.z - b.min.z};
}

}  // namespace

TEST_CASE("plate: one STL is centred on the bed, several are arranged apart") {
  Files f;
  Report report;
  PlateOptions one;
  one.files = {f.stl("cube", geo::translated(geo::box({10, 10, 10}), {-50, 7, 3}))};
  Plate p = build(one, report);
  REQUIRE(p.objects.size() == 1);
  CHECK(world_center(p.objects[0]).x() == doctest::Approx(100));
  CHECK(world_center(p.objects[0]).y() == doctest::Approx(100));
  CHECK(world_bbox(p.objects[0]).min.z == doctest::Approx(0));
  CHECK_FALSE(p.objects[0].placed);
  CHECK(report.size() == 1);  // it floated 3 mm above the bed in its file: dropped onto it, with a note
  CHECK(report.count("plate-dropped") == 1);

  PlateOptions two;
  two.files = {f.stl("a", geo::box({30, 20, 5})), f.stl("b", geo::cylinder(10, 8, 32))};
  p = build(two, report);
  REQUIRE(p.objects.size() == 2);
  CHECK(p.objects[0].name == "a");
  CHECK(p.objects[1].name == "b");
  const auto a = world_bbox(p.objects[0]), b = world_bbox(p.objects[1]);
  const bool apart = a.max.x + 6 <= b.min.x + 1e-6 || b.max.x + 6 <= a.min.x + 1e-6 || a.max.y + 6 <= b.min.y + 1e-6 ||
                     b.max.y + 6 <= a.min.y + 1e-6;
  CHECK(apart);
  CHECK(report.count("plate-overlap") == 0);
  const geo::Mesh merged = merged_mesh(p);
  CHECK(merged.triangles.size() == 12 + 128);
  CHECK(merged.volume() == doctest::Approx(p.objects[0].mesh.volume() + p.objects[1].mesh.volume()));
}

TEST_CASE("plate: rotations, scale, selectors and copies") {
  Files f;
  Report report;
  PlateOptions o;
  o.files = {f.stl("bar", geo::box({10, 30, 5})), f.stl("tower", geo::box({10, 10, 40}))};
  o.rotate = {{"bar", 90}};
  o.rotate_x = {{"2", 90}};
  o.scale = {{"", {2, 2, 2}}};
  o.copies = {{"bar", 3}};
  Plate p = build(o, report);
  REQUIRE(p.objects.size() == 4);
  CHECK(size(p.objects[0]).x() == doctest::Approx(60));
  CHECK(size(p.objects[0]).y() == doctest::Approx(20));
  CHECK(size(p.objects[1]).z() == doctest::Approx(20));  // the tower lies down
  CHECK(size(p.objects[1]).y() == doctest::Approx(80));
  CHECK(p.objects[2].name == "bar");
  CHECK(p.objects[2].copy == 1);
  CHECK(p.objects[3].copy == 2);
  CHECK(size(p.objects[3]).x() == doctest::Approx(60));
  CHECK(report.count("plate-overlap") == 0);

  o.rotate = {{"lid", 90}};
  CHECK(has(build_error(o), "--rotate: no object is named 'lid' (the objects: 'bar', 'tower'"));
}

TEST_CASE("plate: --scale-to-fit, --lay-flat and the bed's height") {
  Files f;
  Report report;
  PlateOptions o;
  o.files = {f.stl("slab", geo::box({400, 100, 10}))};
  Bed bed;
  CHECK(has(build_error(o, bed), "--scale 0.5 fits"));
  o.scale_to_fit = true;
  Plate p = build(o, report, bed);
  CHECK(size(p.objects[0]).x() <= 200);
  CHECK(size(p.objects[0]).x() > 199);
  CHECK(report.count("plate-scaled") == 1);

  // A cone saved upside down and tilted: --lay-flat puts its base on the bed.
  geo::Mesh upside_down = geo::cone(20, 0, 30, 48);
  const Eigen::Matrix3d turn =
      (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX())).matrix();
  for (auto& v : upside_down.vertices) {
    const Eigen::Vector3d q = turn * Eigen::Vector3d(v.x, v.y, v.z);
    v = {q.x(), q.y(), q.z()};
  }
  PlateOptions cone;
  cone.files = {f.stl("cone", upside_down)};
  cone.lay_flat = true;
  p = build(cone, report, bed);
  CHECK(size(p.objects[0]).z() == doctest::Approx(30));
  const geo::Mesh m = world_mesh(p.objects[0]);
  int on_bed = 0;
  for (const auto& v : m.vertices) on_bed += std::abs(v.z) < 1e-6;
  CHECK(on_bed >= 48);  // the base's rim (and centre) on the bed, not the apex

  PlateOptions tall;
  tall.files = {f.stl("tall", geo::box({10, 10, 300}))};
  bed.max_height_mm = 210;
  CHECK(has(build_error(tall, bed), "'tall' is 300.0 mm high"));
  tall.allow_off_bed = true;
  build(tall, report, bed);
  CHECK(report.count("plate-off-bed") == 1);
}

TEST_CASE("plate: 3MF positions are kept and checked; --arrange overrides them") {
  Files f;
  Report report;
  PlateOptions o;
  o.files = {f.three_mf("job", {placed("left", geo::box({20, 20, 10}), {20, 30, 0}),
                                placed("right", geo::box({20, 20, 10}), {150, 30, 5})})};
  Plate p = build(o, report);
  REQUIRE(p.objects.size() == 2);
  CHECK(p.objects[0].placed);
  CHECK(world_bbox(p.objects[0]).min.x == doctest::Approx(20));
  CHECK(world_bbox(p.objects[1]).min.x == doctest::Approx(150));
  CHECK(world_bbox(p.objects[1]).min.z == doctest::Approx(0));
  CHECK(report.count("plate-dropped") == 1);

  // An STL joins them: it is arranged around the two that keep their place.
  o.files.push_back(f.stl("extra", geo::box({30, 30, 10})));
  p = build(o, report);
  CHECK(world_bbox(p.objects[0]).min.x == doctest::Approx(20));
  CHECK(report.count("plate-overlap") == 0);

  o.files = {f.three_mf("off", {placed("edge", geo::box({20, 20, 10}), {-15, 30, 0})})};
  CHECK(has(build_error(o), "'edge' is off the bed by 15.0 mm on the left"));
  o.arrange = ArrangeMode::Always;
  p = build(o, report);
  CHECK(world_center(p.objects[0]).x() == doctest::Approx(100));
}

TEST_CASE("plate: --center and --move, for one object or the plate; --no-arrange keeps the files' layout") {
  Files f;
  Report report;
  PlateOptions o;
  o.files = {f.stl("a", geo::box({10, 10, 10})), f.stl("b", geo::translated(geo::box({10, 10, 10}), {30, 0, 0}))};
  o.center = {{"a", Vec2(40, 40)}};
  Plate p = build(o, report);
  CHECK(p.objects[0].placed);
  CHECK(world_center(p.objects[0]).x() == doctest::Approx(40));
  CHECK_FALSE(p.objects[1].placed);

  PlateOptions keep;
  keep.files = o.files;
  keep.arrange = ArrangeMode::Never;
  keep.move = {{"", Vec2(10, -20)}};
  p = build(keep, report);
  CHECK(world_bbox(p.objects[1]).min.x - world_bbox(p.objects[0]).min.x == doctest::Approx(30));
  CHECK((world_center(p.objects[0]).x() + world_center(p.objects[1]).x()) / 2 == doctest::Approx(110));
  CHECK(world_center(p.objects[0]).y() == doctest::Approx(80));

  PlateOptions crowd;
  crowd.files = {f.stl("big", geo::box({150, 150, 5}))};
  crowd.copies = {{"", 2}};
  CHECK(has(build_error(crowd), "1 object does not fit on the 200 × 200 mm bed beside the others: 'big' (copy 2)"));
}

TEST_CASE("plate: an STL below the bed is lifted, a floating OBJ dropped, each with a warning that says so") {
  Files f;
  Report report;
  PlateOptions o;
  geo::Mesh sunk = geo::box({20, 20, 10});
  sunk.transform(1.0, {0, 0, -4});  // modelled about its middle: 4 mm under the bed
  const std::string obj = (f.dir / "floating.obj").string();
  std::ofstream(obj) << "v 0 0 7\nv 10 0 7\nv 10 10 7\nv 0 10 7\nv 0 0 9\nv 10 0 9\nv 10 10 9\nv 0 10 9\n"
                        "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";
  o.files = {f.stl("sunk", sunk), obj, f.stl("grounded", geo::box({10, 10, 5}))};
  Plate p = build(o, report);
  REQUIRE(p.objects.size() == 3);
  for (const Object& ob : p.objects) CHECK(world_bbox(ob).min.z == doctest::Approx(0));
  CHECK(size(p.objects[0]).z() == doctest::Approx(10));  // lifted whole, not cut at the bed
  CHECK(size(p.objects[1]).z() == doctest::Approx(2));
  REQUIRE(report.count("plate-lifted") == 1);
  REQUIRE(report.count("plate-dropped") == 1);
  for (const Warning& w : report.warnings()) {
    if (w.code == "plate-lifted") {
      CHECK(w.where == "'sunk'");
      CHECK(has(w.message, "reached 4.00 mm below the bed: lifted onto it"));
    }
    if (w.code == "plate-dropped") {
      CHECK(w.where == "'floating'");
      CHECK(has(w.message, "floated 7.00 mm above the bed: dropped onto it"));
    }
  }
}
