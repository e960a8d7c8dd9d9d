#include "geometry/pipeline/driver.h"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_pipeline.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <new>

#include "base/memory.h"
#include "geometry/pipeline/preview_adapter.h"
#include "geometry/plan/layer_loop.h"
#include "geometry/polygon/decompose.h"

namespace tranche::pipeline {
namespace {

// One layer on its way through the pipeline.
struct Item {
  int index = 0;
  Status status = ok_status();
  double time_s = 0, height = 0;
  gcode::LayerText text;
  fmt::memory_buffer svg, json;
  preview::PreviewLayer preview;
  Report warnings;  // passed on in layer order
};

// The seed's exact monotone cells of each island, at the angle the plan decided for it.
std::vector<std::vector<geo::Cell>> exact_cells(const exports::ExportLayer& e, Report& report) {
  const geo::Layer& layer = *e.layer;
  std::vector<std::vector<geo::Cell>> cells(layer.islands.size());
  for (size_t i = 0; i < layer.islands.size(); ++i) {
    const plan::IslandPlan* ip = e.printed_on(i);
    if (!ip) continue;
    const double angle = ip->props[schema::PropId::FillAngle];
    auto c = geo::decompose_island(layer, i, angle);
    if (c)
      cells[i] = std::move(*c);
    else
      report.warn("decompose-failed", fmt::format("layer {} island {}", layer.index, i),
                  fmt::format("the island could not be cut into exact cells at {}° ({}); the export shows none",
                              angle, c.error().message));
  }
  return cells;
}

Error layer_out_of_memory(int layer) {
  return out_of_memory("", fmt::format("slicing layer {}", layer));
}

// Plans layer i and formats everything the outputs need from it (runs in parallel).
void make_item(Item& item, const setup::PrintSetup& setup, const ctx::Cascade& cascade, const LayerOutputs& out) {
  auto plan = plan::plan_layer(setup, cascade, item.index);
  if (!plan) {
    item.status = plan.error();
    return;
  }
  item.time_s = plan->time_s;
  item.height = plan->height;
  if (out.gcode || out.preview) {  // the preview reads the executors' notes from the text
    auto text = gcode::format_layer(setup, cascade.executors(), *plan);
    if (!text) {
      item.status = text.error();
      return;
    }
    item.text = std::move(*text);
  }
  if (out.svg || out.json) {
    const auto l = static_cast<size_t>(item.index);
    exports::ExportLayer e = exports::planned_layer(out.resolved[l], *plan, setup.resolved_index[l]);
    std::vector<std::vector<geo::Cell>> exact;
    if (out.exact_cells) {
      exact = exact_cells(e, item.warnings);
      e.exact = &exact;
    }
    if (out.svg) exports::LayersSvg::append_layer(item.svg, e, static_cast<size_t>(item.index), *out.sheet);
    if (out.json) exports::LayersJson::append_layer(item.json, e);
  }
  if (out.preview) item.preview = preview_layer(setup, *plan, &item.text, out.rules);
}

// A move off the bed would hit the printer's frame: an error naming the layer and by how much,
// unless the user allowed it (then one warning for the run).
Status check_bed(const Item& item, const setup::PrintSetup& setup, Report& report, bool& warned) {
  const gcode::LayerText& t = item.text;
  if (t.off_bed_mm <= 0.001) return ok_status();
  const auto& b = setup.bed;
  const std::string where = fmt::format("layer {} (z {:.2f} mm)", item.index, setup.layers[static_cast<size_t>(item.index)].z_top);
  const std::string what = fmt::format(
      "a move reaches X{:.3f} Y{:.3f}, {:.2f} mm outside the bed ({}{:g} to {:g} x {:g} to {:g} mm)", t.off_bed_x,
      t.off_bed_y, t.off_bed_mm, b.circular ? "a circle in " : "", b.min_x, b.max_x, b.min_y, b.max_y);
  if (!setup.allow_off_bed)
    return Error{where, what + "; scale the model down (--scale), arrange the plate (--arrange), check bed_size_x/"
                                "bed_size_y and bed_origin_x/bed_origin_y, or, if the printer does reach it, "
                                "--allow-off-bed"};
  if (!warned) report.warn("off-bed", where, what + " (--allow-off-bed)");
  warned = true;
  return ok_status();
}

// Writes one layer to every output, in order.
Status write_item(const Item& item, const LayerOutputs& out) {
  if (out.gcode)
    if (Status s = out.gcode->layer(item.text, item.time_s, item.height); !s) return s;
  if (out.svg)
    if (Status s = out.svg->write_layer(item.svg); !s) return s;
  if (out.json)
    if (Status s = out.json->write_layer(item.json); !s) return s;
  if (out.preview)
    if (Status s = out.preview->add_layer(item.preview); !s) return s;
  return ok_status();
}

}  // namespace

Status run_layers(const setup::PrintSetup& setup, const ctx::Cascade& cascade, const LayerOutputs& outputs,
                  Report& report, const std::function<void(size_t)>& progress) {
  const int n = static_cast<int>(setup.layers.size());
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  Status first_error = ok_status();
  size_t written = 0;
  bool warned_off_bed = false;
  std::unique_ptr<tbb::global_control> limit;
  if (outputs.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, outputs.threads);
  const size_t tokens = static_cast<size_t>(2 * std::max(1, tbb::info::default_concurrency()));
  auto source = [&](tbb::flow_control& fc) {
    int i = next++;
    if (i >= n || failed.load()) {
      fc.stop();
      return 0;
    }
    return i;
  };
  auto work = [&](int i) {
    auto item = std::make_shared<Item>();
    item->index = i;
    try {
      if (!failed.load()) make_item(*item, setup, cascade, outputs);
    } catch (const std::bad_alloc&) {  // this layer's plan: the rest of the run is stopped cleanly
      item.reset();  // frees what the layer had made
      item = std::make_shared<Item>();
      item->index = i;
      item->status = layer_out_of_memory(i);
    }
    return item;
  };
  auto sink = [&](std::shared_ptr<Item> item) {
    if (failed.load()) return;
    for (Warning& w : item->warnings.warnings()) report.warn(std::move(w.code), std::move(w.where), std::move(w.message));
    Status s = item->status;
    if (s && outputs.gcode) s = check_bed(*item, setup, report, warned_off_bed);
    if (s && outputs.gcode && outputs.object_change_z > 0 && written == 0 && item->text.any_move)
      s = outputs.gcode->object_change(item->text.first, outputs.object_change_z);
    if (s) {
      try {
        s = write_item(*item, outputs);
      } catch (const std::bad_alloc&) {
        s = layer_out_of_memory(item->index);
      }
    }
    if (!s) {
      first_error = s;
      failed = true;
      return;
    }
    ++written;
    // Layers up to this one are done; those still running are above it and look at most
    // top_layers/bottom_layers (≤ 100) down.
    if (setup.layer_cache && item->index >= 101) setup.layer_cache->release(static_cast<size_t>(item->index - 101));
    if (progress) progress(written);
  };
  try {
    tbb::parallel_pipeline(tokens,
                           tbb::make_filter<void, int>(tbb::filter_mode::serial_in_order, source) &
                               tbb::make_filter<int, std::shared_ptr<Item>>(tbb::filter_mode::parallel, work) &
                               tbb::make_filter<std::shared_ptr<Item>, void>(tbb::filter_mode::serial_in_order, sink));
  } catch (const std::bad_alloc&) {  // the pipeline's own tokens and tasks
    return layer_out_of_memory(std::min(next.load(), n - 1));
  }
  return first_error;
}

}  // namespace tranche::pipeline
