// Perimeters: closed loops that follow an island's real borders (its outline and holes) inward.
// Artificial cuts (hole bridging, the monotone decomposition) are made later, inside the fill
// region, so no loop ever runs along one.
//
// Loop k's centreline is the island shrunk by d_k, with round joins: d_0 = w_0/2 puts the outer
// bead's edge exactly on the outline (round joins reproduce reflex corners instead of
// overshooting them as a miter would), and d_k = d_{k-1} + spacing. Loops k ≥ 1 are opened
// (shrunk then grown by 0.3·spacing) so that where a part is too thin for them they vanish
// instead of laying two overlapping beads.
//
// Where a part is too thin for a loop, or a loop vanished and left a gap narrower than a fill
// bead, the uncovered part gets beads of varying width along its medial axis (gap_fill.h):
// - classic: loop 0 is opened too (its two sides must stay one bead spacing apart, so a 0.6 mm
//   wall gets no loop overlapping itself) with mitred grow-back, which keeps its corners sharp;
//   each uncovered part gets one bead along its axis, as wide as the part (up to
//   max_bead_width).
// - variable: every loop is opened so that it survives only where all the loops fit (a part at
//   least 2·d_last + spacing thick); the thinner parts get n beads side by side along their axis,
//   n = ceil(local width / max_bead_width), each 1/n of the local width, so no bead overlaps
//   another. Unlike Arachne (SkeletalTrapezoidation), the loops of the wide parts are not bent
//   into the thin ones and a change in bead count is a cut (the beads of either side end there)
//   rather than a smooth transition; the bead count is chosen per axis piece, not per region.
#pragma once

#include <vector>

#include "geometry/core/geom.h"
#include "geometry/toolpath/gap_fill.h"

namespace tranche::toolpath {

struct Loop {
  geo::Ring ring;  // centreline; counter-clockwise around material, clockwise around holes
  int depth = 0;   // 0 = outer perimeter
  bool hole = false;
};

enum class WallMode { Classic, Variable };

struct PerimeterSpec {
  std::vector<double> widths = {0.45, 0.45};  // mm, one per loop, outermost first
  double fill_width = 0.45;                   // mm, width of the infill that meets the innermost loop
  double height = 0.2;                        // mm, layer height
  double infill_overlap = 0.15;               // ratio of fill_width the fill region reaches into the loops
  WallMode mode = WallMode::Classic;
  double min_bead_width = 0.1;  // mm: narrower parts of gaps and thin walls are not printed
  double max_bead_width = 0.8;  // mm: widest bead along an axis
};

struct Perimeters {
  std::vector<Loop> loops;  // by depth, outermost first
  // Where the fill's centrelines may go: the island minus every loop's bead, kept one fill
  // spacing (less the overlap) away from the beads. It includes gaps a vanished loop left
  // when they are wide enough for a fill bead.
  geo::Rings fill_region;
  // Beads of varying width along the axis of what no loop or fill covers: gap fill, thin walls.
  std::vector<VarBead> beads;
};

// `island`: the island's outline and holes (non-zero fill). Widths and heights in mm.
// `wall_outline`: the same rings simplified less, when the island was simplified more (see
// setup::PrintSetup::inner_mm), or `island` itself: the outermost loop and the gaps follow them;
// the inner loops and the fill region are made from `island`.
Perimeters make_perimeters(const geo::Rings& island, const PerimeterSpec& spec,
                           const geo::Rings* wall_outline = nullptr);

}  // namespace tranche::toolpath
