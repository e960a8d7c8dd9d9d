#include "geometry/plate/object.h"

#include <fmt/format.h>

#include <algorithm>

namespace tranche::plate {

std::string display_name(const Object& o) {
  return o.copy == 0 ? "'" + o.name + "'" : fmt::format("'{}' (copy {})", o.name, o.copy + 1);
}

geo::Mesh world_mesh(const Object& o) {
  geo::Mesh m;
  m.name = o.name;
  m.vertices.reserve(o.mesh.vertices.size());
  for (const auto& v : o.mesh.vertices) {
    const Eigen::Vector3d p = o.transform * Eigen::Vector3d(v.x, v.y, v.z);
    m.vertices.push_back({p.x(), p.y(), p.z()});
  }
  m.triangles = o.mesh.triangles;
  if (o.transform.linear().determinant() < 0)
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

geo::BBox3 world_bbox(const Object& o) {
  geo::BBox3 b;
  for (const auto& v : o.mesh.vertices) {
    const Eigen::Vector3d p = o.transform * Eigen::Vector3d(v.x, v.y, v.z);
    b.min = {std::min(b.min.x, p.x()), std::min(b.min.y, p.y()), std::min(b.min.z, p.z())};
    b.max = {std::max(b.max.x, p.x()), std::max(b.max.y, p.y()), std::max(b.max.z, p.z())};
  }
  return b;
}

}  // namespace tranche::plate
