// The objects of a plate: each a mesh in its own coordinates and the transform that puts it on
// the bed (Eigen's Affine3d: scale, rotation, mirror and translation, mm). Loaders give each
// object the transform its file gives; the plate's transforms and the arrangement compose onto it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "geometry/mesh/mesh.h"
#include "geometry/plate/bed.h"

namespace tranche::plate {

struct Object {
  std::string name;  // the 3MF object's name, else the file's stem
  std::string file;  // the file it came from
  geo::Mesh mesh;    // object coordinates, mm; triangles counter-clockwise seen from outside
  Eigen::Affine3d transform = Eigen::Affine3d::Identity();  // object -> bed coordinates, mm
  bool placed = false;  // its place on the bed is given (a 3MF build item, --move, --center)
  int copy = 0;         // 0, then 1, 2... for further instances (--copies, repeated 3MF build items)
};

struct Plate {
  std::vector<Object> objects;
  std::optional<Bed> bed;  // the bed it was placed and checked on (build_plate), if any
};

// "lid", or "lid (copy 2)" for copies: how messages name an object.
std::string display_name(const Object& object);

// The object's mesh in bed coordinates: every vertex through `transform`, and the triangles'
// order reversed when the transform mirrors, so that they stay counter-clockwise from outside.
geo::Mesh world_mesh(const Object& object);

// The bounding box of the object in bed coordinates, mm.
geo::BBox3 world_bbox(const Object& object);

}  // namespace tranche::plate
