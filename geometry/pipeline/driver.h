// The parallel part of a run: every layer planned (geometry/plan) and formatted — its G-code
// text and its export fragments — in parallel, then handed in layer order to one writer per
// output, with TBB's pipeline, so only a few layers' toolpaths exist at a time.
#pragma once

#include <functional>
#include <span>

#include "base/report.h"
#include "base/result.h"
#include "geometry/export/layers_json.h"
#include "geometry/export/layers_svg.h"
#include "geometry/gcode/writer.h"
#include "geometry/preview/preview_data.h"
#include "geometry/setup/print_setup.h"
#include "runtime/context/cascade.h"
#include "runtime/vm/vm.h"

namespace tranche::pipeline {

// Where the layers go; any may be null.
struct LayerOutputs {
  gcode::GcodeWriter* gcode = nullptr;
  exports::LayersSvg* svg = nullptr;
  const exports::Sheet* sheet = nullptr;  // the SVG's layout
  exports::LayersJson* json = nullptr;
  std::span<const geo::Layer> resolved;  // the layers as resolved: the exports draw their islands
  bool exact_cells = false;  // the exports also show the seed's exact cells (analysis)
  preview::PreviewEncoder* preview = nullptr;  // --export-preview (needs PrintSetup::provenance for the chains)
  const vm::RuleSet* rules = nullptr;          // names the rules in the preview's provenance
  int threads = 0;           // 0: TBB's default
  // Sequential printing: > 0 for every object but the first, the height (mm) the head rises to
  // before crossing to this object's first layer (GcodeWriter::object_change).
  double object_change_z = 0;
};

// Plans every layer of `setup` and writes it to `outputs`, in order. `progress` is called with
// the number of layers written. Errors: the first by layer order (a rule's run-time error, a
// write that failed); warnings (exact cells that could not be cut) go to `report`.
Status run_layers(const setup::PrintSetup& setup, const ctx::Cascade& cascade, const LayerOutputs& outputs,
                  Report& report, const std::function<void(size_t)>& progress = {});

}  // namespace tranche::pipeline
