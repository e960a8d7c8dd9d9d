#include "geometry/slice/simple_islands.h"

#include <atomic>
#include <exception>
#include <optional>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

namespace tranche::geo {

Result<Polygons> union_nonzero(const Rings& loops) {
  try {
    ClipperLib::Clipper clipper;
    // Nothing with an area to add: Clipper's Execute would report failure on the empty input.
    if (!clipper.AddPaths(loops, ClipperLib::ptSubject, true)) return Polygons{};
    ClipperLib::PolyTree tree;
    if (!clipper.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero))
      return Error{"", "polygon union failed"};
    return to_polygons(tree);
  } catch (const std::exception& e) {  // Clipper throws on coordinates beyond its range
    return Error{"", fmt::format("polygon union failed: {}", e.what())};
  }
}

Status make_islands(Layer& layer) {
  auto polys = union_nonzero(layer.loops);
  if (!polys) return Error{fmt::format("layer {}", layer.index), polys.error().message};
  layer.islands.clear();
  layer.islands.reserve(polys->size());
  for (auto& p : *polys) {
    Island island;
    island.area_mm2 = area_mm2(p);
    island.shape = std::move(p);
    layer.islands.push_back(std::move(island));
  }
  return ok_status();
}

Status make_islands(std::vector<Layer>& layers, const std::function<void(size_t)>& progress) {
  std::vector<std::optional<Error>> errors(layers.size());
  std::atomic<size_t> done{0};
  tbb::parallel_for(size_t{0}, layers.size(), [&](size_t i) {
    auto st = make_islands(layers[i]);
    if (!st) errors[i] = st.error();
    const size_t n = ++done;
    if (progress) progress(n);
  });
  for (auto& e : errors)
    if (e) return *e;
  return ok_status();
}

}  // namespace tranche::geo
