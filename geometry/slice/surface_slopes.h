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
  // Layers over which the height may go from min_height to max_height (0: no smoothing).
  int smoothing = 0;
  // The cusp height allowed (mm): max_height at quality 0, min_height at 1, linear between.
  double cusp() const { return max_height + (min_height - max_height) * quality; }
};

// Errors (a message naming the properties): min_height > max_height, a height that is not a
// positive finite number, a quality outside [0, 1], a negative smoothing.
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
  // With `cap` (mm, at least min_height): the same, the layer no thicker than the cap (the
  // smoothing's, see SmoothHeights). With p.smoothing, a flat surface up to
  // smoothing + 1 layers up is reached by layers of one height (the distance shared evenly:
  // never thicker).
  double adaptive_height(double z, const AdaptiveParams& p, double cap = 1e300) const;

  // The height the slopes ask for across the slab (z0, z1]: the cusp over |n_z| of its flattest
  // sloped facet, clamped to [min_height, max_height] (max_height with none). Flat surfaces and
  // facets above the slab do not count: a height that changes only with the surface's slope.
  double cusp_height(double z0, double z1, const AdaptiveParams& p) const;

  double top() const { return top_; }  // mm: the highest vertex

 private:
  // adaptive_height from a first guess h (at most max_height) down, before the top's rest.
  double limit_height(double z, const AdaptiveParams& p, double h) const;
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

// Smoothing of adaptive heights (PrusaSlicer smooths its adaptive profile so that heights do not
// jump between neighbours): a cap on each layer's height that changes gradually along z, never
// above the cusp height, so the cusp limit still holds and only layers next to a change get
// thinner. The cap is the largest function c ≤ cusp_height whose square changes by at most
// 2·d per mm of z, d = (max_height − min_height) / smoothing: a layer of height h is then
// followed by one of at most √(h² + 2dh) < h + d, and by one of at least √(h² − 2dh) ≈ h − d
// where the cap falls (lower when the slopes or a flat surface end the layer earlier). The
// cusp height is sampled on slabs min_height / 2 thick, the cap interpolated between them; a
// layer gets the cap's lowest value over its height, so it ramps down before a flatter surface.
class SmoothHeights {
 public:
  SmoothHeights() = default;  // caps nothing
  // A cap from z = 0 to the model's top; none when p.smoothing is 0 or the slopes are empty.
  SmoothHeights(const SurfaceSlopes& slopes, const AdaptiveParams& p);
  // The cap on a layer whose bottom is at z (mm): the cap's lowest over the layer; a huge number
  // when there is none.
  double cap(double z) const;

 private:
  double at(double z) const;  // the cap's value at z
  double step_ = 0;          // mm between samples
  std::vector<double> sq_;   // the cap's square at z = k · step_ (mm²)
};

}  // namespace tranche::geo
