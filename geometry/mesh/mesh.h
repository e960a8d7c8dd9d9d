// The triangle mesh of a model, welded: triangles refer to shared vertex ids so that slicing can
// chain segments by topology (two triangles sharing an edge produce segments that meet exactly).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tranche::geo {

struct Vec3 {
  double x = 0, y = 0, z = 0;  // mm
};

struct BBox3 {
  Vec3 min{1e300, 1e300, 1e300};
  Vec3 max{-1e300, -1e300, -1e300};
  bool empty() const { return min.x > max.x; }
};

struct Mesh {
  std::vector<Vec3> vertices;                     // mm; exact duplicates merged
  std::vector<std::array<uint32_t, 3>> triangles;  // vertex ids, counter-clockwise seen from outside
  std::string name;                               // from the STL header or the file name

  BBox3 bbox() const;
  // Volume enclosed (divergence theorem), mm³; approximate for open meshes.
  double volume() const;
  // Moves and scales in place: v' = v * scale + offset.
  void transform(double scale, const Vec3& offset);
};

}  // namespace tranche::geo
