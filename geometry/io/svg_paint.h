// SVG overlap resolution: the material region of shapes painted in document order, under the
// three overlap modes (additive, boolean, subtractive colours).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/core/geom.h"
#include "geometry/io/svg_style.h"

namespace tranche::geo {

enum class SvgOverlap : uint8_t {
  Additive,     // nonzero union of every filled shape
  Boolean,      // even-odd across shapes: where an even number of shapes overlap there is no material
  Subtractive,  // in paint order, shapes filled with the background colour erase; others add
};

namespace svg {

// One filled shape, flattened and placed on the bed plane (nm, y up).
struct Shape {
  Rings rings;           // its subpaths, closed, in drawing order and direction
  bool evenodd = false;  // fill-rule within the shape
  Paint fill;            // Color or Url (never None or CurrentColor: resolved by the reader)
  std::string where;     // "file.svg:12:5", for messages
};

// The material of the shapes under `mode`, as polygons with holes (outer CCW, holes CW, no two
// overlapping). In Subtractive mode, shapes whose fill is exactly `background` erase.
Polygons resolve_shapes(const std::vector<Shape>& shapes, SvgOverlap mode, Rgb background);

}  // namespace svg
}  // namespace tranche::geo
