// Beads of varying width along the medial axis of a region: gap fill (the slivers no loop or
// fill line covers) and the walls too thin for a loop. Each bead follows the region's middle and
// its width follows the region's local width, so that a 0.6 mm wall is one 0.6 mm bead and a
// wedge is filled to its tip.
//
// Widths are in the bead-spacing sense of flow.h: a region 2r wide gets a bead of width
// 2r + h·(1 − π/4), whose stadium cross-section holds exactly 2r·h of plastic per mm, as two
// beads of a fill sit one spacing apart.
#pragma once

#include <vector>

#include "geometry/core/geom.h"

namespace tranche::toolpath {

struct VarBead {
  geo::Ring pts;              // polyline; a bead along a closed axis ends at its first point
  std::vector<float> widths;  // mm, one per piece (pts.size() − 1)
  double mean_width() const;  // length-weighted, mm
};

struct BeadSpec {
  double min_width = 0.1;  // mm: parts of the region narrower than this (2r) are left out
  double max_width = 0.8;  // mm: wider parts get a bead this wide, centred
  double height = 0.2;     // mm, layer height
  // mm: a piece's width changes by at most this along it (longer axis edges are split).
  double width_step = 0.05;
  // Beads side by side across the axis: 1 for gap fill (one bead, clamped to max_width); more
  // for variable-width walls, where a part of local width t gets n = ceil(t / max_width) beads
  // (at most max_beads) each t/n wide, and a change of n ends the beads of one count and starts
  // the other's.
  int max_beads = 1;
};

// The beads along the medial axis of `region` (rings under non-zero fill). At a free end of the
// axis the beads are lengthened so that their plastic matches the region's up to its end. Beads
// shorter than half their width are dropped (a dot of plastic, not a bead); no piece has zero length or a
// non-finite width, and no width exceeds max_width.
// A part of the region whose axis is pruned away entirely (a square, a disc: every branch runs
// into a corner) gets a closed bead instead, half its inner radius r in from its border and r
// wide (r = 2·area / perimeter: a disc's radius, a square's half side).
std::vector<VarBead> axis_beads(const geo::Rings& region, const BeadSpec& spec);
// The beads along the axis only, and the closed beads of the parts they miss.
std::vector<VarBead> axis_beads_only(const geo::Rings& region, const BeadSpec& spec);
std::vector<VarBead> blob_loops(const geo::Rings& region, const std::vector<VarBead>& beads, const BeadSpec& spec);

// The parts of `island` no bead covers: the island minus `covered` (the loops' and fill's
// reach, under non-zero fill: overlapping areas may be listed side by side, outers
// counter-clockwise, and count as their union), opened so that slivers narrower than
// `min_width` mm are dropped.
geo::Rings uncovered(const geo::Rings& island, const geo::Rings& covered, double min_width);

}  // namespace tranche::toolpath
