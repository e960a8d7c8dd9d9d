#include "geometry/export/layers_svg.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "geometry/io/text_out.h"

namespace tranche::exports {

using geo::append_mm;
using schema::PathKind;

namespace {

constexpr size_t kBatch = 64;

// PrusaSlicer's preview colours, so a user sees the kinds as in the slicers they know.
struct KindStyle {
  PathKind kind;
  const char* colour;
  const char* label;
};
constexpr KindStyle kKinds[] = {
    {PathKind::OuterPerimeter, "#ff7d38", "outer perimeter"}, {PathKind::InnerPerimeter, "#ffe64d", "inner perimeter"},
    {PathKind::Infill, "#b03029", "infill"},                  {PathKind::SolidInfill, "#9654cc", "solid infill"},
    {PathKind::TopSolid, "#f04040", "top solid"},             {PathKind::BottomSolid, "#9654cc", "bottom solid"},
    {PathKind::Bridge, "#4d80ba", "bridge"},                  {PathKind::Skirt, "#00876e", "skirt"},
    {PathKind::Ironing, "#ff8c69", "ironing"},                {PathKind::Custom, "#5ed194", "custom"},
    {PathKind::Support, "#00ff00", "support"},                {PathKind::SupportInterface, "#008000", "support interface"},
    {PathKind::Brim, "#00876e", "brim"},                      {PathKind::GapFill, "#a0a0a0", "gap fill"},
};

void append_ring(fmt::memory_buffer& out, const geo::Ring& r, bool close) {
  for (size_t k = 0; k < r.size(); ++k) {
    out.append(std::string_view(k == 0 ? "M" : k == 1 ? "L" : " "));
    append_mm(out, r[k].X);
    out.push_back(' ');
    append_mm(out, -r[k].Y);
  }
  if (close) out.push_back('Z');
}

void append_paths(fmt::memory_buffer& out, const std::vector<plan::PathPlan>& paths) {
  for (const plan::PathPlan& p : paths) {
    if (p.pts.size() < 2) continue;
    fmt::format_to(std::back_inserter(out),
                   "<path class=\"path {}\" tranche:cell=\"{}\" tranche:width=\"{}\" stroke-width=\"{}\" d=\"",
                   kind_name(p.kind), p.cell, p.width, p.width);
    append_ring(out, p.pts, false);
    out.append(std::string_view("\"/>\n"));
  }
}

// The seed's exact cells (analysis), and the cuts between them once each: the real edges are the
// island's own rings.
void append_exact(fmt::memory_buffer& out, const std::vector<geo::Cell>& cells) {
  auto it = std::back_inserter(out);
  for (const auto& cell : cells) {
    fmt::format_to(it, "<path class=\"exact-cell\" tranche:fill-angle=\"{}\" tranche:area=\"{}\" d=\"",
                   cell.fill_angle_deg, std::abs(geo::area_mm2(cell.ring)));
    append_ring(out, cell.ring, true);
    out.append(std::string_view("\"/>\n"));
  }
  bool cuts = false;
  for (const auto& cell : cells) {
    for (size_t k = 0; k < cell.ring.size() && k < cell.edges.size(); ++k) {
      const geo::Point& a = cell.ring[k];
      const geo::Point& b = cell.ring[(k + 1) % cell.ring.size()];
      if (cell.edges[k] != geo::EdgeKind::Artificial || !(a.X < b.X || (a.X == b.X && a.Y < b.Y))) continue;
      out.append(std::string_view(cuts ? "M" : "<path class=\"edge artificial\" d=\"M"));
      cuts = true;
      append_mm(out, a.X);
      out.push_back(' ');
      append_mm(out, -a.Y);
      out.push_back('L');
      append_mm(out, b.X);
      out.push_back(' ');
      append_mm(out, -b.Y);
    }
  }
  if (cuts) out.append(std::string_view("\"/>\n"));
}

}  // namespace

Sheet sheet_layout(const std::vector<geo::Layer>& layers, bool legend) {
  Sheet s;
  for (const auto& l : layers)
    for (const auto& i : l.islands)
      for (const auto& p : i.shape.outer) s.model.add(p);
  if (s.model.empty()) s.model.add({0, 0}), s.model.add({geo::to_units(10), geo::to_units(10)});
  const double w = geo::to_mm(s.model.max_x - s.model.min_x), h = geo::to_mm(s.model.max_y - s.model.min_y);
  const double size = std::max({w, h, 1e-3});
  s.pad = 0.08 * size;
  s.caption = 0.1 * size;
  s.cell_w = w + 2 * s.pad;
  s.cell_h = h + 2 * s.pad + s.caption;
  // About 16:10 overall, so that the whole sheet fits a browser window.
  const double n = static_cast<double>(std::max<size_t>(layers.size(), 1));
  s.cols = static_cast<size_t>(std::clamp(std::ceil(std::sqrt(1.6 * n * s.cell_h / s.cell_w)), 1.0, n));
  s.rows = (static_cast<size_t>(n) + s.cols - 1) / s.cols;
  if (legend) s.legend = s.caption;
  return s;
}

void LayersSvg::append_layer(fmt::memory_buffer& out, const ExportLayer& e, size_t slot, const Sheet& s) {
  const geo::Layer& layer = *e.layer;
  auto it = std::back_inserter(out);
  const double cx = static_cast<double>(slot % s.cols) * s.cell_w,
               cy = s.legend + static_cast<double>(slot / s.cols) * s.cell_h;
  const double min_x = geo::to_mm(s.model.min_x), max_y = geo::to_mm(s.model.max_y);
  // Group coordinates are (x, −y): the translation puts the model's top-left corner in the cell.
  const double tx = cx + s.pad - min_x, ty = cy + s.caption + s.pad + max_y;
  double area = 0;
  for (const auto& i : layer.islands) area += i.area_mm2;
  fmt::format_to(it,
                 "<g id=\"layer-{0}\" class=\"layer\" tranche:index=\"{0}\" tranche:z-bottom=\"{1}\" "
                 "tranche:z-top=\"{2}\" tranche:z-slice=\"{3}\" tranche:area=\"{4}\" tranche:islands=\"{5}\" "
                 "transform=\"translate({6:.4f} {7:.4f})\">\n",
                 layer.index, layer.z_bottom, layer.z_top, layer.z_slice(), area, layer.islands.size(), tx, ty);
  fmt::format_to(it, "<rect class=\"frame\" x=\"{:.4f}\" y=\"{:.4f}\" width=\"{:.4f}\" height=\"{:.4f}\"/>\n",
                 min_x - s.pad * 0.9, -max_y - s.pad * 0.9 - s.caption, s.cell_w - 0.2 * s.pad,
                 s.cell_h - 0.2 * s.pad);
  fmt::format_to(it, "<text class=\"caption\" x=\"{:.4f}\" y=\"{:.4f}\" font-size=\"{:.4f}\">#{} z {:.3f}</text>\n",
                 min_x - s.pad * 0.4, -max_y - s.pad * 0.4 - s.caption * 0.25, s.caption * 0.7, layer.index,
                 layer.z_top);
  for (size_t i = 0; i < layer.islands.size(); ++i) {
    const geo::Island& island = layer.islands[i];
    fmt::format_to(it, "<path class=\"island\" tranche:index=\"{}\" tranche:area=\"{}\" fill-rule=\"evenodd\" d=\"",
                   i, island.area_mm2);
    append_ring(out, island.shape.outer, true);
    for (const auto& h : island.shape.holes) append_ring(out, h, true);
    out.append(std::string_view("\"/>\n"));
    if (const plan::IslandPlan* ip = e.printed_on(i)) append_paths(out, ip->paths);
    if (e.exact && i < e.exact->size()) append_exact(out, (*e.exact)[i]);
  }
  for (const plan::IslandPlan* sp : e.support) append_paths(out, sp->paths);
  if (e.skirt) append_paths(out, *e.skirt);
  out.append(std::string_view("</g>\n"));
}

Result<std::unique_ptr<LayersSvg>> LayersSvg::open(const std::string& path, const std::string& source,
                                                   size_t layer_count, const Sheet& s, bool printed) {
  auto file = OutputFile::create(path, "the SVG export");
  if (!file) return file.error();
  std::unique_ptr<LayersSvg> w(new LayersSvg(std::move(*file)));
  const double width = static_cast<double>(s.cols) * s.cell_w,
               height = s.legend + static_cast<double>(s.rows) * s.cell_h;
  fmt::memory_buffer head;
  auto it = std::back_inserter(head);
  fmt::format_to(it,
                 "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                 "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:tranche=\"{}\" "
                 "tranche:format=\"tranche-layers-svg\" tranche:version=\"{}\" tranche:units=\"mm\" "
                 "tranche:layers=\"{}\" tranche:source=\"",
                 kTrancheSvgNamespace, kLayersSvgVersion, layer_count);
  geo::append_xml_escaped(head, source);
  fmt::format_to(it, "\" viewBox=\"0 0 {:.4f} {:.4f}\">\n<title>", width, height);
  geo::append_xml_escaped(head, source);
  fmt::format_to(it,
                 ": {} layers</title>\n"
                 "<style>\n"
                 "svg {{ background: #f4f5f7; }}\n"
                 ".frame {{ fill: #ffffff; stroke: #c9ced6; stroke-width: 1px; vector-effect: non-scaling-stroke; }}\n"
                 ".caption, .legend text {{ fill: #4b5563; font-family: sans-serif; }}\n"
                 ".island {{ fill: #3b82c4; fill-opacity: {}; stroke: #1e3a5f; stroke-width: 0.75px; "
                 "vector-effect: non-scaling-stroke; }}\n"
                 ".path {{ fill: none; stroke-linecap: round; stroke-linejoin: round; stroke-opacity: 0.9; }}\n"
                 ".exact-cell {{ fill: none; stroke: #ffffff; stroke-opacity: 0.6; stroke-width: 0.5px; "
                 "vector-effect: non-scaling-stroke; }}\n"
                 ".edge.artificial {{ fill: none; stroke: #e0483e; stroke-width: 1px; stroke-dasharray: 4 3; "
                 "vector-effect: non-scaling-stroke; }}\n",
                 layer_count, printed ? "0.15" : "0.85");
  for (const KindStyle& k : kKinds) fmt::format_to(it, ".path.{} {{ stroke: {}; }}\n", kind_name(k.kind), k.colour);
  head.append(std::string_view("</style>\n"));
  if (printed) {
    // The legend: what each colour is; exact cells and cuts only appear with --exact-cells.
    const double fs = s.legend * 0.5, step = std::max(s.cols * s.cell_w / std::size(kKinds), fs * 8);
    fmt::format_to(it, "<g class=\"legend\" font-size=\"{:.4f}\">\n", fs);
    double x = s.pad;
    for (const KindStyle& k : kKinds) {
      fmt::format_to(it,
                     "<rect x=\"{:.4f}\" y=\"{:.4f}\" width=\"{:.4f}\" height=\"{:.4f}\" fill=\"{}\"/>"
                     "<text x=\"{:.4f}\" y=\"{:.4f}\">{}</text>\n",
                     x, s.legend * 0.3, fs, fs, k.colour, x + fs * 1.3, s.legend * 0.3 + fs * 0.9, k.label);
      x += step;
    }
    head.append(std::string_view("</g>\n"));
  }
  if (auto st = w->file_.write({head.data(), head.size()}); !st) return st.error();
  return w;
}

Status LayersSvg::finish() {
  if (Status s = file_.write("</svg>\n"); !s) return s;
  return file_.commit();
}

Status write_layers_svg(const std::string& path, const std::vector<geo::Layer>& layers, const std::string& source,
                        const std::function<void(size_t)>& progress) {
  const Sheet s = sheet_layout(layers, false);
  auto w = LayersSvg::open(path, source, layers.size(), s, false);
  if (!w) return w.error();
  std::vector<fmt::memory_buffer> batch(kBatch);
  for (size_t base = 0; base < layers.size(); base += kBatch) {
    const size_t n = std::min(kBatch, layers.size() - base);
    tbb::parallel_for(size_t{0}, n, [&](size_t i) {
      batch[i].clear();
      ExportLayer e;
      e.layer = &layers[base + i];
      LayersSvg::append_layer(batch[i], e, base + i, s);
    });
    for (size_t i = 0; i < n; ++i)
      if (auto st = (*w)->write_layer(batch[i]); !st) return st;
    if (progress) progress(base + n);
  }
  return (*w)->finish();
}

}  // namespace tranche::exports
