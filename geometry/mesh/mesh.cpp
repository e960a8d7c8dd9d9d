#include "geometry/mesh/mesh.h"

#include <algorithm>

namespace tranche::geo {

BBox3 Mesh::bbox() const {
  BBox3 b;
  for (const auto& v : vertices) {
    b.min.x = std::min(b.min.x, v.x); b.min.y = std::min(b.min.y, v.y); b.min.z = std::min(b.min.z, v.z);
    b.max.x = std::max(b.max.x, v.x); b.max.y = std::max(b.max.y, v.y); b.max.z = std::max(b.max.z, v.z);
  }
  return b;
}

double Mesh::volume() const {
  double six_v = 0;
  for (const auto& t : triangles) {
    const Vec3& a = vertices[t[0]];
    const Vec3& b = vertices[t[1]];
    const Vec3& c = vertices[t[2]];
    six_v += a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x);
  }
  return six_v / 6.0;
}

void Mesh::transform(double scale, const Vec3& offset) {
  for (auto& v : vertices) {
    v.x = v.x * scale + offset.x;
    v.y = v.y * scale + offset.y;
    v.z = v.z * scale + offset.z;
  }
}

}  // namespace tranche::geo
