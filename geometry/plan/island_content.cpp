#include "geometry/plan/island_content.h"

#include <algorithm>
#include <cmath>

#include "geometry/toolpath/cells.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/flow.h"
#include "geometry/toolpath/infill_patterns.h"
#include "geometry/toolpath/island_shape.h"
#include "geometry/toolpath/overhang_walls.h"
#include "geometry/toolpath/perimeters.h"
#include "geometry/toolpath/zigzag.h"

namespace tranche::plan {

using ctx::PropertyValues;
using schema::PathKind;
using schema::PropId;
using toolpath::EdgeGrid;
using toolpath::FillRegion;

IslandNeeds IslandNeeds::of(const Nest& nest) {
  using schema::FieldId;
  IslandNeeds n;
  n.relations = nest.reads(FieldId::IslandSupported) || nest.reads(FieldId::IslandCovered);
  n.edge_angle = nest.reads(FieldId::IslandLongestEdgeAngle);
  n.min_width = nest.reads(FieldId::IslandMinWidth);
  n.convex = nest.reads(FieldId::IslandConvex);
  n.below = nest.reads(FieldId::IslandBelowArea) || nest.reads(FieldId::IslandBelowSupported);
  return n;
}

namespace {

// island.below_area and island.below_supported: the island of the layer below that overlaps
// this one most, and how much of it lies on the layer under it (all of it on the first layer).
void measure_below(IslandPlan& ip, toolpath::Neighbours& nb) {
  ip.below_area = ip.below_supported = 0;
  const geo::Layer* below = nb.at(-1);
  if (!below) return;
  const int i = toolpath::island_under(ip.shape, *below);
  if (i < 0) return;
  const geo::Polygon& p = below->islands[static_cast<size_t>(i)].shape;
  geo::Rings rings{p.outer};
  rings.insert(rings.end(), p.holes.begin(), p.holes.end());
  ip.below_area = toolpath::area_mm2(rings);
  ip.below_supported = nb.index() == 1 ? 1.0 : toolpath::fraction_on(rings, nb.layer(-2));
}

}  // namespace

void measure_island(IslandPlan& ip, const geo::Point& shift, toolpath::Neighbours& nb, const IslandNeeds& needs) {
  // Sizes as the outer wall follows the outline (at the print's resolution).
  const geo::Rings& outline = ip.outline();
  ip.area = toolpath::area_mm2(outline);
  ip.border_length = 0;
  ip.holes = 0;
  for (const auto& r : outline) {
    ip.border_length += geo::length_mm(r);
    if (!ClipperLib::Orientation(r)) ++ip.holes;
  }
  geo::BBox2 b = toolpath::bbox(outline);
  if (!b.empty()) {
    ip.size_x = geo::to_mm(b.max_x - b.min_x);
    ip.size_y = geo::to_mm(b.max_y - b.min_y);
    ip.center_x = geo::to_mm((b.min_x + b.max_x) / 2 + shift.X);
    ip.center_y = geo::to_mm((b.min_y + b.max_y) / 2 + shift.Y);
  }
  if (needs.relations) {
    ip.supported = nb.index() == 0 ? 1.0 : toolpath::fraction_on(ip.shape, nb.layer(-1));
    ip.covered = toolpath::fraction_on(ip.shape, nb.layer(1));
  }
  if (needs.edge_angle) ip.longest_edge_angle = toolpath::longest_edge_angle_deg(ip.shape);
  if (needs.min_width) ip.min_width = toolpath::min_width_mm(ip.shape);
  if (needs.convex) ip.convex = toolpath::is_convex(ip.shape);
  if (needs.below) measure_below(ip, nb);
}

namespace {

// A new cell of the island for the fill path `fp` (its index, area, angle), returned.
CellPlan& add_cell(IslandPlan& ip, const toolpath::FillPath& fp, double angle, bool solid) {
  CellPlan cell;
  cell.index = static_cast<int>(ip.cells.size());
  cell.area_mm2 = fp.area_mm2;
  cell.fill_angle_deg = angle;
  cell.solid = solid;
  ip.cells.push_back(cell);
  return ip.cells.back();
}

// What the paths of one fill region share.
struct RegionFill {
  const FillRegion& region;
  const std::vector<const EdgeGrid*>& borders;
  bool solid;
  double w, s;  // bead width and spacing (mm)
  toolpath::FillSpec fs;
  double flow_scale = 1.0;
  PropertyValues props;
  TraceRef log;
};

// The spec of a fill at `angle` over `rings`: sparse lines on the bed's grid; solid ones border
// to border of `rings` (the whole region, or a cell filled again), shared by its cells.
void fill_spec(RegionFill& f, const geo::Rings& rings, double angle, double density) {
  f.fs.angle_deg = angle;
  f.fs.pitch_mm = f.s / std::min(density, 1.0);
  f.fs.artificial_inset_mm = 0.5 * f.s;
  f.flow_scale = 1.0;
  if (f.solid) {
    toolpath::SolidGrid g = toolpath::region_grid(toolpath::across_range(rings, angle), f.s);
    f.fs.origin_mm = g.origin_mm;
    f.fs.pitch_mm = g.pitch_mm;
    f.flow_scale = std::clamp(g.ratio, 0.6, 1.4);
  }
  // Zig-zags that cannot continue one another are joined by a walk along the border of at most
  // five line pitches (sparse: 11 mm at 20 %, about PrusaSlicer's 12 mm infill anchors) or 16
  // beads (solid: 6.7 mm, half the way round a 4 mm hole). On the Stanford bunny, solid links of
  // 2 / 8 / 16 beads leave 5192 / 4529 / 4228 trips.
  f.fs.link_max_mm = f.solid ? 16 * f.s : 5 * f.fs.pitch_mm;
}

void add_cell_path(IslandPlan& ip, Nest& nest, const RegionFill& f, const CellPlan& cell, toolpath::FillPath& fp,
                   double flow_scale) {
  PathPlan p;
  p.kind = f.region.kind;
  p.cell = cell.index;
  p.width = static_cast<float>(f.w);
  p.flow_scale = static_cast<float>(flow_scale);
  if (f.solid) p.border_flow = 0.5f;
  p.pts = std::move(fp.pts);
  p.border = std::move(fp.border);
  p.props = f.props;
  p.props[PropId::FillAngle] = cell.fill_angle_deg;
  p.trace = nest.path_log(f.log);
  ip.paths.push_back(std::move(p));
}

// Whether `pt` lies in `rings` (non-zero fill; on an edge counts as in).
bool contains(const geo::Rings& rings, const geo::Point& pt) {
  int winding = 0;
  for (const auto& r : rings) {
    const int in = ClipperLib::PointInPolygon(pt, r);
    if (in != 0) winding += ClipperLib::Orientation(r) ? 1 : -1;
  }
  return winding > 0;
}

// The cells (of one region) whose angle the cell stage decided to be `angle`, filled again
// together over the union of their parts of the region, so that their zig-zags run on across
// the cuts between them. A cell's part is its core grown by a pitch and clipped to the region
// (so that it reaches the region's border between its line ends), less the other cells' cores
// grown by half a bead (up to the cuts their line ends stopped short of). Each new path belongs
// to the cell its first piece starts in.
void refill(IslandPlan& ip, Nest& nest, const RegionFill& f, std::vector<toolpath::FillPath>& fps, size_t first,
            const std::vector<size_t>& members, double angle, double density) {
  geo::Rings others;
  for (size_t j = 0; j < fps.size(); ++j)
    if (std::find(members.begin(), members.end(), j) == members.end())
      others = toolpath::union_of(others, toolpath::cell_core(fps[j], f.fs.angle_deg, f.fs.pitch_mm));
  others = toolpath::offset(others, f.fs.artificial_inset_mm);
  std::vector<geo::Rings> parts;
  geo::Rings rings;
  for (size_t i : members) {
    geo::Rings core = toolpath::cell_core(fps[i], f.fs.angle_deg, f.fs.pitch_mm);
    parts.push_back(toolpath::difference(
        toolpath::intersection(toolpath::offset(core, f.fs.pitch_mm), f.region.rings), others));
    rings = toolpath::union_of(rings, parts.back());
    ip.cells[first + i].fill_angle_deg = angle;
  }
  RegionFill again{f.region, f.borders, f.solid, f.w, f.s, {}, 1.0, f.props, f.log};
  fill_spec(again, rings, angle, density);
  for (toolpath::FillPath& q : toolpath::zigzag(toolpath::region_shape(rings, f.borders, 0.25 * f.w), again.fs)) {
    size_t owner = 0;
    if (q.pts.size() >= 2) {
      const geo::Point mid((q.pts[0].X + q.pts[1].X) / 2, (q.pts[0].Y + q.pts[1].Y) / 2);
      for (size_t k = 0; k < parts.size(); ++k)
        if (contains(parts[k], mid)) {
          owner = k;
          break;
        }
    }
    add_cell_path(ip, nest, again, ip.cells[first + members[owner]], q, again.flow_scale);
  }
}

// The cell stage: rules reading `cell.*` may give cells fill angles of their own; the cells
// given one angle are filled again at it (refill), the others keep their zig-zag.
Status place_cells(IslandPlan& ip, Nest& nest, const RegionFill& f, std::vector<toolpath::FillPath>& fps,
                   size_t first, double density) {
  const double island = f.fs.angle_deg;
  std::vector<double> angles(fps.size(), island);
  if (nest.cell_angles())
    for (size_t i = 0; i < fps.size(); ++i) {
      nest.enter_cell(ip.cells[first + i]);
      PropertyValues props = ip.props;
      TraceRef unused;
      if (Status st = nest.decide(schema::Stage::Cell, props, unused); !st) return st;
      angles[i] = props[PropId::FillAngle];
    }
  auto same = [](double a, double b) { return std::abs(a - b) <= 1e-9; };
  std::vector<bool> done(fps.size(), false);
  for (size_t i = 0; i < fps.size(); ++i) {
    if (done[i]) continue;
    if (same(angles[i], island)) {
      add_cell_path(ip, nest, f, ip.cells[first + i], fps[i], f.flow_scale);
      continue;
    }
    std::vector<size_t> members;
    for (size_t j = i; j < fps.size(); ++j)
      if (!done[j] && same(angles[j], angles[i])) {
        members.push_back(j);
        done[j] = true;
      }
    refill(ip, nest, f, fps, first, members, angles[i], density);
  }
  return ok_status();
}

// A sparse region filled with a pattern other than the zig-zag (geometry/toolpath/infill_patterns):
// each path is a cell of its own, at the island's angle (the cell stage does not turn them).
// Lightning's branches (geometry/toolpath/lightning.h) are grown for all layers at once, at the
// first request, and shared through the setup: every point of a top held within width / density
// of a leaf (PrusaSlicer's supporting radius: its infill's width × 100 / density %; Cura's is
// half that, but its trees, grown from the edge of the held area, come out about that much
// closer than lines), in the material less the island's walls (perimeters × the fill's spacing:
// a little less than the walls, so that the roots, clipped to the region, end on them).
void build_pattern(IslandPlan& ip, Nest& nest, const RegionFill& f, schema::InfillPattern pattern,
                   toolpath::Neighbours& nb, double angle, double density) {
  std::vector<toolpath::FillPath> fps;
  toolpath::PatternSpec ps;
  ps.pattern = pattern;
  ps.angle_deg = angle;
  ps.spacing_mm = f.s;
  ps.density = density;
  const geo::Layer* layer = nb.at(0);
  ps.z_mm = layer ? layer->z_slice() : 0.0;
  ps.artificial_inset_mm = f.fs.artificial_inset_mm;
  ps.link_max_mm = f.fs.link_max_mm;
  // Gyroid: joined and anchored along the border as PrusaSlicer's gyroid is by default (links up
  // to infill_anchor_max = 50 mm, free ends anchored by infill_anchor = 600 % of the width: 2.7
  // mm at 0.45), so that it lays what PrusaSlicer's does at the same density (on a plate with
  // holes, whose lines end at every hole, the links and anchors are a third of the infill).
  if (pattern == schema::InfillPattern::Gyroid) {
    ps.link_max_mm = std::max(ps.link_max_mm, 50.0);
    ps.anchor_mm = 6 * f.w;
  }
  const toolpath::FillShape shape = toolpath::region_shape(f.region.rings, f.borders, 0.25 * f.w);
  if (pattern == schema::InfillPattern::Lightning) {
    toolpath::LightningSpec ls;
    ls.top_layers = static_cast<int>(ip.props[PropId::TopLayers]);
    ls.radius_mm = f.w / density;
    ls.inset_mm = std::max(ip.props[PropId::Perimeters], 0.0) * f.s;
    ls.angle_deg = toolpath::LightningCache::kAngleDeg;
    fps = toolpath::clip_fill_lines(nest.setup().lightning.lines(nest.setup().layers, nb.index(), ls), shape, ps);
  } else {
    fps = toolpath::pattern_fill(shape, ps);
  }
  for (toolpath::FillPath& fp : fps) add_cell_path(ip, nest, f, add_cell(ip, fp, angle, false), fp, 1.0);
}

// One fill region's cells: a zig-zag per cell, on the region's grid of lines at `angle` (or the
// island's infill_pattern, for a sparse region).
Status build_cells(IslandPlan& ip, Nest& nest, const FillRegion& region, const std::vector<const EdgeGrid*>& borders,
                   double angle, double height_mm, toolpath::Neighbours& nb) {
  const bool solid = region.kind != PathKind::Infill;
  TraceRef log;
  auto props = nest.path_props(ip.props, region.kind, -1, &log);
  if (!props) return props.error();
  const double w = (*props)[PropId::Width];
  const double density = solid ? 1.0 : (*props)[PropId::InfillDensity];
  if (density <= 0) return ok_status();
  RegionFill f{region, borders, solid, w, toolpath::bead_spacing_mm(w, height_mm), {}, 1.0, *props, log};
  fill_spec(f, region.rings, angle, density);
  const auto pattern = static_cast<schema::InfillPattern>(static_cast<int>((*props)[PropId::InfillPattern]));
  if (!solid && pattern != schema::InfillPattern::Zigzag && density < 1) {
    build_pattern(ip, nest, f, pattern, nb, angle, density);
    return ok_status();
  }
  // Each zig-zag is a cell: a monotone piece of the region at the resolution of its lines.
  // Edges within a quarter bead of the island's fill border are on it (see region_shape).
  std::vector<toolpath::FillPath> fps = toolpath::zigzag(toolpath::region_shape(region.rings, borders, 0.25 * w), f.fs);
  const size_t first = ip.cells.size();
  for (const toolpath::FillPath& fp : fps) add_cell(ip, fp, angle, solid);
  return place_cells(ip, nest, f, fps, first, density);
}

// Ironing: zig-zags at ironing_spacing over the island's top surfaces (its top solid regions,
// less half a bead along their border), across the top's lines. Each line lays flow × the
// layer's height × the spacing of plastic per mm (PrusaSlicer's measure: at 100% a whole
// layer over the surface), so `flow` (15% by default for this kind) fills the valleys between
// the top's beads. Paths of kind ironing, which the print order puts after the walls and fill.
Status add_ironing(IslandPlan& ip, Nest& nest, const std::vector<FillRegion>& fill, double height_mm) {
  geo::Rings top;
  for (const FillRegion& region : fill)
    if (region.kind == PathKind::TopSolid) top = toolpath::union_of(top, region.rings);
  if (top.empty()) return ok_status();
  TraceRef log;
  auto props = nest.path_props(ip.props, PathKind::Ironing, -1, &log);
  if (!props) return props.error();
  const double w = (*props)[PropId::Width];
  const double spacing = ip.props[PropId::IroningSpacing];
  top = toolpath::offset(top, -0.5 * w);
  if (top.empty()) return ok_status();
  toolpath::FillSpec fs;
  fs.angle_deg = ip.props[PropId::FillAngle] + 90;
  fs.pitch_mm = spacing;
  fs.artificial_inset_mm = 0;
  fs.link_max_mm = 5 * w;
  const double scale = height_mm * spacing / toolpath::bead_area_mm2(w, height_mm);
  for (toolpath::FillPath& fp : toolpath::zigzag(toolpath::fill_shape(top, geo::EdgeKind::Real), fs)) {
    PathPlan p;
    p.kind = PathKind::Ironing;
    p.width = static_cast<float>(w);
    p.flow_scale = static_cast<float>(scale);
    p.pts = std::move(fp.pts);
    p.border = std::move(fp.border);
    p.props = *props;
    p.props[PropId::FillAngle] = fs.angle_deg;
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
  spec.mode = static_cast<schema::WallGenerator>(static_cast<int>(P[PropId::WallGenerator])) ==
                      schema::WallGenerator::Variable
                  ? toolpath::WallMode::Variable
                  : toolpath::WallMode::Classic;
  spec.min_bead_width = P[PropId::MinBeadWidth];
  spec.max_bead_width = std::max(P[PropId::MaxBeadWidth], spec.min_bead_width);
  toolpath::Perimeters per = toolpath::make_perimeters(ip.shape, spec, &ip.outline());
  // overhang_walls = bridge: where the wall band lies over air a bead wide or more, that part of
  // the island is a bridge (geometry/toolpath/overhang_walls.h); walls stay where they rest on
  // the layer below. Not on the first layer (the bed holds it), nor where support holds it up.
  toolpath::OverhangWallSplit over;
  geo::Rings border_region;
  if (nb.index() > 0 && !spec.widths.empty() &&
      static_cast<schema::OverhangWalls>(static_cast<int>(P[PropId::OverhangWalls])) == schema::OverhangWalls::Bridge &&
      static_cast<schema::Support>(static_cast<int>(P[PropId::Support])) == schema::Support::None) {
    double band = 0.5 * (spec.widths.front() + spec.widths.back());
    for (size_t k = 1; k < spec.widths.size(); ++k)
      band += toolpath::bead_spacing_mm(spec.widths[k - 1], spec.widths[k], height_mm);
    over = toolpath::split_overhang_walls(ip.shape, nb.layer(-1), band, spec.widths.front());
  }
  if (!over.empty()) {
    const EdgeGrid bridge_grid(over.bridge);
    std::vector<toolpath::Loop> whole;  // loops the bridge does not touch stay loops
    for (auto& loop : per.loops) {
      bool touched = !loop.ring.empty() && bridge_grid.inside(loop.ring.front());
      for (size_t i = 0; i < loop.ring.size() && !touched; ++i)
        touched = bridge_grid.crosses(loop.ring[i], loop.ring[(i + 1) % loop.ring.size()]);
      if (!touched) {
        whole.push_back(std::move(loop));
        continue;
      }
      for (geo::Ring& piece : toolpath::loops_outside({loop.ring}, over.bridge, spec.widths.front())) {
        PathPlan p;
        p.kind = loop.depth == 0 ? PathKind::OuterPerimeter : PathKind::InnerPerimeter;
        p.perimeter = loop.depth;
        p.width = static_cast<float>(spec.widths[static_cast<size_t>(loop.depth)]);
        p.pts = std::move(piece);
        p.border.assign(p.piece_count(), schema::Border::Real);
        p.props = loop_props[static_cast<size_t>(loop.depth)];
        p.trace = nest.path_log(loop_logs[static_cast<size_t>(loop.depth)]);
        ip.paths.push_back(std::move(p));
      }
    }
    per.loops = std::move(whole);
    // Gap fill inside the bridge region would lie on its lines.
    std::erase_if(per.beads, [&](const toolpath::VarBead& b) {
      return std::any_of(b.pts.begin(), b.pts.end(), [&](const geo::Point& q) { return bridge_grid.inside(q); });
    });
    border_region = per.fill_region;  // the cut along the bridge is no border: lines stop short of it
    per.fill_region = toolpath::difference(per.fill_region, over.bridge);
  }
  for (auto& loop : per.loops) {
    PathPlan p;
    p.kind = loop.depth == 0 ? PathKind::OuterPerimeter : PathKind::InnerPerimeter;
    p.perimeter = loop.depth;
    p.closed = true;
    p.width = static_cast<float>(spec.widths[static_cast<size_t>(loop.depth)]);
    p.pts = std::move(loop.ring);
    p.props = loop_props[static_cast<size_t>(loop.depth)];
    p.trace = nest.path_log(loop_logs[static_cast<size_t>(loop.depth)]);
    ip.paths.push_back(std::move(p));
  }
  if (!per.beads.empty()) {
    // Gap fill and thin walls: one open path per bead, each piece with its own width (the
    // `width` decided for the path is not used: the gap gives it).
    TraceRef log;
    auto props = nest.path_props(P, PathKind::GapFill, -1, &log);
    if (!props) return props.error();
    for (auto& b : per.beads) {
      PathPlan p;
      p.kind = PathKind::GapFill;
      p.width = static_cast<float>(b.mean_width());
      p.pts = std::move(b.pts);
      p.widths = std::move(b.widths);
      p.border.assign(p.piece_count(), schema::Border::None);
      p.props = *props;
      p.props[PropId::Width] = p.width;
      p.trace = nest.path_log(log);
      ip.paths.push_back(std::move(p));
    }
  }
  if (!over.empty()) {
    // The bridge: its lines' centres stay half an outer bead inside the outline, where they end
    // on it; where the region meets the walls and the fill kept on the layer below, they stop
    // half a spacing short (an artificial border).
    const geo::Rings inside = toolpath::offset(ip.outline(), -0.5 * spec.widths.front());
    FillRegion region{PathKind::Bridge, toolpath::intersection(over.bridge, inside)};
    if (!region.rings.empty()) {
      const EdgeGrid outline(inside);
      if (Status s = build_cells(ip, nest, region, {&outline}, over.angle_deg, height_mm, nb); !s) return s;
      regions.push_back({region.kind, EdgeGrid(region.rings)});
    }
  }
  if (per.fill_region.empty()) return ok_status();
  toolpath::SolidSpec ss;
  ss.top_layers = static_cast<int>(P[PropId::TopLayers]);
  ss.bottom_layers = static_cast<int>(P[PropId::BottomLayers]);
  ss.density = P[PropId::InfillDensity];
  ss.width = spec.fill_width;
  if (P[PropId::VerticalShell] != 0 && !spec.widths.empty()) {
    // Half the perimeters' band (the innermost loop's centreline distance plus half its
    // spacing). Measured on PrusaSlicer's torus (bench_quality.sh): the whole band gives 1.19×
    // PrusaSlicer's plastic, half of it 0.99× (without: 0.90×), coverage and overlap unchanged.
    double band = 0.5 * spec.widths[0];
    for (size_t k = 1; k < spec.widths.size(); ++k)
      band += toolpath::bead_spacing_mm(spec.widths[k - 1], spec.widths[k], height_mm);
    ss.shell_mm = 0.5 * (band + 0.5 * toolpath::bead_spacing_mm(spec.widths.back(), height_mm));
  }
  const double angle = P[PropId::FillAngle];
  auto fill = toolpath::split_fill(per.fill_region, nb, ss);
  // Solid zig-zags leave small notches between line ends on the side without a connector; their
  // regions reach a further quarter bead into the perimeters so that the beads cover those.
  const double reach = 0.25 * spec.fill_width;
  geo::Rings wide;
  for (auto& region : fill) {
    if (region.kind == PathKind::Infill) continue;
    if (wide.empty()) wide = toolpath::offset(border_region.empty() ? per.fill_region : border_region, reach);
    region.rings = toolpath::intersection(toolpath::offset(region.rings, reach), wide);
  }
  // The island's fill border: where sparse regions meet the perimeters, and (grown) where solid
  // ones do.
  EdgeGrid fill_grid(border_region.empty() ? per.fill_region : border_region), wide_grid(wide);
  std::vector<const EdgeGrid*> borders{&fill_grid};
  if (!wide.empty()) borders.push_back(&wide_grid);
  for (const FillRegion& region : fill) {
    if (Status s = build_cells(ip, nest, region, borders, angle, height_mm, nb); !s) return s;
    regions.push_back({region.kind, EdgeGrid(region.rings)});
  }
  if (P[PropId::Ironing] != 0)
    if (Status s = add_ironing(ip, nest, fill, height_mm); !s) return s;
  return ok_status();
}

Status build_support(IslandPlan& ip, Nest& nest, double height_mm, PathKind kind, bool wall,
                     std::vector<FillGrid>& regions) {
  ip.paths.clear();
  ip.cells.clear();
  ip.fill_region.clear();
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
  // (This also removes what is narrower than a bead: support::project leaves it in.)
  geo::Rings inner = toolpath::offset_coarse(ip.shape, -0.5 * w);
  if (inner.empty()) return ok_status();
  ip.fill_region = inner;  // travels follow it (plan/travel)
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
    inner = toolpath::offset_coarse(inner, -s);
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
      const int cell = add_cell(ip, fp, angle, iface).index;
      PathPlan p;
      p.kind = kind;
      p.cell = cell;
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
