// The per-layer data every stage after slicing reads: the "array of arrays". Slicing fills
// Layer::loops; resolution fills islands; the toolpath stage reads them (it never writes here:
// what is decided per island, such as the fill angle, lives in the layer plans).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/core/geom.h"

namespace tranche::geo {

// Which kind of border an edge of a cell is (the seed's "real borders" vs "cuts").
enum class EdgeKind : uint8_t {
  Real,        // between material and no material: perimeters follow these
  Artificial,  // a cut made by hole bridging or the monotone decomposition: no perimeter
};

// One piece of an island, monotone with respect to its fill direction: every line parallel to
// the fill direction meets it in at most one interval, so one continuous zig-zag fills it with
// no travel move (the seed's exact decomposition, geometry/polygon/decompose.h).
struct Cell {
  Ring ring;                    // counter-clockwise, simple
  std::vector<EdgeKind> edges;  // edges[i] is the edge ring[i] -> ring[(i + 1) % n]
  double fill_angle_deg = 0;    // direction of the fill lines, CCW from +x
  bool solid = false;           // top/bottom/bridge/internal solid vs sparse
};

// A strictly connected region of material in one layer.
struct Island {
  Polygon shape;  // outer CCW, holes CW
  double area_mm2 = 0;
  int object = 0;  // the plate's object it belongs to
};

struct Layer {
  int index = 0;
  double z_bottom = 0;  // mm
  double z_top = 0;     // mm: the nozzle height while printing this layer
  double max_slope = 0;  // deg: layer.max_slope (geometry/slice/surface_slopes.h)
  double z_slice() const { return 0.5 * (z_bottom + z_top); }  // where the mesh is cut
  double height() const { return z_top - z_bottom; }

  Rings loops;                  // closed loops from slicing, oriented by the mesh (CCW = outer)
  std::vector<Island> islands;  // after overlap resolution and strict-connectivity splitting
};

}  // namespace tranche::geo
