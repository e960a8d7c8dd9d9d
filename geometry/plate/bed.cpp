#include "geometry/plate/bed.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace tranche::plate {
namespace {

constexpr double kTolerance = 1e-3;  // mm an object may cross the bed's edge (rounding)
constexpr int kCircleSides = 128;

// A scale factor, rounded down to 2 decimals, that brings `size` within `room`.
double fitting_scale(double room, double size) { return std::floor(100 * room / size) / 100; }

std::string off_rectangle(const Bed& bed, const Footprint& f) {
  const Box2 b = bounds(f.hull);
  const Vec2 lo = bed.min(), hi = bed.max();
  std::vector<std::string> sides;
  auto side = [&](double by, const char* where) {
    if (by > kTolerance) sides.push_back(fmt::format("{:.1f} mm {}", by, where));
  };
  side(lo.x() - b.min.x(), "on the left");
  side(b.max.x() - hi.x(), "on the right");
  side(lo.y() - b.min.y(), "at the front");
  side(b.max.y() - hi.y(), "at the back");
  if (sides.empty()) return {};
  std::string joined;
  for (size_t i = 0; i < sides.size(); ++i)
    joined += (i == 0 ? "" : i + 1 == sides.size() ? " and " : ", ") + sides[i];
  std::string msg =
      fmt::format("{} is off the bed by {} (it spans x {:.1f} to {:.1f}, y {:.1f} to {:.1f} mm; the bed x {:g} to "
                  "{:g}, y {:g} to {:g} mm)",
                  f.name, joined, b.min.x(), b.max.x(), b.min.y(), b.max.y(), lo.x(), hi.x(), lo.y(), hi.y());
  const Vec2 size = b.size();
  if (size.x() > bed.size_x_mm + kTolerance || size.y() > bed.size_y_mm + kTolerance)
    return msg + fmt::format(": at {:.1f} × {:.1f} mm it is larger than the bed; scale it down (--scale {:g} fits)",
                             size.x(), size.y(),
                             std::min(fitting_scale(bed.size_x_mm, size.x()), fitting_scale(bed.size_y_mm, size.y())));
  return msg + ": move it (--center, --move) or let Tranche arrange the plate (--arrange)";
}

std::string off_circle(const Bed& bed, const Footprint& f) {
  const Vec2 c = bed.center();
  double reach = 0;
  for (const Vec2& p : f.hull) reach = std::max(reach, (p - c).norm());
  const double r = bed.radius();
  if (reach <= r + kTolerance) return {};
  const Box2 b = bounds(f.hull);
  double own = 0;  // its radius about its own centre: what must fit if it is centred
  for (const Vec2& p : f.hull) own = std::max(own, (p - b.center()).norm());
  std::string msg = fmt::format("{} reaches {:.1f} mm beyond the edge of the round bed (radius {:g} mm)", f.name,
                                reach - r, r);
  if (own > r + kTolerance)
    return msg + fmt::format(": it is larger than the bed; scale it down (--scale {:g} fits)", fitting_scale(r, own));
  return msg + ": move it (--center, --move) or let Tranche arrange the plate (--arrange)";
}

}  // namespace

Convex Bed::outline() const {
  if (shape == Shape::Rectangle) {
    const Vec2 lo = min(), hi = max();
    return {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  }
  Convex c;
  for (int i = 0; i < kCircleSides; ++i) {
    const double a = 2 * M_PI * i / kCircleSides;
    c.push_back(center() + radius() * Vec2(std::cos(a), std::sin(a)));
  }
  return c;
}

std::vector<std::string> bed_problems(const Bed& bed, const std::vector<Footprint>& footprints) {
  std::vector<std::string> problems;
  for (const Footprint& f : footprints) {
    std::string off = bed.shape == Bed::Shape::Rectangle ? off_rectangle(bed, f) : off_circle(bed, f);
    if (!off.empty()) problems.push_back(std::move(off));
    if (bed.max_height_mm > 0 && f.height_mm > bed.max_height_mm + kTolerance)
      problems.push_back(fmt::format("{} is {:.1f} mm high, {:.1f} mm more than the printer reaches ({:g} mm): scale "
                                     "it down (--scale {:g} fits) or lay it down (--lay-flat, --rotate-x 90)",
                                     f.name, f.height_mm, f.height_mm - bed.max_height_mm, bed.max_height_mm,
                                     fitting_scale(bed.max_height_mm, f.height_mm)));
  }
  return problems;
}

Status check_on_bed(const Bed& bed, const std::vector<Footprint>& footprints) {
  const std::vector<std::string> problems = bed_problems(bed, footprints);
  if (problems.empty()) return ok_status();
  std::string msg = problems.size() == 1 ? problems[0] : fmt::format("{} problems with the bed:", problems.size());
  if (problems.size() > 1)
    for (const auto& p : problems) msg += "\n  " + p;
  return Error{"", msg + (problems.size() > 1 ? "\n" : "; ") +
                       "nothing was sliced (--allow-off-bed slices anyway, if you know better)"};
}

}  // namespace tranche::plate
