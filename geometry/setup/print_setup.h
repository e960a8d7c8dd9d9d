// Print setup, the stage between the polygon stage and the layer loop: the model's facts
// measured once (print.height, size, volume), its placement on the bed, the layers every layer
// task reads (islands simplified once, for all readers), the table of every layer's fields, the
// skirt's hull, and the context the print's own hooks read. This is where several objects and
// support regions will join the print: everything a layer task shares is built here.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "base/report.h"
#include "base/result.h"
#include "geometry/core/layer.h"
#include "geometry/support/brim.h"
#include "geometry/support/support.h"
#include "geometry/toolpath/lightning.h"
#include "geometry/toolpath/motion.h"
#include "geometry/toolpath/relations.h"
#include "runtime/context/cascade.h"

namespace tranche::setup {

// The model as measured before slicing. Lengths mm, volume mm³; `box` in model units.
struct PrintFacts {
  double height = 0;  // top of the model after placing it on the bed (z = 0 at its bottom)
  double volume = 0;  // enclosed by the mesh (0 for drawings)
  geo::BBox2 box;     // XY extent; empty: the layers' extent (drawings)
  // The model is placed (a plate): its coordinates + `shift` are the bed's, and `box` is in bed
  // coordinates; else it is centred on the bed.
  bool placed = false;
  geo::Point shift;
  std::vector<std::string> objects;  // how messages name each object ("lid (copy 2)"), by Island::object
  std::vector<std::string> names;    // each object's own name, copies' too ("lid"), by Island::object
};

// The print context: the print fields (print.height, print.size_x/y, print.volume) of `facts`.
ctx::Context print_context(const PrintFacts& facts);

// What every layer task shares, read-only. Not movable: print_ctx points into it.
struct PrintSetup {
  PrintSetup() = default;
  PrintSetup(const PrintSetup&) = delete;
  PrintSetup& operator=(const PrintSetup&) = delete;

  // Islands simplified by inner_mm (no slicing loops): what walls, fill, support and the
  // relations between layers are made from.
  std::vector<geo::Layer> layers;
  // wall_outlines[l][i]: island i of layers[l] simplified by simplify_mm only, what its outer
  // wall follows; empty where that is the island itself (inner_mm == simplify_mm).
  std::vector<std::vector<geo::Rings>> wall_outlines;
  // resolved_index[l][i]: the index of island i of layers[l] among the islands as resolved (a
  // speck narrower than inner_mm is dropped, so the two may differ).
  std::vector<std::vector<uint32_t>> resolved_index;
  ctx::LayerTable table;            // every layer's layer-level fields, from `layers`
  ctx::Context print_ctx;           // print fields set (print.layers too), `table` bound
  ctx::PropertyValues print_props;  // the print stage, decided once
  geo::Point shift;                 // model units + shift = bed units
  toolpath::MotionLimits motion;
  geo::Rings skirt_around;      // what the skirt surrounds: the convex hull of layer 0
  // mm: the outer walls follow the outlines simplified this much (property `resolution`); all
  // else works on them simplified by inner_mm = max(resolution, kInnerResolutionMm): a polygon
  // operation costs in proportion to its vertices, and a few µm inside the walls print nowhere.
  static constexpr double kInnerResolutionMm = 0.025;
  double simplify_mm = 0.0125;
  double inner_mm = kInnerResolutionMm;
  // What the layer tasks ask of each of `layers` (material, grids, shrunk material), computed
  // once for the print; its contents are filled on first use, from any thread.
  std::shared_ptr<toolpath::LayerCache> layer_cache;
  // The print's hooks (start and end G-code) and the header read the print's context with layer
  // 0's layer fields, and layer 0's layer-stage properties (its temperatures).
  ctx::Context hook_ctx;
  ctx::PropertyValues hook_props;
  schema::Flavor flavor = schema::Flavor::Marlin;
  std::vector<std::string> objects;  // object names, by Island::object
  // object.name of each object, by Island::object: the index of its name among the rules' texts
  // (vm::RuleSet::text_index), -1 when no rule names it. Set by the caller that has the rules.
  std::vector<int> object_texts;
  // Record who decided what for every element (--export-preview); off, deciding records nothing.
  bool provenance = false;
  // The bed in G-code coordinates (mm), from the print stage: every move of every layer must
  // stay on it unless allow_off_bed (then a warning).
  struct Bed {
    bool circular = false;
    double min_x = 0, min_y = 0, max_x = 200, max_y = 200;  // the rectangle, or the circle's square
    // How far (mm) the point (x, y) lies outside the bed; 0 on it.
    double outside(double x, double y) const;
  } bed;
  bool allow_off_bed = false;
  // Support material and the brim, filled by plan/support_pass before the layer loop (empty:
  // none): per layer the support to print, each island's overhang (mm², island.overhang_area,
  // [layer][island]), and layer 0's brim.
  std::vector<support::SupportLayer> support;
  std::vector<std::vector<float>> overhang_area;
  std::vector<support::BrimPath> brim;
  // Lightning infill's branches for every layer, grown top down by the first layer task that
  // needs them (per spec: top layers, radius, inset) and shared: the one thing a layer task may
  // add to the setup.
  mutable toolpath::LightningCache lightning;
};

// Builds the setup of `layers` (resolved, bottom to top, not empty). `print_ctx` and
// `print_props` come from print_context() and the cascade's print stage; the model is centred
// on the bed (a warning names `model_name` when it is larger). Errors: a layer-stage rule that
// fails on layer 0.
Result<std::unique_ptr<PrintSetup>> make_setup(std::span<const geo::Layer> layers, const PrintFacts& facts,
                                               const ctx::Context& print_ctx,
                                               const ctx::PropertyValues& print_props,
                                               const ctx::Cascade& cascade, const std::string& model_name,
                                               Report& report);

}  // namespace tranche::setup
