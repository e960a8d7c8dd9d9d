#include "geometry/io/layers_json.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "base/output_file.h"
#include "geometry/io/text_out.h"

namespace tranche::geo {
namespace {

// Layers are formatted in parallel in batches of this many, then written in order: output
// memory stays bounded whatever the model.
constexpr size_t kBatch = 64;

void append_ring(fmt::memory_buffer& out, const Ring& ring) {
  out.push_back('[');
  for (size_t i = 0; i < ring.size(); ++i) {
    if (i) out.push_back(',');
    out.push_back('[');
    append_mm(out, ring[i].X);
    out.push_back(',');
    append_mm(out, ring[i].Y);
    out.push_back(']');
  }
  out.push_back(']');
}

// The island's monotone cells (geometry/polygon): fill angle, then each cell's ring with one
// letter per edge, r (real border) or a (artificial cut). Absent before decomposition.
void append_cells(fmt::memory_buffer& out, const Island& island) {
  if (std::isnan(island.fill_angle_deg)) return;
  fmt::format_to(std::back_inserter(out), ", \"fill_angle\": {}, \"cells\": [", island.fill_angle_deg);
  for (size_t c = 0; c < island.cells.size(); ++c) {
    const Cell& cell = island.cells[c];
    fmt::format_to(std::back_inserter(out), "{}{{\"area\": {}, \"ring\": ", c ? "," : "",
                   std::abs(area_mm2(cell.ring)));
    append_ring(out, cell.ring);
    out.append(std::string_view(", \"edges\": \""));
    for (const EdgeKind k : cell.edges) out.push_back(k == EdgeKind::Real ? 'r' : 'a');
    out.append(std::string_view("\"}"));
  }
  out.push_back(']');
}

}  // namespace

void append_layer_json(fmt::memory_buffer& out, const Layer& layer) {
  double area = 0;
  for (const auto& island : layer.islands) area += island.area_mm2;
  fmt::format_to(
      std::back_inserter(out),
      "{{\"index\": {}, \"z_bottom\": {}, \"z_top\": {}, \"z_slice\": {}, \"area\": {}, \"islands\": [",
      layer.index, layer.z_bottom, layer.z_top, layer.z_slice(), area);
  for (size_t i = 0; i < layer.islands.size(); ++i) {
    const Island& island = layer.islands[i];
    fmt::format_to(std::back_inserter(out), "{}\n  {{\"area\": {}, \"outer\": ", i ? "," : "",
                   island.area_mm2);
    append_ring(out, island.shape.outer);
    out.append(std::string_view(", \"holes\": ["));
    for (size_t h = 0; h < island.shape.holes.size(); ++h) {
      if (h) out.push_back(',');
      append_ring(out, island.shape.holes[h]);
    }
    out.push_back(']');
    append_cells(out, island);
    out.push_back('}');
  }
  out.append(std::string_view(layer.islands.empty() ? "]}" : "\n]}"));
}

Status write_layers_json(const std::string& path, const std::vector<Layer>& layers, const std::string& source,
                         const std::function<void(size_t)>& progress) {
  auto file = OutputFile::create(path, "the layer export");
  if (!file) return file.error();
  fmt::memory_buffer head;
  fmt::format_to(std::back_inserter(head),
                 "{{\"format\": \"tranche-layers\", \"version\": {}, \"units\": \"mm\", \"source\": ",
                 kLayersJsonVersion);
  append_json_string(head, source);
  fmt::format_to(std::back_inserter(head), ", \"layer_count\": {},\n\"layers\": [\n", layers.size());
  if (auto st = file->write({head.data(), head.size()}); !st) return st;

  std::vector<fmt::memory_buffer> batch(kBatch);
  for (size_t base = 0; base < layers.size(); base += kBatch) {
    const size_t n = std::min(kBatch, layers.size() - base);
    tbb::parallel_for(size_t{0}, n, [&](size_t i) {
      batch[i].clear();
      append_layer_json(batch[i], layers[base + i]);
      batch[i].append(std::string_view(base + i + 1 < layers.size() ? ",\n" : "\n"));
    });
    for (size_t i = 0; i < n; ++i)
      if (auto st = file->write({batch[i].data(), batch[i].size()}); !st) return st;
    if (progress) progress(base + n);
  }
  if (auto st = file->write("]}\n"); !st) return st;
  return file->commit();
}

}  // namespace tranche::geo
