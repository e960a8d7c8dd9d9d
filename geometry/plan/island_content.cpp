#include "geometry/plan/island_content.h"

#include <algorithm>

#include "geometry/toolpath/cells.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/flow.h"
#include "geometry/toolpath/perimeters.h"
#include "geometry/toolpath/zigzag.h"

namespace tranche::plan {

using ctx::PropertyValues;
using schema::PathKind;
using schema::PropId;
using toolpath::EdgeGrid;
using toolpath::FillRegion;

void measure_island(IslandPlan& ip, const geo::Point& shift, toolpath::Neighbours& nb, bool relations) {
  ip.area = toolpath::area_mm2(ip.shape);
  ip.border_length = 0;
  ip.holes = 0;
  for (const auto& r : ip.shape) {
    ip.border_length += geo::length_mm(r);
    if (!ClipperLib::Orientation(r)) ++ip.holes;
  }
  geo::BBox2 b = toolpath::bbox(ip.shape);
  if (!b.empty()) {
    ip.size_x = geo::to_mm(b.max_x - b.min_x);
    ip.size_y = geo::to_mm(b.max_y - b.min_y);
    ip.center_x = geo::to_mm((b.min_x + b.max_x) / 2 + shift.X);
    ip.center_y = geo::to_mm((b.min_y + b.max_y) / 2 + shift.Y);
  }
  if (relations) {
    ip.supported = nb.index() == 0 ? 1.0 : toolpath::fraction_on(ip.shape, nb.layer(-1));
    ip.covered = toolpath::fraction_on(ip.shape, nb.layer(1));
  }
}

namespace {

// One fill region's cells: a zig-zag per cell, on the region's grid of lines at `angle`.
Status build_cells(IslandPlan& ip, Nest& nest, const FillRegion& region, const std::vector<const EdgeGrid*>& borders,
                   double angle, double height_mm) {
  const bool solid = region.kind != PathKind::Infill;
  TraceRef log;
  auto props = nest.path_props(ip.props, region.kind, -1, &log);
  if (!props) return props.error();
  double w = (*props)[PropId::Width];
  double s = toolpath::bead_spacing_mm(w, height_mm);
  double density = solid ? 1.0 : (*props)[PropId::InfillDensity];
  if (density <= 0) return ok_status();
  toolpath::FillSpec fs;
  fs.angle_deg = angle;
  fs.pitch_mm = s / std::min(density, 1.0);
  fs.artificial_inset_mm = 0.5 * s;
  double flow_scale = 1.0;
  if (solid) {  // border to border of the whole region, shared by its cells
    toolpath::SolidGrid g = toolpath::region_grid(toolpath::across_range(region.rings, angle), s);
    fs.origin_mm = g.origin_mm;
    fs.pitch_mm = g.pitch_mm;
    flow_scale = std::clamp(g.ratio, 0.6, 1.4);
  }
  // Zig-zags that cannot continue one another are joined by a walk along the border of at most
  // five line pitches (sparse: 11 mm at 20 %, about PrusaSlicer's 12 mm infill anchors) or 16
  // beads (solid: 6.7 mm, half the way round a 4 mm hole). On the Stanford bunny, solid links of
  // 2 / 8 / 16 beads leave 5192 / 4529 / 4228 trips.
  fs.link_max_mm = solid ? 16 * s : 5 * fs.pitch_mm;
  // Each zig-zag is a cell: a monotone piece of the region at the resolution of its lines.
  // Edges within a quarter bead of the island's fill border are on it (see region_shape).
  for (toolpath::FillPath& fp : toolpath::zigzag(toolpath::region_shape(region.rings, borders, 0.25 * w), fs)) {
    CellPlan cell;
    cell.index = static_cast<int>(ip.cells.size());
    cell.area_mm2 = fp.area_mm2;
    cell.fill_angle_deg = angle;
    cell.solid = solid;
    ip.cells.push_back(cell);
    PathPlan p;
    p.kind = region.kind;
    p.cell = cell.index;
    p.width = static_cast<float>(w);
    p.flow_scale = static_cast<float>(flow_scale);
    if (solid) p.border_flow = 0.5f;
    p.pts = std::move(fp.pts);
    p.border = std::move(fp.border);
    p.props = *props;
    p.trace = nest.path_log(log);
    ip.paths.push_back(std::move(p));
  }
  return ok_status();
}

}  // namespace

Status build_island(IslandPlan& ip, Nest& nest, toolpath::Neighbours& nb, double height_mm,
                    std::vector<FillGrid>& regions) {
  ip.paths.clear();
  ip.cells.clear();
  regions.clear();
  const PropertyValues& P = ip.props;
  const int count = static_cast<int>(P[PropId::Perimeters]);
  toolpath::PerimeterSpec spec;
  spec.widths.clear();
  std::vector<PropertyValues> loop_props;
  std::vector<TraceRef> loop_logs(static_cast<size_t>(std::max(count, 0)));
  for (int k = 0; k < count; ++k) {
    auto p = nest.path_props(P, k == 0 ? PathKind::OuterPerimeter : PathKind::InnerPerimeter, k,
                             &loop_logs[static_cast<size_t>(k)]);
    if (!p) return p.error();
    spec.widths.push_back((*p)[PropId::Width]);
    loop_props.push_back(*p);
  }
  auto fill_props = nest.path_props(P, PathKind::Infill, -1);
  if (!fill_props) return fill_props.error();
  spec.fill_width = (*fill_props)[PropId::Width];
  spec.height = height_mm;
  spec.infill_overlap = P[PropId::InfillOverlap];
  spec.min_feature = P[PropId::NozzleDiameter] / 3;
  toolpath::Perimeters per = toolpath::make_perimeters(ip.shape, spec);
  for (auto& loop : per.loops) {
    PathPlan p;
    p.kind = loop.depth == 0 ? PathKind::OuterPerimeter : PathKind::InnerPerimeter;
    p.perimeter = loop.depth;
    p.closed = true;
    p.width = static_cast<float>(spec.widths[static_cast<size_t>(loop.depth)]);
    p.flow_scale = static_cast<float>(loop.flow_scale);
    p.pts = std::move(loop.ring);
    p.props = loop_props[static_cast<size_t>(loop.depth)];
    p.trace = nest.path_log(loop_logs[static_cast<size_t>(loop.depth)]);
    ip.paths.push_back(std::move(p));
  }
  if (per.fill_region.empty()) return ok_status();
  toolpath::SolidSpec ss;
  ss.top_layers = static_cast<int>(P[PropId::TopLayers]);
  ss.bottom_layers = static_cast<int>(P[PropId::BottomLayers]);
  ss.density = P[PropId::InfillDensity];
  ss.width = spec.fill_width;
  const double angle = P[PropId::FillAngle];
  auto fill = toolpath::split_fill(per.fill_region, nb, ss);
  // Solid zig-zags leave small notches between line ends on the side without a connector; their
  // regions reach a further quarter bead into the perimeters so that the beads cover those.
  const double reach = 0.25 * spec.fill_width;
  geo::Rings wide;
  for (auto& region : fill) {
    if (region.kind == PathKind::Infill) continue;
    if (wide.empty()) wide = toolpath::offset(per.fill_region, reach);
    region.rings = toolpath::intersection(toolpath::offset(region.rings, reach), wide);
  }
  // The island's fill border: where sparse regions meet the perimeters, and (grown) where solid
  // ones do.
  EdgeGrid fill_grid(per.fill_region), wide_grid(wide);
  std::vector<const EdgeGrid*> borders{&fill_grid};
  if (!wide.empty()) borders.push_back(&wide_grid);
  for (const FillRegion& region : fill) {
    if (Status s = build_cells(ip, nest, region, borders, angle, height_mm); !s) return s;
    regions.push_back({region.kind, EdgeGrid(region.rings)});
  }
  return ok_status();
}

Status build_support(IslandPlan& ip, Nest& nest, double height_mm, PathKind kind, bool wall,
                     std::vector<FillGrid>& regions) {
  ip.paths.clear();
  ip.cells.clear();
  regions.clear();
  const PropertyValues& P = ip.props;
  TraceRef log;
  auto props = nest.path_props(P, kind, -1, &log);
  if (!props) return props.error();
  const double w = (*props)[PropId::Width];
  const bool iface = kind == PathKind::SupportInterface;
  const double density = std::min(1.0, P[iface ? PropId::SupportInterfaceDensity : PropId::SupportDensity]);
  if (density <= 0) return ok_status();
  // Bead edges stay on the region's border: the xy gap is air between the part and the beads.
  geo::Rings inner = toolpath::offset(ip.shape, -0.5 * w);
  if (inner.empty()) return ok_status();
  const double s = toolpath::bead_spacing_mm(w, height_mm);
  if (wall) {  // a branch's wall, then its inside
    for (const geo::Ring& r : inner) {
      PathPlan p;
      p.kind = kind;
      p.perimeter = 0;
      p.closed = true;
      p.width = static_cast<float>(w);
      p.pts = r;
      p.props = *props;
      p.trace = nest.path_log(log);
      ip.paths.push_back(std::move(p));
    }
    inner = toolpath::offset(inner, -s);
    if (inner.empty()) return ok_status();
  }
  std::vector<double> angles{iface ? 90.0 : 0.0};
  double pitch = s / density;
  if (!iface && P[PropId::SupportPattern] == static_cast<double>(schema::SupportPattern::Grid)) {
    angles.push_back(90.0);  // both ways in every layer, each way at half the density
    pitch *= 2;
  }
  for (double angle : angles) {
    toolpath::FillSpec fs;
    fs.angle_deg = angle;
    fs.pitch_mm = pitch;
    fs.origin_mm = 0;  // a grid fixed to the bed: lines stand on the lines below
    fs.link_max_mm = 5 * pitch;
    for (toolpath::FillPath& fp : toolpath::zigzag(toolpath::fill_shape(inner, geo::EdgeKind::Real), fs)) {
      CellPlan cell;
      cell.index = static_cast<int>(ip.cells.size());
      cell.area_mm2 = fp.area_mm2;
      cell.fill_angle_deg = angle;
      cell.solid = iface;
      ip.cells.push_back(cell);
      PathPlan p;
      p.kind = kind;
      p.cell = cell.index;
      p.width = static_cast<float>(w);
      p.pts = std::move(fp.pts);
      p.border = std::move(fp.border);
      p.props = *props;
      p.trace = nest.path_log(log);
      ip.paths.push_back(std::move(p));
    }
  }
  regions.push_back({kind, EdgeGrid(inner)});
  return ok_status();
}

Status build_skirt(LayerPlan& plan, Nest& nest, double height_mm) {
  const auto& S = nest.setup();
  const int loops = S.skirt_around.empty() ? 0 : static_cast<int>(S.print_props[PropId::SkirtLoops]);
  if (loops <= 0 && S.brim.empty()) return ok_status();
  nest.ctx().clear_from(schema::Level::Island);
  TraceRef log;
  auto props = nest.path_props(plan.props, PathKind::Skirt, -1, &log);
  if (!props) return props.error();
  const double w = (*props)[PropId::Width];
  const double s = toolpath::bead_spacing_mm(w, height_mm);
  const double d0 = S.print_props[PropId::SkirtDistance] + 0.5 * w;
  for (int k = loops - 1; k >= 0; --k) {  // outermost first: the skirt ends next to the part
    for (auto& r : toolpath::offset(S.skirt_around, d0 + k * s)) {
      if (!ClipperLib::Orientation(r)) continue;
      PathPlan p;
      p.kind = PathKind::Skirt;
      p.closed = true;
      p.width = static_cast<float>(w);
      p.pts = std::move(r);
      p.props = *props;
      p.trace = nest.path_log(log);
      plan.skirt.push_back(std::move(p));
    }
  }
  if (S.brim.empty()) return ok_status();
  TraceRef brim_log;
  auto brim = nest.path_props(plan.props, PathKind::Brim, -1, &brim_log);
  if (!brim) return brim.error();
  for (const auto& b : S.brim) {
    PathPlan p;
    p.kind = PathKind::Brim;
    p.closed = b.closed;
    p.width = static_cast<float>((*brim)[PropId::Width]);
    p.pts = b.pts;
    p.props = *brim;
    p.trace = nest.path_log(brim_log);
    plan.skirt.push_back(std::move(p));
  }
  return ok_status();
}

}  // namespace tranche::plan
