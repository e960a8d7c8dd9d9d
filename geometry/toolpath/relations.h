// Layer relations: what lies below and above a layer, for the island fields (supported,
// covered), piece.overhang, and the solid regions of the fill (top and bottom skins, bridges,
// internal solid). A layer's material is the union of its islands (they are disjoint).
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include "geometry/core/layer.h"
#include "geometry/toolpath/edge_grid.h"
#include "runtime/schema/schema.h"

namespace tranche::toolpath {

// A layer's material as rings (outer CCW, holes CW, non-zero fill).
geo::Rings material(const geo::Layer& layer);

// Whether `m` (rings with their grid `g`) covers all of `region` (with its grid): exact segment
// and point tests, much cheaper than a boolean; touching counts as not covered.
bool covers(const geo::Rings& m, const EdgeGrid& g, const geo::Rings& region, const EdgeGrid& region_grid);

// What the layer tasks ask of each layer, computed once for the whole print and shared by them
// (thread-safe): its material as rings and as an edge grid, and its material shrunk by a depth
// (the vertical shell's test, asked of each layer by the three or so layers on either side).
// What is returned stays valid until release(i), which the caller does only when no task can
// still ask for layer i (the layer loop: once every layer up to i + 100, the farthest a layer
// looks, is done).
class LayerCache {
 public:
  explicit LayerCache(std::span<const geo::Layer> layers);
  size_t size() const { return layers_.size(); }
  const geo::Rings& material(size_t i);
  const EdgeGrid& grid(size_t i);
  struct Eroded {
    geo::Rings rings;  // arcs to 25 µm
    EdgeGrid grid;
  };
  const Eroded& eroded(size_t i, double mm);
  // The intersection of layers first .. first + n - 1 (n ≥ 1, all in the print), each shrunk by
  // `mm`, intersected in that order: a layer's window above is the window below of the layer n + 1
  // higher, so each is computed once for the print instead of once by each. Held with layer
  // `first` (released with it).
  const geo::Rings& eroded_window(size_t first, int n, double mm);
  // Frees what layer i holds (asked again, it is computed again).
  void release(size_t i);

 private:
  struct Slot {
    std::mutex mutex;  // held while filling: a task asking for the same layer waits for it
    bool has_material = false, has_grid = false;
    geo::Rings material;
    EdgeGrid grid;
    std::vector<std::pair<double, std::unique_ptr<Eroded>>> eroded;  // by depth (one in practice)
    // (n, depth) → the window of n layers from this one (see eroded_window).
    std::vector<std::pair<std::pair<int, double>, std::unique_ptr<geo::Rings>>> windows;
  };
  const geo::Rings& material_locked(size_t i, Slot& s);
  const Eroded& eroded_locked(size_t i, Slot& s, double mm);
  std::span<const geo::Layer> layers_;
  std::unique_ptr<Slot[]> slots_;
};

// The neighbourhood of one layer; window results are computed on first use and cached, so a
// layer whose islands all use the same top_layers/bottom_layers computes each window once.
// Not thread-safe: one per layer task. With a LayerCache, what is asked of single layers comes
// from it (shared by every task).
class Neighbours {
 public:
  Neighbours(std::span<const geo::Layer> layers, int index, LayerCache* cache = nullptr);

  int index() const { return index_; }
  // Material of layer index + k (k may be negative); empty outside the print.
  const geo::Rings& layer(int k);
  // Layer index + k itself (its islands), or null outside the print.
  const geo::Layer* at(int k) const {
    const int i = index_ + k;
    return i >= 0 && static_cast<size_t>(i) < layers_.size() ? &layers_[static_cast<size_t>(i)] : nullptr;
  }
  // Layer index + k's material shrunk by `mm` (arcs to 25 µm) and its grid; null outside the
  // print.
  const LayerCache::Eroded* eroded(int k, double mm);
  // The intersection of the `n` nearest layers above (sign > 0) or below (sign < 0), each shrunk
  // by `mm`: where a spot is at least `mm` inside all of them. Null when one of them is outside
  // the print (a top or the bed-side bottom). Intersected from the lowest layer up, with or
  // without a cache (the same rings either way).
  const geo::Rings* all_eroded(int sign, int n, double mm);
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
  LayerCache* cache_;
  std::map<int, geo::Rings> material_;
  std::map<int, EdgeGrid> grids_;
  std::map<std::pair<int, double>, LayerCache::Eroded> eroded_;  // without a cache
  // Without a cache: (first layer index, n, mm) → the window (LayerCache::eroded_window).
  std::map<std::tuple<int, int, double>, geo::Rings> windows_;
};

// For each piece of the polyline `pts`, the fraction of a bead `width_mm` wide along it that
// does not rest on the material `below` (0..1), sampled across the bead at a quarter, half and
// three quarters of the piece (at its middle only when it is shorter than the bead is wide).
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

// The part of `fill` (one island's fill region, `fill_grid` its grid) that one of the next
// top_layers layers or of the bottom_layers below leaves uncovered, or (shell_mm > 0) that lies
// within shell_mm of one of their borders: split_fill's solid fill before strips narrower than
// half a bead are dropped and skins grown.
geo::Rings solid_region(const geo::Rings& fill, const EdgeGrid& fill_grid, Neighbours& nb, const SolidSpec& spec);

// Splits `fill` (one island's fill region) into bridge, bottom, top, internal solid and sparse
// regions: top = not covered by the layer above; solid = not covered by all of the next
// top_layers layers or not on all of the bottom_layers layers below; bridge = bottom over empty
// space (not on layer 0, where everything is bottom). Solid regions are grown by one bead into
// the sparse region so skins are anchored.
std::vector<FillRegion> split_fill(const geo::Rings& fill, Neighbours& nb, const SolidSpec& spec);

}  // namespace tranche::toolpath
