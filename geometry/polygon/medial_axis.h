// Medial axis (skeleton) of a region: the points inside it that have two or more nearest points
// on its border, with their distance to the border, which is half the region's local width.
// Gap fill and variable-width walls lay one bead along it whose width follows that distance.
//
// Built from the Voronoi diagram of the border's segments (Boost.Polygon, confined to the .cpp):
// the diagram's edges that lie inside the region, chained into polylines between branch points.
// Curved edges (between a reflex corner and a segment) are sampled.
#pragma once

#include <vector>

#include "geometry/core/geom.h"

namespace tranche::geo {

struct AxisPath {
  Ring pts;                       // polyline along the middle of the region
  std::vector<double> radius_mm;  // per point: distance to the region's border (half the local width)
  bool closed = false;            // a loop around a hole: ends at its first point
  // Whether the path's first / last point is a free end (no other path of the axis meets it
  // there): the region ends about radius_mm beyond it.
  bool free_start = false, free_end = false;
};

struct AxisOptions {
  // Curved edges are sampled every `sample_mm` at most.
  double sample_mm = 0.1;
  // A branch that runs from a junction to an end (into a corner of the border) is pruned when
  // its length plus the radius at its end is less than `corner_prune` times the radius at the
  // junction: the corners of a bar (90°: 1.41 × the radius), rounded or not, are not part of its
  // axis; a sharp wedge's tip (30°: 3.9 ×) is. A chain with no junction is always kept.
  double corner_prune = 2.0;
};

// The medial axis of `region` (rings under non-zero fill: outlines counter-clockwise, holes
// clockwise, as Clipper returns them). Rings must not cross one another; degenerate input
// (fewer than 3 points, zero area, coordinates beyond ±1073 mm) gives no axis, never an error.
std::vector<AxisPath> medial_axis(const Rings& region, const AxisOptions& opt = {});

}  // namespace tranche::geo
