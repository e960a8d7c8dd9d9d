// The plate's objects (geometry/plate: loaded, transformed, arranged, checked) sliced into one
// stack of layers: the print facts measured over every object, the print stage decided once, the
// layer heights planned for the tallest, then each object sliced and resolved on its own and its
// islands added to the layers, tagged with their object, at their place on the bed.
#pragma once

#include "geometry/slice/surface_slopes.h"
#include <string>
#include <vector>

#include "base/report.h"
#include "base/result.h"
#include "geometry/core/layer.h"
#include "geometry/pipeline/progress.h"
#include "geometry/plate/object.h"
#include "geometry/polygon/resolve.h"
#include "geometry/setup/print_setup.h"
#include "runtime/context/cascade.h"

namespace tranche::pipeline {

// The print stage, decided once: the print context and its decisions.
struct PrintStage {
  ctx::Context ctx;           // the print fields
  ctx::PropertyValues props;  // the print stage's decisions
};
Result<PrintStage> decide_print(const ctx::Cascade& cascade, const setup::PrintFacts& facts);

// The bed a print stage gives: bed_shape, bed_size_x/y, bed_origin_x/y, max_print_height.
plate::Bed bed_of(const ctx::PropertyValues& print);

// The bed before there is a plate. Placing the objects (arranging, --scale-to-fit, --center,
// the bed check) needs the bed, and the print stage's fields (print.height, print.size_x/y,
// print.volume, object.count) are measured on the placed plate: so the bed is decided first,
// from the print stage of an empty plate (those fields read 0). slice_plate's print stage, the
// one every later stage reads, must give the same bed (a rule that makes the bed depend on the
// plate is refused), so both decisions agree.
Result<plate::Bed> decide_bed(const ctx::Cascade& cascade);

// Layer heights from the cascade (layer_height, first_layer_height, --set) up to `top` mm.
// `slopes`, the models' surfaces (none for a drawing: only vertical walls), give layer.max_slope
// and, with adaptive_layers, the planner's height that layer_height rules start from.
// Errors: contradictory adaptive bounds (min_layer_height > max_layer_height, adaptive_quality
// outside 0–1) when adaptive_layers is on. Warns (`report`) when adaptive_layers is on but a
// rule or --set decides layer_height on every layer, so that the planner's heights are unused.
Result<std::vector<geo::Layer>> plan_heights(const ctx::Cascade& cascade, const PrintStage& print, double top,
                                             const std::string& model, const geo::SurfaceSlopes* slopes = nullptr,
                                             Report* report = nullptr);

struct SlicedPlate {
  std::vector<geo::Layer> layers;  // every object's islands (Island::object), in bed coordinates
  setup::PrintFacts facts;         // placed: the islands are where the bed has them
  PrintStage print;
  size_t triangles = 0;
};

// `resolve`: the overlap mode and strictness, applied to each object on its own.
Result<SlicedPlate> slice_plate(const plate::Plate& plate, const ctx::Cascade& cascade,
                                const geo::ResolveOptions& resolve, Progress& progress, Report& report);

}  // namespace tranche::pipeline
