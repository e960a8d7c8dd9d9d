#include "geometry/support/brim.h"

#include <algorithm>

#include "geometry/support/overhang.h"
#include "geometry/toolpath/clip.h"

namespace tranche::support {

using geo::Rings;

namespace {

// `loop` (closed) minus `obstacles`, as open pieces; the loop whole when nothing cuts it.
std::vector<BrimPath> cut(const geo::Ring& loop, const Rings& obstacles) {
  const Rings near = toolpath::near(obstacles, geo::bbox(loop));
  if (near.empty()) return {{loop, true}};
  Rings pieces = toolpath::clip_loops({loop}, near, false);
  const double kept = lines_length(pieces);
  if (kept >= geo::length_mm(loop) - 1e-3) return {{loop, true}};  // nothing was cut
  std::vector<BrimPath> out;
  for (auto& p : pieces)
    if (p.size() >= 2) out.push_back({std::move(p), false});
  return out;
}

}  // namespace

std::vector<BrimPath> brim_paths(const std::vector<BrimIsland>& islands, const Rings& islands_all, double width_mm,
                                 double spacing_mm) {
  std::vector<BrimPath> out;
  int most = 0;
  for (const auto& b : islands) most = std::max(most, b.loops);
  if (most <= 0 || width_mm <= 0 || spacing_mm <= 0) return out;
  const Rings obstacles = toolpath::offset(islands_all, 0.4 * width_mm);
  for (int k = most - 1; k >= 0; --k) {  // outermost first
    Rings around;
    for (const auto& b : islands)
      if (b.loops > k) around.push_back(b.outline);
    for (const geo::Ring& r : toolpath::offset(toolpath::union_of(around), 0.5 * width_mm + k * spacing_mm)) {
      if (!ClipperLib::Orientation(r)) continue;  // a gap the brim closes round: no loop inside it
      for (BrimPath& p : cut(r, obstacles)) out.push_back(std::move(p));
    }
  }
  return out;
}

}  // namespace tranche::support
