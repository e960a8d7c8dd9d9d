#include "geometry/polygon/layers.h"

#include <tbb/parallel_for.h>

#include <optional>

namespace tranche::geo {
namespace {

// Runs f(i) for every layer in parallel; returns the first error by layer index.
template <class F>
Status each_layer(size_t n, F&& f) {
  std::vector<std::optional<Error>> errors(n);
  tbb::parallel_for(size_t{0}, n, [&](size_t i) {
    Status st = f(i);
    if (!st) errors[i] = st.error();
  });
  for (auto& e : errors) {
    if (e) return *e;
  }
  return ok_status();
}

}  // namespace

Status resolve_layers(std::vector<Layer>& layers, const ResolveOptions& options, Report& report) {
  std::vector<Report> local(layers.size());
  Status st =
      each_layer(layers.size(), [&](size_t i) { return resolve_layer(layers[i], options, local[i]); });
  for (const Report& r : local) {
    for (Warning& w : r.warnings()) report.warn(std::move(w.code), std::move(w.where), std::move(w.message));
  }
  return st;
}

Status decompose_layers(std::vector<Layer>& layers, DecomposeStats* total) {
  std::vector<DecomposeStats> stats(layers.size());
  Status st = each_layer(layers.size(), [&](size_t i) { return decompose_layer(layers[i], &stats[i]); });
  if (total) {
    for (const DecomposeStats& s : stats) {
      total->sweep_cells += s.sweep_cells;
      total->cells += s.cells;
      total->cuts += s.cuts;
    }
  }
  return st;
}

}  // namespace tranche::geo
