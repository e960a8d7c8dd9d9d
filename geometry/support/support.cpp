#include "geometry/support/support.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/relations.h"

namespace tranche::support {

using geo::Rings;

namespace {

constexpr geo::coord_t kSimplify = 12500;     // 12.5 µm, the islands' own resolution: the columns
constexpr geo::coord_t kPrintSimplify = 50000;  // 50 µm: what support prints (a bead is 450 µm)

Rings closing(const Rings& r, double mm) {
  return mm > 0 ? toolpath::offset_coarse(toolpath::offset_coarse(r, mm), -mm) : r;
}

// `r` without its rings of less than a bead's square: outlines no bead fits in, and holes too small
// to matter (the part's own holes in support are at least its xy gap across, twice; a hole in a
// dropped outline is smaller still, and must go with it).
Rings drop_specks(Rings r, double bead_mm) {
  const double min_area = bead_mm * bead_mm * geo::kUnitsPerMm * geo::kUnitsPerMm;
  std::erase_if(r, [&](const geo::Ring& ring) { return std::abs(ClipperLib::Area(ring)) < min_area; });
  return r;
}

// Union of the part below each layer (0..k), for bed-only contacts: computed only when one asks.
std::vector<Rings> footprints(std::span<const geo::Layer> layers) {
  std::vector<Rings> out(layers.size());
  Rings acc;
  for (size_t k = 0; k < layers.size(); ++k) {
    acc = toolpath::simplify(toolpath::union_of(acc, toolpath::material(layers[k])), kSimplify);
    out[k] = acc;
  }
  return out;
}

}  // namespace

namespace {

// What layer k prints of its column: the part and its gaps cut out, the interface under the
// contacts, the rest sparse. Layers are independent here: run in parallel.
SupportLayer print_layer(const ProjectInput& in, const std::vector<Rings>& material, size_t k, const Rings& column,
                         const Rings& iface_src) {
  SupportLayer out;
  if (column.empty()) return out;
  const geo::BBox2 box = toolpath::bbox(column);
  const Rings& keep = k < in.keep_out.size() && !in.keep_out[k].empty() ? in.keep_out[k] : material[k];
  // Simplified for printing only: done on the column itself, it would erode it layer after layer.
  // (The gaps are cut after: simplifying there would cut chords into them.)
  Rings printed = toolpath::difference(toolpath::simplify(column, kPrintSimplify), toolpath::near(keep, box));
  for (int g = 1; g <= in.bottom_gap_layers && static_cast<int>(k) - g >= 0; ++g)
    printed = toolpath::difference(printed, toolpath::near(material[k - static_cast<size_t>(g)], box));
  // The contacts of a slope are slivers a reach apart: closed, they make one band of interface.
  Rings iface = iface_src.empty() ? Rings{}
                                  : toolpath::intersection(printed, closing(toolpath::union_of(iface_src), 0.5 * in.merge_mm));
  // No opening here (it was two thirds of this function's time): the toolpaths erode each support
  // island by half a bead before filling it (plan::build_support), which removes every sliver
  // narrower than a bead just as an opening would; only specks are dropped now, so that they do
  // not become islands of their own.
  out.interface = drop_specks(std::move(iface), in.min_width_mm);
  // The interface is cut from a column simplified for printing, its sources are not: grown by a
  // little more than that simplification, it leaves no base sliver along its edge.
  const Rings iface_cut = toolpath::offset_coarse(out.interface, 1.2 * geo::to_mm(kPrintSimplify));
  out.base = drop_specks(toolpath::difference(printed, iface_cut), in.min_width_mm);
  out.area_mm2 = toolpath::area_mm2(out.base) + toolpath::area_mm2(out.interface);
  return out;
}

}  // namespace

ProjectResult project(const ProjectInput& in) {
  const size_t n = in.layers.size();
  std::vector<Rings> material(n);  // each layer's, computed once
  tbb::parallel_for(size_t{0}, n, [&](size_t k) { material[k] = toolpath::material(in.layers[k]); });
  ProjectResult res;
  res.layers.resize(n);
  const bool any_bed_only = std::any_of(in.contacts.begin(), in.contacts.end(), [](const auto& cs) {
    return std::any_of(cs.begin(), cs.end(), [](const Contact& c) { return c.bed_only; });
  });
  const std::vector<Rings> foot = any_bed_only ? footprints(in.layers) : std::vector<Rings>{};
  std::vector<Rings> iface_src(n), columns(n);
  Rings column;
  // Top-down, serial: each layer's column is the one above, plus its contacts, less the part.
  for (size_t k = n; k-- > 0;) {
    bool added = false;
    if (k < in.contacts.size())
      for (const Contact& c : in.contacts[k]) {
        Rings r = toolpath::simplify(c.region, kSimplify);  // once: slope slivers carry arcs of the reach
        if (c.bed_only) {
          Rings kept = toolpath::difference(r, foot[k]);
          res.blocked_mm2 += std::max(0.0, toolpath::area_mm2(r) - toolpath::area_mm2(kept));
          r = std::move(kept);
        }
        if (r.empty()) continue;
        if (in.columns) column.insert(column.end(), r.begin(), r.end()), added = true;
        for (int j = 0; j < c.interface_layers && static_cast<int>(k) - j >= 0; ++j)
          iface_src[k - static_cast<size_t>(j)].insert(iface_src[k - static_cast<size_t>(j)].end(), r.begin(), r.end());
      }
    if (!in.columns) column = iface_src[k], added = true;  // the interface alone, layer by layer
    if (column.empty()) continue;
    if (added) column = toolpath::union_of(column);
    if (Rings part = toolpath::near(material[k], toolpath::bbox(column)); !part.empty())
      column = toolpath::difference(column, part);
    // Only new contacts can reach past the bed: below them the column only shrinks.
    if (added && !in.bed.empty()) {
      Rings on = toolpath::intersection(column, in.bed);
      res.off_bed_mm2 += std::max(0.0, toolpath::area_mm2(column) - toolpath::area_mm2(on));
      column = std::move(on);
    }
    columns[k] = column;
  }
  tbb::parallel_for(size_t{0}, n, [&](size_t k) { res.layers[k] = print_layer(in, material, k, columns[k], iface_src[k]); });
  return res;
}

Rings bed_region(bool circular, double min_x, double min_y, double max_x, double max_y, const geo::Point& shift) {
  geo::Ring r;
  if (!circular) {
    for (auto [x, y] : {std::pair{min_x, min_y}, {max_x, min_y}, {max_x, max_y}, {min_x, max_y}})
      r.push_back(geo::Point(geo::to_units(x) - shift.X, geo::to_units(y) - shift.Y));
  } else {
    const double cx = 0.5 * (min_x + max_x), cy = 0.5 * (min_y + max_y), rad = 0.5 * (max_x - min_x);
    for (int i = 0; i < 256; ++i) {
      const double a = 2 * std::numbers::pi * i / 256;  // inscribed: never past the real bed
      r.push_back(geo::Point(geo::to_units(cx + rad * std::cos(a)) - shift.X, geo::to_units(cy + rad * std::sin(a)) - shift.Y));
    }
  }
  return {r};
}

}  // namespace tranche::support
