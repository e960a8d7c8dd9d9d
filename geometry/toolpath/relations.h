// Layer relations: what lies below and above a layer, for the island fields (supported,
// covered), piece.overhang, and the solid regions of the fill (top and bottom skins, bridges,
// internal solid). A layer's material is the union of its islands (they are disjoint).
#pragma once

#include <map>
#include <span>
#include <utility>
#include <vector>

#include "geometry/core/layer.h"
#include "geometry/toolpath/edge_grid.h"
#include "runtime/schema/schema.h"

namespace tranche::toolpath {

// A layer's material as rings (outer CCW, holes CW, non-zero fill).
geo::Rings material(const geo::Layer& layer);

// The neighbourhood of one layer; window results are computed on first use and cached, so a
// layer whose islands all use the same top_layers/bottom_layers computes each window once.
// Not thread-safe: one per layer task.
class Neighbours {
 public:
  Neighbours(std::span<const geo::Layer> layers, int index);

  int index() const { return index_; }
  // Material of layer index + k (k may be negative); empty outside the print.
  const geo::Rings& layer(int k);
  // Layer index + k itself (its islands), or null outside the print.
  const geo::Layer* at(int k) const {
    const int i = index_ + k;
    return i >= 0 && static_cast<size_t>(i) < layers_.size() ? &layers_[static_cast<size_t>(i)] : nullptr;
  }
  // Region covered by all of the `n` layers above (n ≥ 1), resp. below; empty when any of them is
  // outside the print (a top or the bed-side bottom).
  const geo::Rings& all_above(int n);
  const geo::Rings& all_below(int n);
  // Where a spot stays sparse: covered by all `top` layers above and all `bottom` layers below
  // (either count may be 0: that side does not matter).
  const geo::Rings& keep_sparse(int top, int bottom);
  // Material below this layer as an edge grid (overhang, bridges).
  const EdgeGrid& below_grid() { return grid(-1); }
  // Material of layer index + k as an edge grid.
  const EdgeGrid& grid(int k);
  // Whether layer index + k covers all of `region` (whose own grid is `region_grid`): exact
  // segment and point tests, much cheaper than a boolean; touching counts as not covered.
  bool covers(int k, const geo::Rings& region, const EdgeGrid& region_grid);

 private:
  std::span<const geo::Layer> layers_;
  int index_;
  std::map<int, geo::Rings> material_;
  std::vector<geo::Rings> above_, below_;  // [n-1] = intersection of the n nearest layers
  std::map<std::pair<int, int>, geo::Rings> keep_;
  std::map<int, EdgeGrid> grids_;
};

// For each piece of the polyline `pts`, the fraction of a bead `width_mm` wide along it that
// does not rest on the material `below` (0..1), sampled across the bead at a quarter, half and
// three quarters of the piece.
std::vector<float> overhang_fractions(const geo::Ring& pts, double width_mm, const EdgeGrid& below);

// How far along a path piece.overhang is averaged: a piece shorter than this takes the
// length-weighted mean of the path over this length centred on its middle, so that the short
// pieces of a curved wall do not flip a rule's speed back and forth.
inline constexpr double kOverhangWindowMm = 2.0;

// `values` (one per piece of the polyline `pts`) averaged along it: each piece gets the
// length-weighted mean over max(window_mm, its length) of path centred on its middle, the
// window shifted inward at the path's ends (the whole path when it is shorter). Zero-length
// pieces take their neighbourhood's mean too.
std::vector<float> average_along(const std::vector<float>& values, const geo::Ring& pts, double window_mm);

// Fraction of `island` (area) lying on `other` (0..1); 0 for an empty island.
double fraction_on(const geo::Rings& island, const geo::Rings& other);

// The fill region of an island split by what it needs, in the order they are printed.
struct FillRegion {
  schema::PathKind kind;  // Infill, SolidInfill, TopSolid, BottomSolid or Bridge
  geo::Rings rings;
};

struct SolidSpec {
  int top_layers = 3, bottom_layers = 3;
  double density = 0.2;  // sparse infill density (≥ 1: everything solid)
  double width = 0.45;   // mm, fill bead width: slivers narrower than half of it are dropped
  // Ensure vertical shell thickness (vertical_shell): > 0, a depth (mm); the fill within that
  // depth of the border of a layer within top_layers above or bottom_layers below is solid too,
  // as if those layers ended that much further in, so that a gentle slope keeps a shell about as
  // thick as the perimeters (the fill that supports, or rests on, a neighbour's perimeters).
  double shell_mm = 0;
};

// Splits `fill` (one island's fill region) into bridge, bottom, top, internal solid and sparse
// regions: top = not covered by the layer above; solid = not covered by all of the next
// top_layers layers or not on all of the bottom_layers layers below; bridge = bottom over empty
// space (not on layer 0, where everything is bottom). Solid regions are grown by one bead into
// the sparse region so skins are anchored.
std::vector<FillRegion> split_fill(const geo::Rings& fill, Neighbours& nb, const SolidSpec& spec);

}  // namespace tranche::toolpath
