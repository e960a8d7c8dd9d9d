// Zig-zag fill: parallel lines at the fill angle, each pair of consecutive lines joined by a
// connector that follows the shape's border between them, so a shape monotone with respect to
// the fill direction (a cell) is filled by ONE continuous path with no travel. A shape that is
// not monotone is filled by several zig-zags (one per run of connectable lines).
#pragma once

#include <vector>

#include "geometry/core/layer.h"
#include "runtime/schema/schema.h"

namespace tranche::toolpath {

// A shape to fill: rings (outer counter-clockwise, holes clockwise: material on the left of
// every edge) and the kind of each edge.
struct FillShape {
  geo::Rings rings;
  std::vector<std::vector<geo::EdgeKind>> kinds;  // kinds[r][i]: edge rings[r][i] -> rings[r][i+1]
};

struct FillSpec {
  double angle_deg = 45;  // direction of the lines, counter-clockwise from +x
  double pitch_mm = 0.4;  // distance between consecutive lines
  // Sparse fill puts its lines on a grid fixed to the bed (v = k·pitch) so that cells and
  // layers line up; solid fill spreads its lines evenly from border to border of each shape.
  bool bed_grid = false;
  // Distance kept from artificial edges (half a bead), so that the connectors of two cells
  // sharing a cut lie side by side instead of on top of each other. Real edges are followed.
  double artificial_inset_mm = 0.2;
};

// One continuous extrusion path: pts[i] -> pts[i+1] is piece i, border[i] says what it runs
// along (none for fill lines, real or artificial for connectors).
struct FillPath {
  geo::Ring pts;  // open polyline (not closed)
  std::vector<schema::Border> border;
  // Solid fill spreads its lines evenly from border to border: actual pitch / requested pitch.
  // Scaling the flow by it keeps the deposited volume per area exact.
  double pitch_ratio = 1.0;
};

std::vector<FillPath> zigzag(const FillShape& shape, const FillSpec& spec);

// A FillShape whose edges are all of one kind.
FillShape fill_shape(const geo::Rings& rings, geo::EdgeKind kind);

}  // namespace tranche::toolpath
