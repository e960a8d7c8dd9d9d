// Planar geometry on fixed-point integer coordinates (Clipper's), shared by every geometry stage.
//
// Units: 1 coordinate unit = 1 nm (kUnitsPerMm = 1e6). Coordinates within ±1073 mm stay inside
// Clipper's fast 64-bit range (loRange = 2^30 − 1), so topology decisions are exact integer
// arithmetic with no epsilons. Doubles are used only for lengths/areas reported to users.
#pragma once

#include <polyclipping/clipper.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

namespace tranche::geo {

using coord_t = ClipperLib::cInt;
using Point = ClipperLib::IntPoint;  // {X, Y} in units
using Ring = ClipperLib::Path;       // closed ring, last point != first; CCW = material outside holes
using Rings = ClipperLib::Paths;

inline constexpr double kUnitsPerMm = 1e6;
inline constexpr double kMmPerUnit = 1e-6;

inline coord_t to_units(double mm) { return static_cast<coord_t>(std::llround(mm * kUnitsPerMm)); }
inline double to_mm(coord_t units) { return static_cast<double>(units) * kMmPerUnit; }
inline Point to_point(double x_mm, double y_mm) { return Point(to_units(x_mm), to_units(y_mm)); }

// A polygon with holes: `outer` is counter-clockwise (positive area), each hole clockwise.
struct Polygon {
  Ring outer;
  Rings holes;
};
using Polygons = std::vector<Polygon>;

struct BBox2 {
  coord_t min_x = INT64_MAX, min_y = INT64_MAX, max_x = INT64_MIN, max_y = INT64_MIN;
  bool empty() const { return min_x > max_x; }
  void add(const Point& p) {
    min_x = std::min(min_x, p.X); min_y = std::min(min_y, p.Y);
    max_x = std::max(max_x, p.X); max_y = std::max(max_y, p.Y);
  }
};

// Signed area in mm² (positive for counter-clockwise rings).
double area_mm2(const Ring& ring);
// Area of the polygon in mm² (outer minus holes; orientation-independent).
double area_mm2(const Polygon& poly);
double area_mm2(const Polygons& polys);
// Perimeter length of a closed ring in mm.
double length_mm(const Ring& ring);
BBox2 bbox(const Ring& ring);
BBox2 bbox(const Polygon& poly);

// All rings of the polygons (outers and holes) as one flat list, e.g. for a Clipper call.
Rings to_rings(const Polygons& polys);
// Clipper PolyTree -> polygons with holes (outer CCW, holes CW); islands inside holes become
// their own polygons.
Polygons to_polygons(const ClipperLib::PolyTree& tree);

}  // namespace tranche::geo
