// The brim: loops around the first layer's islands that hold them to the bed (ABS, tall thin
// parts). Each island asks for its own number of loops (brim_width, decided per island); where
// the brims of islands meet they merge, and a loop never runs over an island.
#pragma once

#include <vector>

#include "geometry/core/geom.h"

namespace tranche::support {

struct BrimIsland {
  geo::Ring outline;  // the island's outer ring (holes get no brim)
  int loops = 0;
};

struct BrimPath {
  geo::Ring pts;  // a loop (closed: last point != first) or, cut by an island, an open piece
  bool closed = true;
};

// The loops, outermost first (the brim ends next to the part). `islands_all`: every island of
// the layer (outer rings), which loops keep half a bead away from. Bead `width_mm`, loops
// `spacing_mm` apart, the first one's centre half a bead from the island.
std::vector<BrimPath> brim_paths(const std::vector<BrimIsland>& islands, const geo::Rings& islands_all, double width_mm,
                                 double spacing_mm);

}  // namespace tranche::support
