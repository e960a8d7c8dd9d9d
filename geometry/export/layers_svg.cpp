#include "geometry/io/svg_export.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "base/output_file.h"
#include "geometry/io/text_out.h"

namespace tranche::geo {
namespace {

constexpr size_t kBatch = 64;

// The contact sheet's grid, in mm of the sheet.
struct Sheet {
  BBox2 model;                  // all layers' islands (units)
  double pad = 0, caption = 0;  // mm
  double cell_w = 0, cell_h = 0;
  size_t cols = 1, rows = 1;
};

Sheet layout(const std::vector<Layer>& layers) {
  Sheet s;
  for (const auto& l : layers)
    for (const auto& i : l.islands)
      for (const auto& p : i.shape.outer) s.model.add(p);
  if (s.model.empty()) s.model.add({0, 0}), s.model.add({to_units(10), to_units(10)});
  const double w = to_mm(s.model.max_x - s.model.min_x), h = to_mm(s.model.max_y - s.model.min_y);
  const double size = std::max({w, h, 1e-3});
  s.pad = 0.08 * size;
  s.caption = 0.1 * size;
  s.cell_w = w + 2 * s.pad;
  s.cell_h = h + 2 * s.pad + s.caption;
  // About 16:10 overall, so that the whole sheet fits a browser window.
  const double n = static_cast<double>(std::max<size_t>(layers.size(), 1));
  s.cols = static_cast<size_t>(std::clamp(std::ceil(std::sqrt(1.6 * n * s.cell_h / s.cell_w)), 1.0, n));
  s.rows = (static_cast<size_t>(n) + s.cols - 1) / s.cols;
  return s;
}

void append_layer(fmt::memory_buffer& out, const Layer& layer, size_t slot, const Sheet& s) {
  auto it = std::back_inserter(out);
  const double cx = static_cast<double>(slot % s.cols) * s.cell_w,
               cy = static_cast<double>(slot / s.cols) * s.cell_h;
  const double min_x = to_mm(s.model.min_x), max_y = to_mm(s.model.max_y);
  // Group coordinates are (x, −y): the translation puts the model's top-left corner in the cell.
  const double tx = cx + s.pad - min_x, ty = cy + s.caption + s.pad + max_y;
  double area = 0;
  for (const auto& i : layer.islands) area += i.area_mm2;
  fmt::format_to(it,
                 "<g id=\"layer-{0}\" class=\"layer\" tranche:index=\"{0}\" tranche:z-bottom=\"{1}\" "
                 "tranche:z-top=\"{2}\" tranche:z-slice=\"{3}\" tranche:area=\"{4}\" tranche:islands=\"{5}\" "
                 "transform=\"translate({6:.4f} {7:.4f})\">\n",
                 layer.index, layer.z_bottom, layer.z_top, layer.z_slice(), area, layer.islands.size(), tx,
                 ty);
  fmt::format_to(it, "<rect class=\"frame\" x=\"{:.4f}\" y=\"{:.4f}\" width=\"{:.4f}\" height=\"{:.4f}\"/>\n",
                 min_x - s.pad * 0.9, -max_y - s.pad * 0.9 - s.caption, s.cell_w - 0.2 * s.pad,
                 s.cell_h - 0.2 * s.pad);
  fmt::format_to(
      it, "<text class=\"caption\" x=\"{:.4f}\" y=\"{:.4f}\" font-size=\"{:.4f}\">#{} z {:.3f}</text>\n",
      min_x - s.pad * 0.4, -max_y - s.pad * 0.4 - s.caption * 0.25, s.caption * 0.7, layer.index,
      layer.z_top);
  for (const auto& island : layer.islands) {
    fmt::format_to(it, "<path class=\"island\" tranche:area=\"{}\" fill-rule=\"evenodd\" d=\"",
                   island.area_mm2);
    auto ring = [&](const Ring& r) {
      for (size_t k = 0; k < r.size(); ++k) {
        out.append(std::string_view(k == 0 ? "M" : k == 1 ? "L" : " "));
        append_mm(out, r[k].X);
        out.push_back(' ');
        append_mm(out, -r[k].Y);
      }
      out.push_back('Z');
    };
    ring(island.shape.outer);
    for (const auto& h : island.shape.holes) ring(h);
    out.append(std::string_view("\"/>\n"));
    // Monotone cells (geometry/polygon), and the cuts between them once each: the real edges
    // are the island's own rings above.
    for (const auto& cell : island.cells) {
      fmt::format_to(it, "<path class=\"cell\" tranche:fill-angle=\"{}\" tranche:area=\"{}\" d=\"",
                     cell.fill_angle_deg, std::abs(area_mm2(cell.ring)));
      ring(cell.ring);
      out.append(std::string_view("\"/>\n"));
    }
    bool cuts = false;
    for (const auto& cell : island.cells) {
      for (size_t k = 0; k < cell.ring.size() && k < cell.edges.size(); ++k) {
        const Point& a = cell.ring[k];
        const Point& b = cell.ring[(k + 1) % cell.ring.size()];
        if (cell.edges[k] != EdgeKind::Artificial || !(a.X < b.X || (a.X == b.X && a.Y < b.Y))) continue;
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
  out.append(std::string_view("</g>\n"));
}

}  // namespace

Status write_layers_svg(const std::string& path, const std::vector<Layer>& layers, const std::string& source,
                        const std::function<void(size_t)>& progress) {
  auto file = OutputFile::create(path, "the SVG export");
  if (!file) return file.error();
  const Sheet s = layout(layers);
  const double width = static_cast<double>(s.cols) * s.cell_w,
               height = static_cast<double>(s.rows) * s.cell_h;
  fmt::memory_buffer head;
  auto it = std::back_inserter(head);
  fmt::format_to(it,
                 "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                 "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:tranche=\"{}\" "
                 "tranche:format=\"tranche-layers-svg\" tranche:version=\"{}\" tranche:units=\"mm\" "
                 "tranche:layers=\"{}\" tranche:source=\"",
                 kTrancheSvgNamespace, kLayersSvgVersion, layers.size());
  append_xml_escaped(head, source);
  fmt::format_to(it, "\" viewBox=\"0 0 {:.4f} {:.4f}\">\n<title>", width, height);
  append_xml_escaped(head, source);
  fmt::format_to(
      it,
      ": {} layers</title>\n"
      "<style>\n"
      "svg {{ background: #f4f5f7; }}\n"
      ".frame {{ fill: #ffffff; stroke: #c9ced6; stroke-width: 1px; vector-effect: non-scaling-stroke; }}\n"
      ".caption {{ fill: #4b5563; font-family: sans-serif; }}\n"
      ".island {{ fill: #3b82c4; fill-opacity: 0.85; stroke: #1e3a5f; stroke-width: 0.75px; "
      "vector-effect: non-scaling-stroke; }}\n"
      ".cell {{ fill: none; stroke: #ffffff; stroke-opacity: 0.6; stroke-width: 0.5px; "
      "vector-effect: non-scaling-stroke; }}\n"
      ".edge.artificial {{ fill: none; stroke: #e0483e; stroke-width: 1px; stroke-dasharray: 4 3; "
      "vector-effect: non-scaling-stroke; }}\n"
      "</style>\n",
      layers.size());
  if (auto st = file->write({head.data(), head.size()}); !st) return st;

  std::vector<fmt::memory_buffer> batch(kBatch);
  for (size_t base = 0; base < layers.size(); base += kBatch) {
    const size_t n = std::min(kBatch, layers.size() - base);
    tbb::parallel_for(size_t{0}, n, [&](size_t i) {
      batch[i].clear();
      append_layer(batch[i], layers[base + i], base + i, s);
    });
    for (size_t i = 0; i < n; ++i)
      if (auto st = file->write({batch[i].data(), batch[i].size()}); !st) return st;
    if (progress) progress(base + n);
  }
  if (auto st = file->write("</svg>\n"); !st) return st;
  return file->commit();
}

}  // namespace tranche::geo
