#include "geometry/plate/transform.h"

#include <algorithm>
#include <cmath>

namespace tranche::plate {

Eigen::Vector3d world_center(const Object& o) {
  const geo::BBox3 b = world_bbox(o);
  return {(b.min.x + b.max.x) / 2, (b.min.y + b.max.y) / 2, (b.min.z + b.max.z) / 2};
}

void rotate(Object& o, const Eigen::Vector3d& axis, double deg) {
  const Eigen::Vector3d c = world_center(o);
  const Eigen::Affine3d turn =
      Eigen::Translation3d(c) * Eigen::AngleAxisd(deg * M_PI / 180, axis.normalized()) * Eigen::Translation3d(-c);
  o.transform = turn * o.transform;
}

void scale(Object& o, const Eigen::Vector3d& factors) {
  const Eigen::Vector3d c = world_center(o);
  o.transform = Eigen::Translation3d(c) * Eigen::Scaling(factors) * Eigen::Translation3d(-c) * o.transform;
}

void translate(Object& o, const Eigen::Vector3d& by_mm) { o.transform = Eigen::Translation3d(by_mm) * o.transform; }

void center_at(Object& o, const Vec2& xy) {
  const Eigen::Vector3d c = world_center(o);
  translate(o, {xy.x() - c.x(), xy.y() - c.y(), 0});
}

double drop_to_bed(Object& o) {
  const double z = world_bbox(o).min.z;
  translate(o, {0, 0, -z});
  return -z;
}

Convex footprint(const Object& o) {
  std::vector<Vec2> pts;
  pts.reserve(o.mesh.vertices.size());
  for (const auto& v : o.mesh.vertices) {
    const Eigen::Vector3d p = o.transform * Eigen::Vector3d(v.x, v.y, v.z);
    pts.emplace_back(p.x(), p.y());
  }
  return convex_hull(std::move(pts));
}

}  // namespace tranche::plate
