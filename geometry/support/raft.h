// The raft: a few layers of support material under the whole first layer, printed before the
// part, which starts a gap above them (bed adhesion for ABS, for parts with a small or warped
// footprint). Pure geometry: plan/support_pass decides it from the print's raft_* properties.
#pragma once

#include <vector>

#include "base/result.h"
#include "geometry/core/layer.h"

namespace tranche::support {

struct RaftSpec {
  int layers = 0;               // raft layers (0: no raft)
  double first_height = 0.2;    // mm, the raft's first layer
  double height = 0.2;          // mm, its other layers
  double gap = 0.1;             // mm of air between the raft's top and the part's first layer
};

// `layers` (the part, bottom to top, from index 0 at z 0) lifted onto a raft: `spec.layers` empty
// layers put under them (indices 0 .. n-1, the first `first_height`, the others `height` thick),
// the part's layers renumbered after them and raised by the raft's thickness plus the gap.
void lift_onto_raft(std::vector<geo::Layer>& layers, const RaftSpec& spec);

// The raft's outline: `footprint` (the part's first layer and the support under and around it,
// model units) grown by `expansion_mm`, holes filled (a raft is one sheet), clipped to `bed` when
// it is not empty.
geo::Rings raft_region(const geo::Rings& footprint, double expansion_mm, const geo::Rings& bed);

// Whether raft layer `k` of `count` is printed dense: the first (it holds the raft to the bed)
// and the top one (the part lies on it); those between are sparse.
inline bool raft_layer_dense(int k, int count) { return k == 0 || k == count - 1; }

}  // namespace tranche::support
