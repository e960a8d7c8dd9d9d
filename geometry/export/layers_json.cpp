#include "geometry/export/layers_json.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "geometry/io/text_out.h"

namespace tranche::exports {

using geo::append_mm;

namespace {

// Layers are formatted in parallel in batches of this many, then written in order: output
// memory stays bounded whatever the model.
constexpr size_t kBatch = 64;

void append_points(fmt::memory_buffer& out, const geo::Ring& ring) {
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

void append_paths(fmt::memory_buffer& out, const std::vector<plan::PathPlan>& paths) {
  out.push_back('[');
  for (size_t k = 0; k < paths.size(); ++k) {
    const plan::PathPlan& p = paths[k];
    fmt::format_to(std::back_inserter(out), "{}\n    {{\"kind\": \"{}\", \"cell\": {}, \"width\": {}, \"closed\": {}, \"points\": ",
                   k ? "," : "", kind_name(p.kind), p.cell, p.width, p.closed ? "true" : "false");
    append_points(out, p.pts);
    out.push_back('}');
  }
  out.push_back(']');
}

// What the G-code prints on the island: its fill angle, its cells (one zig-zag each), its paths.
void append_printed(fmt::memory_buffer& out, const plan::IslandPlan& ip) {
  fmt::format_to(std::back_inserter(out), ", \"fill_angle\": {}, \"replaced\": {}, \"cells\": [",
                 ip.props[schema::PropId::FillAngle], ip.replaced ? "true" : "false");
  for (size_t c = 0; c < ip.cells.size(); ++c) {
    const plan::CellPlan& cell = ip.cells[c];
    fmt::format_to(std::back_inserter(out), "{}{{\"index\": {}, \"solid\": {}, \"fill_angle\": {}, \"area\": {}}}",
                   c ? "," : "", cell.index, cell.solid ? "true" : "false", cell.fill_angle_deg, cell.area_mm2);
  }
  out.append(std::string_view("], \"paths\": "));
  append_paths(out, ip.paths);
}

// The seed's exact monotone cells (analysis): each ring with one letter per edge, r (real
// border) or a (artificial cut).
void append_exact(fmt::memory_buffer& out, const std::vector<geo::Cell>& cells) {
  out.append(std::string_view(", \"exact_cells\": ["));
  for (size_t c = 0; c < cells.size(); ++c) {
    const geo::Cell& cell = cells[c];
    fmt::format_to(std::back_inserter(out), "{}{{\"area\": {}, \"fill_angle\": {}, \"ring\": ", c ? "," : "",
                   std::abs(geo::area_mm2(cell.ring)), cell.fill_angle_deg);
    append_points(out, cell.ring);
    out.append(std::string_view(", \"edges\": \""));
    for (const geo::EdgeKind k : cell.edges) out.push_back(k == geo::EdgeKind::Real ? 'r' : 'a');
    out.append(std::string_view("\"}"));
  }
  out.push_back(']');
}

}  // namespace

void LayersJson::append_layer(fmt::memory_buffer& out, const ExportLayer& e) {
  const geo::Layer& layer = *e.layer;
  double area = 0;
  for (const auto& island : layer.islands) area += island.area_mm2;
  fmt::format_to(
      std::back_inserter(out),
      "{{\"index\": {}, \"z_bottom\": {}, \"z_top\": {}, \"z_slice\": {}, \"area\": {}, \"islands\": [",
      layer.index, layer.z_bottom, layer.z_top, layer.z_slice(), area);
  for (size_t i = 0; i < layer.islands.size(); ++i) {
    const geo::Island& island = layer.islands[i];
    fmt::format_to(std::back_inserter(out), "{}\n  {{\"index\": {}, \"area\": {}, \"outer\": ", i ? "," : "", i,
                   island.area_mm2);
    append_points(out, island.shape.outer);
    out.append(std::string_view(", \"holes\": ["));
    for (size_t h = 0; h < island.shape.holes.size(); ++h) {
      if (h) out.push_back(',');
      append_points(out, island.shape.holes[h]);
    }
    out.push_back(']');
    if (const plan::IslandPlan* ip = e.printed_on(i)) append_printed(out, *ip);
    if (e.exact && i < e.exact->size()) append_exact(out, (*e.exact)[i]);
    out.push_back('}');
  }
  out.push_back(']');
  if (!e.support.empty()) {  // support islands: their outline and what the G-code prints there
    out.append(std::string_view(", \"support\": ["));
    for (size_t k = 0; k < e.support.size(); ++k) {
      const plan::IslandPlan& sp = *e.support[k];
      fmt::format_to(std::back_inserter(out), "{}\n  {{\"area\": {}, \"outer\": ", k ? "," : "", sp.area);
      append_points(out, sp.shape.empty() ? geo::Ring{} : sp.shape[0]);
      out.append(std::string_view(", \"paths\": "));
      append_paths(out, sp.paths);
      out.push_back('}');
    }
    out.push_back(']');
  }
  if (e.skirt && !e.skirt->empty()) {
    out.append(std::string_view(", \"skirt\": "));
    append_paths(out, *e.skirt);
  }
  out.append(std::string_view(layer.islands.empty() ? "}" : "\n}"));
}

Result<std::unique_ptr<LayersJson>> LayersJson::open(const std::string& path, const std::string& source,
                                                     size_t layer_count, bool printed, bool exact) {
  auto file = OutputFile::create(path, "the layer export");
  if (!file) return file.error();
  std::unique_ptr<LayersJson> w(new LayersJson(std::move(*file)));
  fmt::memory_buffer head;
  fmt::format_to(std::back_inserter(head),
                 "{{\"format\": \"tranche-layers\", \"version\": {}, \"units\": \"mm\", \"source\": ",
                 kLayersJsonVersion);
  geo::append_json_string(head, source);
  fmt::format_to(std::back_inserter(head), ", \"layer_count\": {}, \"printed\": {}, \"exact_cells\": {},\n\"layers\": [\n",
                 layer_count, printed ? "true" : "false", exact ? "true" : "false");
  if (auto st = w->file_.write({head.data(), head.size()}); !st) return st.error();
  return w;
}

Status LayersJson::write_layer(const fmt::memory_buffer& element) {
  if (written_++ > 0)
    if (Status s = file_.write(",\n"); !s) return s;
  return file_.write({element.data(), element.size()});
}

Status LayersJson::finish() {
  if (Status s = file_.write(written_ ? "\n]}\n" : "]}\n"); !s) return s;
  return file_.commit();
}

Status write_layers_json(const std::string& path, const std::vector<geo::Layer>& layers, const std::string& source,
                         const std::function<void(size_t)>& progress) {
  auto w = LayersJson::open(path, source, layers.size(), false, false);
  if (!w) return w.error();
  std::vector<fmt::memory_buffer> batch(kBatch);
  for (size_t base = 0; base < layers.size(); base += kBatch) {
    const size_t n = std::min(kBatch, layers.size() - base);
    tbb::parallel_for(size_t{0}, n, [&](size_t i) {
      batch[i].clear();
      ExportLayer e;
      e.layer = &layers[base + i];
      LayersJson::append_layer(batch[i], e);
    });
    for (size_t i = 0; i < n; ++i)
      if (auto st = (*w)->write_layer(batch[i]); !st) return st;
    if (progress) progress(base + n);
  }
  return (*w)->finish();
}

}  // namespace tranche::exports
