// The slope of a model's surface along z, for adaptive layer heights and layer.max_slope.
//
// A stack of layers of height h approximates a surface whose normal makes an angle with the
// vertical by stairs: the stair-step's height measured along the normal, the cusp height, is
// c = h · |n_z| (0 on a vertical wall, h on a flat one). Adaptive layers keep c at most a given
// cusp: h = cusp / |n_z| for every facet the layer crosses, clamped to [min, max] — thin layers
// where the surface is nearly flat (a dome's top), thick ones along walls. This is the cusp
// height method of PrusaSlicer's and Cura's adaptive slicing (Dolenc and Mäkelä), written from
// its description: its quality maps linearly to the cusp, from max_layer_height at 0 to
// min_layer_height at 1.
#pragma once

#include <cstdint>
#include <vector>

#include "base/result.h"
#include "geometry/mesh/mesh.h"

namespace tranche::geo {

struct AdaptiveParams {
  double min_height = 0.07;  // mm
  double max_height = 0.3;   // mm
  double quality = 0.5;      // 0 coarsest … 1 finest
  // The cusp height allowed (mm): max_height at quality 0, min_height at 1, linear between.
  double cusp() const { return max_height + (min_height - max_height) * quality; }
};

// Errors (a message naming the properties): min_height > max_height, a height that is not a
// positive finite number, a quality outside [0, 1].
Status check_adaptive(const AdaptiveParams& p);

class SurfaceSlopes {
 public:
  SurfaceSlopes() = default;
  // The facets of `mesh` (mm; placed with its bottom at z = 0) that are not vertical.
  void add(const Mesh& mesh);

  bool empty() const { return facets_.empty(); }

  // How far the surface leans from vertical (deg) at its flattest among the facets that reach
  // into the slab (z0, z1]: 0 when there are only vertical walls (or nothing), 90 with a
  // horizontal facet inside.
  double max_slope_deg(double z0, double z1) const;

  // The adaptive height of a layer whose bottom is at `z` (mm): the largest h in
  // [min_height, max_height] such that every sloped facet crossing (z, z + h) has
  // h · |n_z| ≤ cusp; a flatter facet starting above z ends the layer where it starts, when
  // that is at least min_height up; a horizontal facet (a flat top or a shelf) in
  // (z + min_height, z + h) ends the layer at its height, so flat surfaces land on layer
  // boundaries. Near the model's top, a rest thinner than min_height is not left for the last
  // layer: the last two layers share it.
  double adaptive_height(double z, const AdaptiveParams& p) const;

 private:
  struct Facet {
    double zmin, zmax, nz;  // mm; |n_z| of its unit normal
  };
  // Calls f(facet) for the facets meeting (z0, z1] (some more than once).
  template <class F>
  void for_each_in(double z0, double z1, F&& f) const;
  void rebuild_index();

  std::vector<Facet> facets_;
  // Facet indices by z: bucket b holds the facets meeting [b·step, (b+1)·step].
  std::vector<std::vector<uint32_t>> buckets_;
  double step_ = 0.05;
  double top_ = 0;  // mm: the highest vertex
};

}  // namespace tranche::geo
