// Zig-zag fill: parallel lines at the fill angle, each pair of consecutive lines joined by a
// connector that follows the shape's border between them, so a shape monotone with respect to
// the fill direction is filled by ONE continuous path with no travel. A shape that is not
// monotone is filled by several zig-zags, one per run of lines whose connectors stay between
// them: the runs are the shape's monotone cells at the resolution of the lines (a notch
// narrower than the pitch, which no line meets, does not cut the fill). Runs whose ends lie
// close along the border are then joined by a link along it (FillSpec::link_max_mm).
#pragma once

#include <utility>
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
  // The lines lie on the grid v = origin + k·pitch, v measured across the lines (mm, see
  // across_range): sparse fill uses a grid fixed to the bed (origin 0) so that cells and layers
  // line up; solid fill a grid spread from border to border of its whole region (region_grid),
  // shared by the region's cells so that lines continue straight across their cuts.
  double origin_mm = 0;
  // Line ends and connectors keep away from artificial edges so that two cells sharing a cut
  // do not lay beads on top of each other: line ends stop this far short of the cut along
  // the line (half a bead: the two round ends touch), connectors run this far·|sin θ| beside it.
  double artificial_inset_mm = 0.2;
  // Runs that cannot be one zig-zag (the shape is not monotone at this pitch) are joined end to
  // start by an extrusion along the shape's border when the walk along it is at most this long
  // (mm; 0: never): an anchor, as the lines' own connectors are, instead of a travel.
  double link_max_mm = 0;
};

// One continuous extrusion path: pts[i] -> pts[i+1] is piece i, border[i] says what it runs
// along (none for fill lines, real or artificial for connectors).
struct FillPath {
  geo::Ring pts;  // open polyline (not closed)
  std::vector<schema::Border> border;
  double area_mm2 = 0;  // area its lines fill: their length times the pitch
  int runs = 1;         // zig-zags joined by links along the border
};

// Range [lo, hi] (mm) of v = −x·sin a + y·cos a over the rings: the extent across lines at
// angle a (degrees).
std::pair<double, double> across_range(const geo::Rings& rings, double angle_deg);

// A grid for solid fill over the region spanning `range` (mm across the lines): lines on both
// borders and evenly between, as close to `pitch_mm` as fits. Returns the spec (origin, pitch)
// and the ratio actual / requested pitch, by which the flow is scaled to keep the volume exact.
struct SolidGrid {
  double origin_mm, pitch_mm, ratio;
};
SolidGrid region_grid(std::pair<double, double> range, double pitch_mm);

std::vector<FillPath> zigzag(const FillShape& shape, const FillSpec& spec);

// A FillShape whose edges are all of one kind.
FillShape fill_shape(const geo::Rings& rings, geo::EdgeKind kind);

}  // namespace tranche::toolpath
