// Changes of one object's transform, each about the object's own centre so that it stays where
// it stands: the steps of --scale, --rotate, --lay-flat, --center and dropping onto the bed.
#pragma once

#include <optional>

#include "geometry/plate/hull.h"
#include "geometry/plate/object.h"

namespace tranche::plate {

// The centre of the object's bounding box in bed coordinates, mm.
Eigen::Vector3d world_center(const Object& o);

// Turns the object by `deg` degrees about `axis` (counter-clockwise looking down the axis)
// through its centre.
void rotate(Object& o, const Eigen::Vector3d& axis, double deg);

// Scales the object by `factors` (x, y, z; > 0) about its centre.
void scale(Object& o, const Eigen::Vector3d& factors);

void translate(Object& o, const Eigen::Vector3d& by_mm);

// Moves the object so that the centre of its bounding box is at `xy` (mm); z is kept.
void center_at(Object& o, const Vec2& xy);

// Moves the object so that its lowest point is at z = 0; returns how far it moved up (mm;
// negative when it was floating and came down).
double drop_to_bed(Object& o);

// The face the object was laid on: its outward normal before turning, the area of its contact
// polygon (mm²) and whether the object's centre of mass stands above that polygon.
struct FlatFace {
  Eigen::Vector3d normal;
  double area_mm2 = 0;
  bool stable = false;
};

// Turns the object so that its largest flat face lies on the bed, as PrusaSlicer's "place on
// face" does: faces are grouped by plane; of the planes that touch the object from outside, the
// one whose contact polygon (the hull of the object's points on it) has the largest area wins,
// stable ones first. Nothing happens (nullopt) to an object with no flat face on its hull.
std::optional<FlatFace> lay_flat(Object& o);

// The convex hull of the object's vertices projected on the bed, mm.
Convex footprint(const Object& o);

}  // namespace tranche::plate
