// Tree support: branches that grow from the overhangs down to the bed (or the part), leaning
// toward each other to merge and away from the part, so that far less plastic holds the same
// overhangs and touches the part only under them (Cura's tree support and PrusaSlicer 2.6's
// organic supports solve the same problem; this is our own, simpler growth).
//
// Tips are laid on a grid over each contact region. Going down one layer at a time, every branch
// moves at most height·tan(branch angle) sideways: toward its nearest neighbour (two branches
// closer than their radii merge into one, thicker), and out of the part grown by the xy gap and
// the branch's radius. A branch that cannot get out ends on the part (its last layers above it
// left out: the z gap); with support_on_bed_only the whole tree above it is dropped instead.
// Each branch widens as it descends. The layer's branches are the union of their discs and of
// bars that join branches standing close together (link_mm): the edges, no longer than link_mm,
// of a minimum spanning tree over the layer's branches. A bar holds the interface between the tips
// and makes a group of close branches print as one island, reached by one travel instead of one
// per branch (issue 12: the tips under a cap were each an island, ~60 trips a layer); as branches
// converge going down the bars shorten, so each bar stands on the one below it, and a bar is cut
// where it would lie on the part's top within the z gap.
#pragma once

#include <span>
#include <vector>

#include "geometry/core/layer.h"
#include "geometry/support/support.h"

namespace tranche::support {

struct TreeSpec {
  double tip_radius_mm = 0.6;     // a branch's radius where it meets the interface
  double max_radius_mm = 3;       // trunks stop widening here
  double widen_per_mm = 0.1;      // radius added per mm of descent
  double branch_angle_deg = 40;   // the most a branch leans from vertical
  double tip_spacing_mm = 7;      // tips on a grid this fine over each contact
  int bottom_gap_layers = 1;      // a branch ending on the part leaves this many layers of air
  double link_mm = 14;            // branches of a layer this close are joined by a bar (0: never)
  double link_radius_mm = 0.45;   // a bar's half width: two 0.45 mm beads, its wall
};

struct TreeResult {
  std::vector<geo::Rings> branches;  // per layer: the branches' cross-sections (the part and its gap cut out)
  double blocked_mm2 = 0;            // bed-only contacts whose trees could not reach the bed
  int tips = 0, trunks_on_bed = 0;   // for tests and the bench
};

// `in` as for project(): the part, contacts by layer (their regions), keep_out, bed.
TreeResult grow_trees(const ProjectInput& in, const TreeSpec& spec);

}  // namespace tranche::support
