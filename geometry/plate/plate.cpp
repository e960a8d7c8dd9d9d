#include "geometry/plate/plate.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <map>
#include <tuple>

#include "geometry/mesh/primitives.h"
#include "geometry/plate/model_file.h"
#include "geometry/plate/transform.h"

namespace tranche::plate {
namespace {

constexpr double kNoticeMm = 0.01;  // a z change smaller than this goes unsaid

// The objects among the first `loaded` that `selector` names; every one for an empty selector.
Result<std::vector<size_t>> select(const Plate& plate, size_t loaded, const std::string& selector,
                                   const std::string& option) {
  std::vector<size_t> out;
  if (selector.empty()) {
    for (size_t i = 0; i < loaded; ++i) out.push_back(i);
    return out;
  }
  size_t n = 0;
  const auto [end, ec] = std::from_chars(selector.data(), selector.data() + selector.size(), n);
  if (ec == std::errc() && end == selector.data() + selector.size() && n >= 1 && n <= loaded) return std::vector{n - 1};
  for (size_t i = 0; i < loaded; ++i)
    if (plate.objects[i].name == selector) out.push_back(i);
  if (!out.empty()) return out;
  std::string names;
  for (size_t i = 0; i < loaded && i < 12; ++i) names += (i ? ", " : "") + ("'" + plate.objects[i].name + "'");
  return Error{"", fmt::format("{}: no object is named '{}' (the objects: {}; or give a number from 1 to {})", option,
                               selector, names, loaded)};
}

// Calls apply(index, value) for each object each item of `list` selects. Items without a
// selector select every object, unless `plate_wide` (--move, --center), where they are left for
// place_objects.
template <class T, class F>
Status for_each_selected(const Plate& plate, size_t loaded, const std::vector<PerObject<T>>& list,
                         const std::string& option, bool plate_wide, F apply) {
  for (const auto& item : list) {
    if (plate_wide && item.selector.empty()) continue;
    auto which = select(plate, loaded, item.selector, option);
    if (!which) return which.error();
    for (size_t i : *which) apply(i, item.value);
  }
  return ok_status();
}

void scale_to_fit(Object& o, const Bed& bed, Report& report) {
  const geo::BBox3 b = world_bbox(o);
  double f = std::min(bed.size_x_mm / (b.max.x - b.min.x), bed.size_y_mm / (b.max.y - b.min.y));
  if (bed.shape == Bed::Shape::Circle) f = bed.size_x_mm / std::hypot(b.max.x - b.min.x, b.max.y - b.min.y);
  if (bed.max_height_mm > 0) f = std::min(f, bed.max_height_mm / (b.max.z - b.min.z));
  if (!std::isfinite(f) || f <= 0) return;
  f *= 0.999;  // clear of the edges by rounding
  scale(o, Eigen::Vector3d::Constant(f));
  report.warn("plate-scaled", display_name(o), fmt::format("scaled by {:.3g} to fit the bed (--scale-to-fit)", f));
}

// An object whose file puts it below the bed or above it (any format: an STL's or OBJ's own
// coordinates, a 3MF build item's transform) is told that it moved up or down to the bed.
void note_height(const Object& o, Report& report) {
  const double up = -world_bbox(o).min.z;
  if (std::fabs(up) < kNoticeMm) return;
  if (up > 0)
    report.warn("plate-lifted", display_name(o),
                fmt::format("reached {:.2f} mm below the bed: lifted onto it (objects are not cut at the bed)", up));
  else
    report.warn("plate-dropped", display_name(o), fmt::format("floated {:.2f} mm above the bed: dropped onto it", -up));
}

}  // namespace

Result<Plate> load_plate(const std::vector<std::string>& files, Report& report) {
  if (files.empty()) return Error{"", "no model file given"};
  Plate plate;
  for (const auto& f : files) {
    auto objects = load_model_file(f, report);
    if (!objects) return objects.error();
    for (auto& o : *objects) plate.objects.push_back(std::move(o));
  }
  return plate;
}

Status apply_transforms(Plate& plate, const PlateOptions& opt, const Bed& bed, Report& report) {
  const size_t loaded = plate.objects.size();
  auto& objects = plate.objects;
  for (auto& o : objects) {
    note_height(o, report);
    if (opt.lay_flat) lay_flat(o);
  }
  const auto turn = [&](const Eigen::Vector3d& axis) {
    return [&objects, axis](size_t i, double deg) { rotate(objects[i], axis, deg); };
  };
  for (const auto& [list, option, axis] : {std::tuple{&opt.rotate_x, "--rotate-x", Eigen::Vector3d::UnitX()},
                                          {&opt.rotate_y, "--rotate-y", Eigen::Vector3d::UnitY()},
                                          {&opt.rotate, "--rotate", Eigen::Vector3d::UnitZ()}})
    if (Status s = for_each_selected(plate, loaded, *list, option, false, turn(axis)); !s) return s;
  if (Status s = for_each_selected(plate, loaded, opt.scale, "--scale", false,
                                   [&](size_t i, const Eigen::Vector3d& f) { scale(objects[i], f); });
      !s)
    return s;
  for (auto& o : objects) {
    if (opt.scale_to_fit) scale_to_fit(o, bed, report);
    drop_to_bed(o);
    if (opt.arrange == ArrangeMode::Always) o.placed = false;  // 3MF positions give way to the arrangement
  }
  std::vector<int> copies(loaded, 1);
  if (Status s = for_each_selected(plate, loaded, opt.copies, "--copies", false, [&](size_t i, int n) { copies[i] = n; });
      !s)
    return s;
  std::map<std::pair<std::string, std::string>, int> next;  // (file, name) -> next copy number
  for (size_t i = 0; i < loaded; ++i) {
    int& k = next[{objects[i].file, objects[i].name}];
    k = std::max(k, objects[i].copy + 1);
  }
  for (size_t i = 0; i < loaded; ++i)
    for (int c = 1; c < copies[i]; ++c) {
      Object o = objects[i];
      o.copy = next[{o.file, o.name}]++;
      o.placed = false;
      objects.push_back(std::move(o));
    }
  if (Status s = for_each_selected(plate, loaded, opt.move, "--move", true,
                                   [&](size_t i, const Vec2& by) {
                                     translate(objects[i], {by.x(), by.y(), 0});
                                     objects[i].placed = true;
                                   });
      !s)
    return s;
  return for_each_selected(plate, loaded, opt.center, "--center", true, [&](size_t i, const Vec2& at) {
    center_at(objects[i], at);
    objects[i].placed = true;
  });
}

std::vector<Footprint> footprints(const Plate& plate) {
  std::vector<Footprint> out;
  for (const auto& o : plate.objects) {
    const geo::BBox3 b = world_bbox(o);
    out.push_back({display_name(o), footprint(o), b.max.z - std::min(0.0, b.min.z)});
  }
  return out;
}

geo::Mesh merged_mesh(const Plate& plate) {
  geo::Mesh out;
  for (const auto& o : plate.objects) geo::append(out, world_mesh(o));
  out.name = plate.objects.size() == 1 ? plate.objects[0].name : fmt::format("{} objects", plate.objects.size());
  return out;
}

Result<Plate> build_plate(const PlateOptions& options, const Bed& bed, Report& report) {
  auto plate = load_plate(options.files, report);
  if (!plate) return plate.error();
  if (Status s = apply_transforms(*plate, options, bed, report); !s) return s.error();
  if (Status s = place_objects(*plate, options, bed); !s) return s.error();
  if (Status s = check_plate(*plate, bed, options.allow_off_bed, report); !s) return s.error();
  plate->bed = bed;
  return plate;
}

}  // namespace tranche::plate
