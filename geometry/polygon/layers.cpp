#include "geometry/polygon/layers.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include <atomic>
#include <optional>

namespace tranche::geo {
namespace {

// Runs f(i) for every layer in parallel; returns the first error by layer index.
template <class F>
Status each_layer(size_t n, const LayerProgress& progress, F&& f) {
  std::vector<std::optional<Error>> errors(n);
  std::atomic<size_t> done{0};
  tbb::parallel_for(size_t{0}, n, [&](size_t i) {
    Status st = f(i);
    if (!st) errors[i] = st.error();
    if (progress) progress(++done);
  });
  for (auto& e : errors) {
    if (e) return *e;
  }
  return ok_status();
}

}  // namespace

Status resolve_layers(std::vector<Layer>& layers, const ResolveOptions& options, Report& report,
                      const LayerProgress& progress) {
  std::vector<Report> local(layers.size());
  Status st = each_layer(layers.size(), progress,
                         [&](size_t i) { return resolve_layer(layers[i], options, local[i]); });
  for (const Report& r : local) {
    for (Warning& w : r.warnings()) report.warn(std::move(w.code), std::move(w.where), std::move(w.message));
  }
  return st;
}

Result<std::vector<LayerCells>> decompose_layers(const std::vector<Layer>& layers, const IslandAngle& angle,
                                                 DecomposeStats* total, Report* report,
                                                 const LayerProgress& progress) {
  std::vector<LayerCells> out(layers.size());
  std::vector<DecomposeStats> stats(layers.size());
  std::vector<Report> local(layers.size());
  Status st = each_layer(layers.size(), progress, [&](size_t i) -> Status {
    const Layer& layer = layers[i];
    out[i].resize(layer.islands.size());
    for (size_t k = 0; k < layer.islands.size(); ++k) {
      const double a = angle(layer, k);
      DecomposeStats s;
      auto cells = decompose_island(layer, k, a, &s);
      if (!cells) {
        if (!report) return cells.error();
        local[i].warn("decompose-failed", fmt::format("layer {} island {}", layer.index, k),
                      fmt::format("the island could not be cut into cells at {}° ({}); it has no cells", a,
                                  cells.error().message));
        continue;
      }
      out[i][k] = std::move(*cells);
      stats[i].sweep_cells += s.sweep_cells;
      stats[i].cells += s.cells;
      stats[i].cuts += s.cuts;
    }
    return ok_status();
  });
  if (report) {
    for (const Report& r : local) {
      for (Warning& w : r.warnings())
        report->warn(std::move(w.code), std::move(w.where), std::move(w.message));
    }
  }
  if (total) {
    for (const DecomposeStats& s : stats) {
      total->sweep_cells += s.sweep_cells;
      total->cells += s.cells;
      total->cuts += s.cuts;
    }
  }
  if (!st) return st.error();
  return out;
}

}  // namespace tranche::geo
