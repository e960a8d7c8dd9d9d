// place_objects and check_plate (plate.h): where the objects without a place go, and the check
// that every object is on the bed.
#include <fmt/format.h>

#include <algorithm>

#include "geometry/plate/arrange.h"
#include "geometry/plate/plate.h"
#include "geometry/plate/transform.h"

namespace tranche::plate {
namespace {

Box2 extent(const Plate& plate, const std::vector<size_t>& which) {
  Box2 b;
  for (size_t i : which) {
    const geo::BBox3 w = world_bbox(plate.objects[i]);
    b.add(Vec2(w.min.x, w.min.y));
    b.add(Vec2(w.max.x, w.max.y));
  }
  return b;
}

void shift(Plate& plate, const std::vector<size_t>& which, const Vec2& by) {
  for (size_t i : which) translate(plate.objects[i], {by.x(), by.y(), 0});
}

Error unfit_error(const Plate& plate, const std::vector<size_t>& unfit, const std::vector<Convex>& hulls,
                  const Bed& bed, double spacing) {
  std::string names;
  for (size_t k = 0; k < unfit.size(); ++k) {
    const size_t i = unfit[k];
    names += (k ? ", " : "") + display_name(plate.objects[i]);
    const Vec2 size = bounds(hulls[i]).size();
    if (size.x() > bed.size_x_mm || size.y() > bed.size_y_mm)
      names += fmt::format(" ({:.1f} × {:.1f} mm, larger than the bed)", size.x(), size.y());
  }
  return Error{"", fmt::format("{} not fit on the {:g} × {:g} mm bed beside the others: {}; use fewer --copies, "
                               "--scale them down, a smaller --spacing (now {:g} mm), or slice them in several runs",
                               unfit.size() == 1 ? "1 object does" : fmt::format("{} objects do", unfit.size()),
                               bed.size_x_mm, bed.size_y_mm, names, spacing)};
}

}  // namespace

Status place_objects(Plate& plate, const PlateOptions& opt, const Bed& bed) {
  std::vector<size_t> loose, all;
  for (size_t i = 0; i < plate.objects.size(); ++i) {
    all.push_back(i);
    if (!plate.objects[i].placed) loose.push_back(i);
  }
  if (opt.arrange == ArrangeMode::Never || (loose.size() == 1 && loose.size() == all.size())) {
    // The objects without a place keep their files' layout, centred on the bed as a group.
    if (!loose.empty()) shift(plate, loose, bed.center() - extent(plate, loose).center());
  } else if (!loose.empty()) {
    std::vector<ArrangeItem> items;
    std::vector<Convex> hulls;
    for (const auto& o : plate.objects) {
      hulls.push_back(footprint(o));
      items.push_back({hulls.back(), o.placed});
    }
    const Arrangement a = arrange(items, bed, opt.spacing_mm);
    if (!a.unfit.empty()) return unfit_error(plate, a.unfit, hulls, bed, opt.spacing_mm);
    for (size_t i : loose) translate(plate.objects[i], {a.moves[i].x(), a.moves[i].y(), 0});
  }
  // A plate-wide --center or --move (no object named) moves everything, arranged or not.
  for (const auto& c : opt.center)
    if (c.selector.empty()) shift(plate, all, c.value - extent(plate, all).center());
  for (const auto& m : opt.move)
    if (m.selector.empty()) shift(plate, all, m.value);
  return ok_status();
}

Status check_plate(const Plate& plate, const Bed& bed, bool allow_off_bed, Report& report) {
  const std::vector<Footprint> f = footprints(plate);
  std::vector<Box2> box;
  for (const auto& p : f) box.push_back(bounds(p.hull));
  for (size_t i = 0; i < f.size(); ++i)
    for (size_t j = i + 1; j < f.size(); ++j) {
      if (f[i].hull.size() < 3 || f[j].hull.size() < 3) continue;
      const Box2 &a = box[i], &b = box[j];
      if (a.max.x() <= b.min.x() || b.max.x() <= a.min.x() || a.max.y() <= b.min.y() || b.max.y() <= a.min.y())
        continue;
      // Two convex hulls overlap when the origin is inside their Minkowski difference.
      if (strictly_inside(minkowski_sum(f[i].hull, negated(f[j].hull)), Vec2::Zero(), 1e-6))
        report.warn("plate-overlap", "",
                    fmt::format("{} and {} overlap on the bed: where they meet they print as one", f[i].name,
                                f[j].name));
    }
  if (!allow_off_bed) return check_on_bed(bed, f);
  for (const auto& p : bed_problems(bed, f)) report.warn("plate-off-bed", "", p + " — sliced anyway (--allow-off-bed)");
  return ok_status();
}

}  // namespace tranche::plate
