#include "geometry/setup/print_setup.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "geometry/toolpath/clip.h"

namespace tranche::setup {

using schema::FieldId;
using schema::PropId;

ctx::Context print_context(const PrintFacts& facts) {
  ctx::Context c;
  const geo::BBox2& box = facts.box;
  c.set(FieldId::PrintHeight, facts.height);
  c.set(FieldId::PrintSizeX, box.empty() ? 0 : geo::to_mm(box.max_x - box.min_x));
  c.set(FieldId::PrintSizeY, box.empty() ? 0 : geo::to_mm(box.max_y - box.min_y));
  c.set(FieldId::PrintVolume, facts.volume);
  c.set(FieldId::ObjectCount, static_cast<double>(std::max<size_t>(facts.objects.size(), 1)));
  return c;
}

namespace {

// Each layer's islands are read by its own task and by its neighbours' (skins, overhang):
// simplified once here, in parallel, instead of by every reader. Only what the toolpath stage
// reads is kept (no slicing loops); `source` maps each kept island to its index as resolved.
// Islands are simplified by `inner_mm`; where `wall_mm` is finer, `walls` gets each island
// simplified by it too (the outline its outer wall follows), else stays empty.
std::vector<geo::Layer> simplify_layers(std::span<const geo::Layer> layers, double wall_mm, double inner_mm,
                                        std::vector<std::vector<geo::Rings>>& walls,
                                        std::vector<std::vector<uint32_t>>& source) {
  const geo::coord_t tol = geo::to_units(inner_mm), wall_tol = geo::to_units(wall_mm);
  const bool two = wall_tol < tol;
  std::vector<geo::Layer> out(layers.size());
  source.assign(layers.size(), {});
  walls.assign(two ? layers.size() : 0, {});
  tbb::parallel_for(size_t{0}, layers.size(), [&](size_t i) {
    const geo::Layer& src = layers[i];
    geo::Layer& dst = out[i];
    dst.index = src.index;
    dst.z_bottom = src.z_bottom;
    dst.z_top = src.z_top;
    dst.max_slope = src.max_slope;
    dst.islands.reserve(src.islands.size());
    for (uint32_t k = 0; k < src.islands.size(); ++k) {
      const geo::Island& isl = src.islands[k];
      geo::Island is;
      is.shape.outer = toolpath::simplify(isl.shape.outer, tol);
      if (is.shape.outer.empty()) continue;  // narrower than the tolerance
      // With two tolerances, the same rings at the finer one (a hole the coarse one dropped stays
      // dropped: it is narrower than 2 · inner_mm, and its wall would have nothing inside it).
      geo::Rings w;
      if (two) w.push_back(toolpath::simplify(isl.shape.outer, wall_tol));
      for (const auto& h : isl.shape.holes) {
        auto s = toolpath::simplify(h, tol);
        if (s.empty()) continue;
        is.shape.holes.push_back(std::move(s));
        if (two) w.push_back(toolpath::simplify(h, wall_tol));
      }
      if (two) walls[i].push_back(std::move(w));
      is.area_mm2 = isl.area_mm2;
      is.object = isl.object;
      dst.islands.push_back(std::move(is));
      source[i].push_back(k);
    }
  });
  return out;
}

double layer_area_mm2(const geo::Layer& l) {
  double area = 0;
  for (const auto& isl : l.islands) area += geo::area_mm2(isl.shape);
  return area;
}

}  // namespace

double PrintSetup::Bed::outside(double x, double y) const {
  if (circular) {
    const double cx = 0.5 * (min_x + max_x), cy = 0.5 * (min_y + max_y), r = 0.5 * (max_x - min_x);
    return std::max(0.0, std::hypot(x - cx, y - cy) - r);
  }
  const double dx = std::max({min_x - x, 0.0, x - max_x}), dy = std::max({min_y - y, 0.0, y - max_y});
  return std::hypot(dx, dy);
}

Result<std::unique_ptr<PrintSetup>> make_setup(std::span<const geo::Layer> layers, const PrintFacts& facts,
                                               const ctx::Context& print_ctx,
                                               const ctx::PropertyValues& print_props,
                                               const ctx::Cascade& cascade, const std::string& model_name,
                                               Report& report) {
  auto s = std::make_unique<PrintSetup>();
  const auto& P = print_props;
  s->print_props = P;
  s->flavor = static_cast<schema::Flavor>(static_cast<int>(P[PropId::GcodeFlavor]));
  // Placement: the model's XY extent centred on the bed (a drawing's: its layers').
  s->objects = facts.objects;
  s->bed.circular = P[PropId::BedShape] == static_cast<double>(schema::BedShape::Circular);
  s->bed.min_x = P[PropId::BedOriginX];
  s->bed.min_y = P[PropId::BedOriginY];
  s->bed.max_x = s->bed.min_x + P[PropId::BedSizeX];
  s->bed.max_y = s->bed.min_y + (s->bed.circular ? P[PropId::BedSizeX] : P[PropId::BedSizeY]);
  geo::BBox2 box = facts.box;
  if (box.empty())
    for (const auto& l : layers)
      for (const auto& isl : l.islands)
        for (const auto& p : isl.shape.outer) box.add(p);
  if (facts.placed) s->shift = facts.shift;
  if (!box.empty() && !facts.placed) {
    s->shift = geo::Point(geo::to_units(0.5 * (s->bed.min_x + s->bed.max_x)) - (box.min_x + box.max_x) / 2,
                          geo::to_units(0.5 * (s->bed.min_y + s->bed.max_y)) - (box.min_y + box.max_y) / 2);
    const double w = geo::to_mm(box.max_x - box.min_x), d = geo::to_mm(box.max_y - box.min_y);
    if (w > P[PropId::BedSizeX] || d > P[PropId::BedSizeY])
      report.warn("bed-size", model_name,
                  fmt::format("the model ({:.1f} × {:.1f} mm) is larger than the bed ({:g} × {:g} mm)", w, d,
                              P[PropId::BedSizeX], P[PropId::BedSizeY]));
  }
  s->simplify_mm = P[PropId::Resolution];
  s->inner_mm = std::max(s->simplify_mm, PrintSetup::kInnerResolutionMm);
  s->layers = simplify_layers(layers, s->simplify_mm, s->inner_mm, s->wall_outlines, s->resolved_index);
  s->layer_cache = std::make_shared<toolpath::LayerCache>(s->layers);
  s->table = ctx::LayerTable(s->layers.size());
  for (size_t i = 0; i < s->layers.size(); ++i) {
    const geo::Layer& l = s->layers[i];
    s->table.set(i, FieldId::LayerIndex, static_cast<double>(i));
    s->table.set(i, FieldId::LayerZBottom, l.z_bottom);
    s->table.set(i, FieldId::LayerZ, l.z_top);
    s->table.set(i, FieldId::LayerHeight, l.height());
    s->table.set(i, FieldId::LayerArea, layer_area_mm2(l));
    s->table.set(i, FieldId::LayerIslands, static_cast<double>(l.islands.size()));
    s->table.set(i, FieldId::LayerMaxSlope, l.max_slope);
  }
  s->print_ctx = print_ctx;
  s->print_ctx.set(FieldId::PrintLayers, static_cast<double>(s->layers.size()));
  s->print_ctx.set_layers(&s->table);
  // The skirt surrounds the convex hull of the first layer (as resolved: its outline's every point).
  geo::Ring pts;
  for (const auto& isl : layers.front().islands)
    for (const auto& p : isl.shape.outer) pts.push_back(p);
  s->skirt_around = toolpath::convex_hull(pts);
  // Layer-stage values of layer 0, which the print's hooks read ({nozzle_temp}, {bed_temp}).
  ctx::Context c0 = s->print_ctx;
  c0.clear_from(schema::Level::Layer);
  for (FieldId f : {FieldId::LayerIndex, FieldId::LayerZBottom, FieldId::LayerZ, FieldId::LayerHeight,
                    FieldId::LayerArea, FieldId::LayerIslands, FieldId::LayerMaxSlope})
    c0.set(f, s->table.get(0, f));
  s->hook_props = P;
  if (Status st = cascade.decide(schema::Stage::Layer, c0, s->hook_props); !st) return st.error();
  s->hook_ctx = c0;
  return s;
}

}  // namespace tranche::setup
