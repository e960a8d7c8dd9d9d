// Lightning infill: branching trees that hold up only the tops above (Cura's and PrusaSlicer's
// lightning, written anew and smaller). Computed top down for all layers at once, before the
// layer tasks need it:
//   outline(i)  where layer i has sparse infill: its material shrunk by the walls (`inset_mm`),
//               under material on each of the top_layers layers above;
//   need(i)     outline(i) less a band of h·tan(angle) along its border (the walls hold that),
//               less outline(i + 1): the undersides of the solid layers that start above i.
// Layer i's forest is the one of layer i + 1 carried down, then grown:
//   carried     each leaf shortened by h·tan(angle) ("prune": a branch leans at most `angle`
//               from vertical), chains of single nodes pulled straight by up to h·tan(angle)
//               ("straighten"), nodes outside outline(i) and edges that leave it removed;
//   regrounded  a tree whose root is no longer on the border is joined to a node of another
//               tree (merging them) or to the nearest point of the border, by the cost below;
//   grown       points of need(i) on a grid of radius/6, nearest the border first, each not
//               within `radius_mm` of a leaf yet becomes one (PrusaSlicer's lightning: a leaf
//               holds the points round it, its branch none): joined to the tree node or the
//               border of least cost, the border's its distance, a node's its distance less 4
//               radii when it has one to three edges (so that leaves join trees rather than
//               the walls and trees grow long), nodes looked for up to 4 radii (2.5 mm at most)
//               beyond the border's distance; joined to the border, it is a new tree anchored
//               at the walls. So a denser infill has more leaves on about as many trees, and
//               more plastic.
// A layer's branches are its forest's edges as open polylines: each tree walked from its root,
// a branch continuing its parent's polyline, every further one starting its own. The slicer clips
// them to the island's sparse region and joins them along its border as the other patterns
// (geometry/plan/island_content.cpp, toolpath::clip_fill_lines).
#pragma once

#include <map>
#include <mutex>
#include <span>
#include <tuple>
#include <vector>

#include "geometry/core/layer.h"

namespace tranche::toolpath {

struct LightningSpec {
  int top_layers = 3;      // solid layers under each top: the trees hold up the lowest one
  double radius_mm = 1.0;  // a point of a top is held when a leaf lies within this distance
  double inset_mm = 0.0;   // the sparse region's distance inside the material (the walls)
  double angle_deg = 40;   // overhang of branches from vertical (Cura's prune/straighten angle)
};

// Every layer's branches, bottom to top: open polylines in bed units. Bad specs (radius not
// above zero or not a number, angle not a number) give no branches.
std::vector<geo::Rings> lightning_trees(std::span<const geo::Layer> layers, const LightningSpec& spec);

// The areas lightning_trees() reads, for tests: every layer's outline and need (see above).
struct LightningAreas {
  std::vector<geo::Rings> outline, need;
};
LightningAreas lightning_areas(std::span<const geo::Layer> layers, const LightningSpec& spec);

// lightning_trees() of one print's layers, computed at the first request for a spec (top
// layers, radius and inset, the latter two to the micrometre) and kept: the layer tasks, run in
// parallel, share it. Thread-safe.
class LightningCache {
 public:
  // The branches of layer `index` of `layers` (always the same layers for one cache).
  const geo::Rings& lines(std::span<const geo::Layer> layers, int index, const LightningSpec& spec) const;

  // PrusaSlicer's lightning_infill_prune_angle, straightening and overhang angles (Cura's
  // default is 40°: 45° prunes the trees a layer height a layer).
  static constexpr double kAngleDeg = 45;

 private:
  mutable std::mutex mu_;
  mutable std::map<std::tuple<int, long long, long long, long long>, std::vector<geo::Rings>> by_spec_;
};

}  // namespace tranche::toolpath
