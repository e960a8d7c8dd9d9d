// The printer's bed as the plate sees it: where objects may stand and how high they may rise.
// A plain value: the pipeline fills it from the printer profile (bed_size_x, bed_size_y...).
#pragma once

#include <string>
#include <vector>

#include "base/result.h"
#include "geometry/plate/hull.h"

namespace tranche::plate {

struct Bed {
  enum class Shape { Rectangle, Circle };
  Shape shape = Shape::Rectangle;
  double size_x_mm = 200, size_y_mm = 200;  // the rectangle, or the circle's bounding square
  double origin_x_mm = 0, origin_y_mm = 0;  // bed coordinates of that rectangle's front-left corner
  double max_height_mm = 0;                 // highest printable z; 0: not known, not checked
  // How far the print reaches round the objects (the skirt): the arrangement keeps objects this
  // far from the edges, so that what it arranges prints on the bed. 0: right up to the edges.
  double margin_mm = 0;

  Vec2 min() const { return {origin_x_mm, origin_y_mm}; }
  Vec2 max() const { return {origin_x_mm + size_x_mm, origin_y_mm + size_y_mm}; }
  Vec2 center() const { return (min() + max()) / 2; }
  double radius() const { return size_x_mm / 2; }  // Circle: a delta's bed (0, 0 often its centre)
  // The bed's outline: the rectangle, or a regular polygon inscribed in the circle (a little
  // smaller than it, so that what fits the polygon fits the bed).
  Convex outline() const;
};

// What the bed check looks at: an object's outline on the bed and its height.
struct Footprint {
  std::string name;  // as messages name it: "'lid' (copy 2)"
  Convex hull;       // convex hull of the object's points projected on the bed, mm
  double height_mm = 0;
};

// Every footprint must lie on the bed (within 0.001 mm) and below its maximum height: one
// sentence per object that does not, saying by how much and on which side, and what to do
// (scale it down, with a factor that fits; move it; arrange the plate).
std::vector<std::string> bed_problems(const Bed& bed, const std::vector<Footprint>& footprints);

// The problems as one error (nothing is sliced; --allow-off-bed slices anyway), or ok.
Status check_on_bed(const Bed& bed, const std::vector<Footprint>& footprints);

}  // namespace tranche::plate
