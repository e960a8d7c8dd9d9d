#include "geometry/toolpath/layer_loop.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/toolpath/cells.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/comb.h"
#include "geometry/toolpath/context_fill.h"
#include "geometry/toolpath/edge_grid.h"
#include "geometry/toolpath/flow.h"
#include "geometry/toolpath/order.h"
#include "geometry/toolpath/perimeters.h"
#include "geometry/toolpath/relations.h"
#include "geometry/toolpath/walk.h"
#include "geometry/toolpath/zigzag.h"

namespace tranche::toolpath {
namespace {

using ctx::PropertyValues;
using schema::Border;
using schema::FieldId;
using schema::Level;
using schema::PathKind;
using schema::PropId;
using schema::Stage;

constexpr double kNoAngle = std::numeric_limits<double>::quiet_NaN();

class LayerTask;

// `replace island { ... }`: offsets the island's shape, emits moves and text, and the default.
class IslandReplace final : public ctx::ReplaceApi {
 public:
  IslandReplace(LayerTask& t, IslandPlan& ip) : t_(t), ip_(ip) {}
  void move_to(double x, double y, const ctx::MoveOptions& o) override;
  void gcode(std::string_view line) override {
    ip_.ops.push_back({Op::Kind::Text, {}, 0, 1, 0, std::string(line)});
  }
  void comment(std::string_view text) override { gcode(fmt::format("; {}", text)); }
  Status emit_default() override;
  Status offset(double mm) override;
  Status reverse() override { return Error{"replace island", "reverse applies to paths, not islands"}; }
  void retract() override { ip_.ops.push_back({Op::Kind::Retract, {}, 0, 1, 0, {}}); }
  Status status = ok_status();

 private:
  LayerTask& t_;
  IslandPlan& ip_;
  bool altered_ = false, built_ = false;
};

// `replace path { ... }`.
class PathReplace final : public ctx::ReplaceApi {
 public:
  PathReplace(LayerTask& t, IslandPlan* ip, PathPlan& p) : t_(t), ip_(ip), p_(p) {}
  void move_to(double x, double y, const ctx::MoveOptions& o) override;
  void gcode(std::string_view line) override {
    p_.ops.push_back({Op::Kind::Text, {}, 0, 1, 0, std::string(line)});
  }
  void comment(std::string_view text) override { gcode(fmt::format("; {}", text)); }
  Status emit_default() override {
    p_.ops.push_back({Op::Kind::Default, {}, 0, 1, 0, {}});
    return ok_status();
  }
  Status offset(double mm) override;
  Status reverse() override;
  void retract() override { p_.ops.push_back({Op::Kind::Retract, {}, 0, 1, 0, {}}); }

 private:
  LayerTask& t_;
  IslandPlan* ip_;
  PathPlan& p_;
};

class LayerTask {
 public:
  LayerTask(const PrintSetup& s, int index, Report& report)
      : S(s), L(index), report_(report), ctx_(s.print_ctx), nb_(s.layers, index) {
    const auto* d = s.rules.decider;
    const auto* b = s.rules.defaults;
    auto varies = [&](Stage st) {
      Level l = Level::Print;
      if (d) l = std::max(l, d->varies_at(st));
      if (b) l = std::max(l, b->varies_at(st));
      return l;
    };
    per_piece_ = varies(Stage::Piece) == Level::Piece;
    cooling_at_ = varies(Stage::Cooling);
    has_exec_ = s.rules.executors != nullptr;
    has_repl_path_ = s.rules.replacers && s.rules.replacers->has(Level::Path);
    has_repl_island_ = s.rules.replacers && s.rules.replacers->has(Level::Island);
    auto reads = [&](FieldId f) {
      return (d && d->reads(f)) || (b && b->reads(f)) || (has_exec_ && s.rules.executors->reads(f)) ||
             (s.rules.replacers && s.rules.replacers->reads(f));
    };
    need_support_ = reads(FieldId::IslandSupported) || reads(FieldId::IslandCovered);
    need_overhang_ = reads(FieldId::PieceOverhang);
    height_ = s.layers[static_cast<size_t>(index)].height();
    filament_ = s.print_props[PropId::FilamentDiameter];
  }

  Result<LayerPlan> run() {
    if (Status st = layer_level(); !st) return st.error();
    return std::move(plan_);
  }

  // Used by the replacer APIs.
  Status decide(Stage st, PropertyValues& props, double script_angle = kNoAngle) {
    ctx_.set_props(&props);
    if (S.rules.defaults) {
      if (Status s = S.rules.defaults->decide(st, ctx_, props); !s) return s;
    }
    if (st == Stage::Island && !std::isnan(script_angle)) props[PropId::FillAngle] = script_angle;
    if (S.rules.decider) {
      if (Status s = S.rules.decider->decide(st, ctx_, props); !s) return s;
    }
    return ok_status();
  }
  Status island_decide(IslandPlan& ip) {
    ctx_.clear_from(Level::Island);
    island_fields(ip);
    set_island_fields(ctx_, ip);
    ip.props = plan_.props;
    return decide(Stage::Island, ip.props, script_angle_);
  }
  Status island_content(IslandPlan& ip);
  // Speed, flow and width a replacer's `move to` uses in this context (path kind `custom`
  // for island replacers).
  Result<Op> custom_move(const PropertyValues& base, bool in_path) {
    PropertyValues p = base;
    if (!in_path) {
      ctx_.clear_from(Level::Cell);
      ctx_.set(FieldId::PathKind, static_cast<double>(PathKind::Custom));
      ctx_.set(FieldId::PathPerimeter, -1);
      if (Status s = decide(Stage::PathPlan, p); !s) return s.error();
    }
    if (Status s = decide(Stage::Piece, p); !s) return s.error();
    Op op;
    op.speed = static_cast<float>(p[PropId::Speed]);
    op.flow = static_cast<float>(p[PropId::Flow]);
    op.width = static_cast<float>(p[PropId::Width]);
    return op;
  }
  geo::Point to_model(double x_mm, double y_mm) const {
    return geo::Point(geo::to_units(x_mm) - S.shift.X, geo::to_units(y_mm) - S.shift.Y);
  }
  void island_fields(IslandPlan& ip);
  // A replacer altered the path: the rest of it reads the new shape (a new path generation).
  void path_altered(PathPlan& p) {
    ctx_.clear_from(Level::Path);
    set_path_fields(ctx_, p);
    path_view_.bind(ctx_, p, S.shift);
  }

 private:
  Status layer_level();
  Status skirt_level();
  Status island_level(const geo::Island& src, int index, IslandPlan& ip);
  Status cell_level(IslandPlan& ip, const FillRegion& region, const std::vector<const EdgeGrid*>& borders,
                    double angle);
  void order(IslandPlan& ip, geo::Point& pos);
  Status path_level(IslandPlan* ip, PathPlan& p);
  Status piece_level(PathPlan& p);
  void travel_and_retract();
  void time_and_slowdown();
  Status cooling_level();
  Result<PropertyValues> plan_path_props(const PropertyValues& island_props, PathKind kind, int perimeter) {
    ctx_.clear_from(Level::Cell);
    ctx_.set(FieldId::PathKind, static_cast<double>(kind));
    ctx_.set(FieldId::PathPerimeter, perimeter);
    PropertyValues p = island_props;
    if (Status s = decide(Stage::PathPlan, p); !s) return s.error();
    return p;
  }
  std::string where() const { return fmt::format("layer {}", L); }

  const PrintSetup& S;
  int L;
  Report& report_;
  ctx::Context ctx_;
  Neighbours nb_;
  LayerPlan plan_;
  PathView path_view_;
  IslandsView islands_view_;
  double height_ = 0.2, filament_ = 1.75;
  double script_angle_ = kNoAngle;
  bool per_piece_ = false, has_exec_ = false, has_repl_path_ = false, has_repl_island_ = false;
  bool need_support_ = false, need_overhang_ = false;  // costly fields, computed only when read
  Level cooling_at_ = Level::Layer;
  // Per island (by index): each fill region's edges, to join zig-zags without leaving it.
  std::vector<std::vector<std::pair<PathKind, EdgeGrid>>> region_grids_;
};

Status LayerTask::layer_level() {
  const geo::Layer& layer = S.layers[static_cast<size_t>(L)];
  plan_.index = L;
  plan_.z_bottom = layer.z_bottom;
  plan_.z = layer.z_top;
  plan_.height = layer.height();
  for (const auto& isl : layer.islands) plan_.area += geo::area_mm2(isl.shape);
  ctx_.clear_from(Level::Layer);
  set_layer_fields(ctx_, plan_, static_cast<int>(layer.islands.size()));
  plan_.props = S.print_props;
  if (Status s = decide(Stage::Layer, plan_.props); !s) return s;

  plan_.islands.resize(layer.islands.size());
  region_grids_.resize(layer.islands.size());
  for (size_t i = 0; i < layer.islands.size(); ++i)
    if (Status s = island_level(layer.islands[i], static_cast<int>(i), plan_.islands[i]); !s) return s;
  if (L == 0)
    if (Status s = skirt_level(); !s) return s;

  // Print order: skirt, then islands nearest first, starting at the rear of the layer.
  geo::Point pos(0, 0);
  {
    geo::BBox2 all;
    for (const auto& ip : plan_.islands)
      for (const auto& r : ip.shape)
        for (const auto& q : r) all.add(q);
    if (!all.empty()) pos = geo::Point((all.min_x + all.max_x) / 2, all.max_y);
  }
  for (auto& sk : plan_.skirt) {
    size_t seam = choose_seam(sk.pts, schema::Seam::Rear, pos);
    sk.pts = open_loop_at(sk.pts, seam);
    sk.border.assign(sk.piece_count(), Border::None);
    pos = sk.pts.front();
  }
  // Islands nearest first (by bounding box, from the previous island's centre). Odd layers take
  // that order backwards, so that a layer starts on the island where the one below ended: the
  // layer change then stays inside the part. (Layers are planned in parallel: a layer cannot
  // know where the one below ended, but both find the same order when their islands match.)
  std::vector<size_t> seq;
  {
    std::vector<char> used(plan_.islands.size(), 0);
    std::vector<geo::BBox2> boxes;
    for (const auto& ip : plan_.islands) boxes.push_back(bbox(ip.shape));
    geo::Point at = pos;
    for (size_t step = 0; step < plan_.islands.size(); ++step) {
      double bd = 1e300;
      size_t bi = 0;
      for (size_t i = 0; i < plan_.islands.size(); ++i) {
        if (used[i]) continue;
        const geo::BBox2& b = boxes[i];
        double dx = std::max<double>({0.0, double(b.min_x - at.X), double(at.X - b.max_x)});
        double dy = std::max<double>({0.0, double(b.min_y - at.Y), double(at.Y - b.max_y)});
        double d = b.empty() ? 1e299 : dx * dx + dy * dy;
        if (d < bd) bd = d, bi = i;
      }
      used[bi] = 1;
      seq.push_back(bi);
      const geo::BBox2& b = boxes[bi];
      if (!b.empty()) at = geo::Point((b.min_x + b.max_x) / 2, (b.min_y + b.max_y) / 2);
    }
  }
  if (L % 2 == 1) std::reverse(seq.begin(), seq.end());
  std::vector<IslandPlan> ordered;
  ordered.reserve(plan_.islands.size());
  for (size_t bi : seq) {
    order(plan_.islands[bi], pos);
    ordered.push_back(std::move(plan_.islands[bi]));
  }
  plan_.islands = std::move(ordered);
  if (has_exec_ || has_repl_path_) islands_view_.bind(ctx_, plan_.islands);

  // Path and piece levels, in print order.
  for (auto& sk : plan_.skirt)
    if (Status s = path_level(nullptr, sk); !s) return s;
  for (auto& ip : plan_.islands) {
    ctx_.clear_from(Level::Island);
    set_island_fields(ctx_, ip);
    for (auto& p : ip.paths)
      if (Status s = path_level(&ip, p); !s) return s;
  }
  travel_and_retract();
  time_and_slowdown();
  return cooling_level();
}

Status LayerTask::skirt_level() {
  int loops = static_cast<int>(S.print_props[PropId::SkirtLoops]);
  if (loops <= 0 || S.skirt_around.empty()) return ok_status();
  ctx_.clear_from(Level::Island);
  auto props = plan_path_props(plan_.props, PathKind::Skirt, -1);
  if (!props) return props.error();
  double w = (*props)[PropId::Width];
  double s = bead_spacing_mm(w, height_);
  double d0 = S.print_props[PropId::SkirtDistance] + 0.5 * w;
  for (int k = loops - 1; k >= 0; --k) {  // outermost first: the skirt ends next to the part
    for (auto& r : offset(S.skirt_around, d0 + k * s)) {
      if (!ClipperLib::Orientation(r)) continue;
      PathPlan p;
      p.kind = PathKind::Skirt;
      p.closed = true;
      p.width = static_cast<float>(w);
      p.pts = std::move(r);
      p.props = *props;
      plan_.skirt.push_back(std::move(p));
    }
  }
  return ok_status();
}

void LayerTask::island_fields(IslandPlan& ip) {
  ip.area = area_mm2(ip.shape);
  ip.border_length = 0;
  ip.holes = 0;
  for (const auto& r : ip.shape) {
    ip.border_length += geo::length_mm(r);
    if (!ClipperLib::Orientation(r)) ++ip.holes;
  }
  geo::BBox2 b = bbox(ip.shape);
  if (!b.empty()) {
    ip.size_x = geo::to_mm(b.max_x - b.min_x);
    ip.size_y = geo::to_mm(b.max_y - b.min_y);
    ip.center_x = geo::to_mm((b.min_x + b.max_x) / 2 + S.shift.X);
    ip.center_y = geo::to_mm((b.min_y + b.max_y) / 2 + S.shift.Y);
  }
  if (need_support_) {
    ip.supported = L == 0 ? 1.0 : fraction_on(ip.shape, nb_.layer(-1));
    ip.covered = fraction_on(ip.shape, nb_.layer(1));
  }
}

Status LayerTask::island_level(const geo::Island& src, int index, IslandPlan& ip) {
  ip.index = index;
  geo::Rings rings;
  rings.push_back(src.shape.outer);
  for (const auto& h : src.shape.holes) rings.push_back(h);
  ip.shape = std::move(rings);  // simplified once for all readers (PrintSetup::layers)
  script_angle_ = src.fill_angle_deg;
  if (Status s = island_decide(ip); !s) return s;
  if (has_repl_island_) {
    IslandReplace api(*this, ip);
    auto r = S.rules.replacers->replace(Level::Island, ctx_, api);
    if (!r) return r.error();
    if (!api.status) return api.status;
    if (*r) {
      ip.replaced = true;
      return ok_status();
    }
    ip.ops.clear();
  }
  return island_content(ip);
}

Status LayerTask::island_content(IslandPlan& ip) {
  ip.paths.clear();
  region_grids_[static_cast<size_t>(ip.index)].clear();
  ip.cells.clear();
  const PropertyValues& P = ip.props;
  int count = static_cast<int>(P[PropId::Perimeters]);
  PerimeterSpec spec;
  spec.widths.clear();
  std::vector<PropertyValues> loop_props;
  for (int k = 0; k < count; ++k) {
    auto p = plan_path_props(P, k == 0 ? PathKind::OuterPerimeter : PathKind::InnerPerimeter, k);
    if (!p) return p.error();
    spec.widths.push_back((*p)[PropId::Width]);
    loop_props.push_back(*p);
  }
  auto fill_props = plan_path_props(P, PathKind::Infill, -1);
  if (!fill_props) return fill_props.error();
  spec.fill_width = (*fill_props)[PropId::Width];
  spec.height = height_;
  spec.infill_overlap = P[PropId::InfillOverlap];
  spec.min_feature = P[PropId::NozzleDiameter] / 3;
  Perimeters per = make_perimeters(ip.shape, spec);
  for (auto& loop : per.loops) {
    PathPlan p;
    p.kind = loop.depth == 0 ? PathKind::OuterPerimeter : PathKind::InnerPerimeter;
    p.perimeter = loop.depth;
    p.closed = true;
    p.width = static_cast<float>(spec.widths[static_cast<size_t>(loop.depth)]);
    p.flow_scale = static_cast<float>(loop.flow_scale);
    p.pts = std::move(loop.ring);
    p.props = loop_props[static_cast<size_t>(loop.depth)];
    ip.paths.push_back(std::move(p));
  }
  if (per.fill_region.empty()) return ok_status();
  SolidSpec ss;
  ss.top_layers = static_cast<int>(P[PropId::TopLayers]);
  ss.bottom_layers = static_cast<int>(P[PropId::BottomLayers]);
  ss.density = P[PropId::InfillDensity];
  ss.width = spec.fill_width;
  double angle = P[PropId::FillAngle];
  auto regions = split_fill(per.fill_region, nb_, ss);
  // Solid zig-zags leave small notches between line ends on the side without a connector; their
  // regions reach a further quarter bead into the perimeters so that the beads cover those.
  const double reach = 0.25 * spec.fill_width;
  geo::Rings wide;
  for (auto& region : regions) {
    if (region.kind == PathKind::Infill) continue;
    if (wide.empty()) wide = offset(per.fill_region, reach);
    region.rings = intersection(offset(region.rings, reach), wide);
  }
  // The island's fill border: where sparse regions meet the perimeters, and (grown) where solid
  // ones do.
  EdgeGrid fill_grid(per.fill_region), wide_grid(wide);
  std::vector<const EdgeGrid*> borders{&fill_grid};
  if (!wide.empty()) borders.push_back(&wide_grid);
  for (const FillRegion& region : regions)
    if (Status s = cell_level(ip, region, borders, angle); !s) return s;
  return ok_status();
}

Status LayerTask::cell_level(IslandPlan& ip, const FillRegion& region,
                             const std::vector<const EdgeGrid*>& borders, double angle) {
  const bool solid = region.kind != PathKind::Infill;
  auto props = plan_path_props(ip.props, region.kind, -1);
  if (!props) return props.error();
  double w = (*props)[PropId::Width];
  double s = bead_spacing_mm(w, height_);
  double density = solid ? 1.0 : (*props)[PropId::InfillDensity];
  if (density <= 0) return ok_status();
  FillSpec fs;
  fs.angle_deg = angle;
  fs.pitch_mm = s / std::min(density, 1.0);
  fs.artificial_inset_mm = 0.5 * s;
  double flow_scale = 1.0;
  if (solid) {  // border to border of the whole region, shared by its cells
    SolidGrid g = region_grid(across_range(region.rings, angle), s);
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
  for (FillPath& fp : zigzag(region_shape(region.rings, borders, 0.25 * w), fs)) {
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
    ip.paths.push_back(std::move(p));
  }
  region_grids_[static_cast<size_t>(ip.index)].emplace_back(region.kind, EdgeGrid(region.rings));
  return ok_status();
}

void LayerTask::order(IslandPlan& ip, geo::Point& pos) {
  if (ip.replaced && ip.paths.empty()) return;
  const bool outer_first = ip.props[PropId::OuterFirst] != 0;
  const bool infill_first = ip.props[PropId::InfillFirst] != 0;
  const auto seam = static_cast<schema::Seam>(static_cast<int>(ip.props[PropId::Seam]));
  std::vector<PathPlan> loops, fills, out;
  for (auto& p : ip.paths) (p.closed ? loops : fills).push_back(std::move(p));
  // Loops: by depth (innermost first unless outer_first), nearest seam first within a depth.
  std::stable_sort(loops.begin(), loops.end(), [&](const PathPlan& a, const PathPlan& b) {
    return outer_first ? a.perimeter < b.perimeter : a.perimeter > b.perimeter;
  });
  const int deepest = loops.empty() ? 0 : std::max(loops.front().perimeter, loops.back().perimeter);
  // `link`: the infill was printed just before. The first loop, if it is an innermost one,
  // starts at its point nearest the infill's end (inner seams do not show), and the infill's
  // last path reaches it by a short extrusion instead of a travel.
  auto emit_loops = [&](bool link) {
    for (size_t i = 0; i < loops.size();) {
      size_t j = i;
      while (j < loops.size() && loops[j].perimeter == loops[i].perimeter) ++j;
      std::vector<size_t> seams(j - i);
      for (size_t k = i; k < j; ++k) seams[k - i] = choose_seam(loops[k].pts, seam, pos);
      std::vector<char> used(j - i, 0);
      for (size_t step = i; step < j; ++step) {
        double bd = 1e300;
        size_t bk = i;
        if (link && step == 0 && loops[i].perimeter == deepest) {
          geo::Point at;
          for (size_t k = i; k < j; ++k) {
            auto [d, q] = nearest_on_loop(loops[k].pts, pos);
            if (d < bd) bd = d, bk = k, at = q;
          }
          seams[bk - i] = insert_vertex(loops[bk].pts, at);
          PathPlan& f = out.back();
          double limit = 1.5 * std::max(f.width, loops[bk].width) * geo::kUnitsPerMm;
          if (bd > 0 && bd <= limit * limit && !f.pts.empty() && f.pts.back() == pos) {
            f.pts.push_back(loops[bk].pts[seams[bk - i]]);
            f.border.push_back(Border::Artificial);
          }
        } else {
          for (size_t k = i; k < j; ++k) {
            if (used[k - i]) continue;
            size_t s = seam == schema::Seam::Nearest ? choose_seam(loops[k].pts, seam, pos) : seams[k - i];
            seams[k - i] = s;
            double d = dist2(pos, loops[k].pts[s]);
            if (d < bd) bd = d, bk = k;
          }
        }
        used[bk - i] = 1;
        PathPlan& p = loops[bk];
        p.pts = open_loop_at(p.pts, seams[bk - i]);
        p.border.assign(p.piece_count(), Border::Real);
        pos = p.pts.front();
        out.push_back(std::move(p));
      }
      i = j;
    }
  };
  // Zig-zags (one per cell): the order with the fewest and shortest travels, either end may
  // start. A zig-zag that starts right next to where the previous one of the same region ended
  // is joined to it by a short extrusion (across the gap between their line ends) instead of a
  // travel.
  const auto& grids = region_grids_[static_cast<size_t>(ip.index)];
  auto joinable = [&](const PathPlan& a, const PathPlan& b, const geo::Point& from, const geo::Point& to) {
    if (a.kind != b.kind || a.width != b.width) return false;
    const EdgeGrid* grid = nullptr;
    for (const auto& [kind, g] : grids)
      if (kind == b.kind) grid = &g;
    double s = bead_spacing_mm(b.width, height_);
    double pitch =
        b.kind == PathKind::Infill ? s / std::max(1e-3, std::min(1.0, b.props[PropId::InfillDensity])) : s;
    double limit = std::max(2.5 * s, 1.5 * pitch) * geo::kUnitsPerMm;
    return grid && dist2(from, to) <= limit * limit && !grid->crosses(from, to);
  };
  auto emit_fills = [&](bool before_loops) {
    // A travel costs its length plus this (mm): fewer travels first, then shorter ones.
    constexpr double kTravelMm = 10;
    // Before the loops, the infill should end where the innermost loop will start next to the
    // outer loop's seam, so that the step from one loop to the next is short.
    std::vector<geo::Point> seams_out;
    if (before_loops && seam != schema::Seam::Nearest)
      for (const auto& l : loops)
        if (l.perimeter == 0) seams_out.push_back(l.pts[choose_seam(l.pts, seam, pos)]);
    EndCost end_cost;
    if (!seams_out.empty())
      end_cost = [&](const geo::Point& e) {
        double bd = 1e300;
        for (const auto& q : seams_out) bd = std::min(bd, dist2(e, q));
        return std::sqrt(bd) * geo::kMmPerUnit;
      };
    auto step = [&](size_t i, const geo::Point& a, size_t j, const geo::Point& b) {
      if (i != kStart && joinable(fills[i], fills[j], a, b)) return 0.0;
      return std::sqrt(dist2(a, b)) * geo::kMmPerUnit + kTravelMm;
    };
    std::vector<const geo::Ring*> ends;
    for (const auto& f : fills) ends.push_back(&f.pts);
    const size_t first_fill = out.size();
    for (const Visit& v : chain_open_best(ends, pos, step, 48, end_cost)) {
      PathPlan& p = fills[v.index];
      if (v.reversed) {
        std::reverse(p.pts.begin(), p.pts.end());
        std::reverse(p.border.begin(), p.border.end());
      }
      out.push_back(std::move(p));
    }
    for (size_t i = first_fill + 1; i < out.size(); ++i) {
      PathPlan& prev = out[i - 1];
      PathPlan& p = out[i];
      if (prev.pts.empty() || p.pts.empty()) continue;
      const geo::Point a = prev.pts.back();
      if (!joinable(prev, p, a, p.pts.front())) continue;
      p.pts.insert(p.pts.begin(), a);
      p.border.insert(p.border.begin(), Border::Artificial);
    }
    if (out.size() > first_fill && !out.back().pts.empty()) pos = out.back().pts.back();
  };
  if (infill_first && !fills.empty()) {
    emit_fills(true);
    emit_loops(true);
  } else {
    emit_loops(false);
    emit_fills(false);
  }
  if (!out.empty() && !out.back().pts.empty()) pos = out.back().pts.back();
  for (size_t i = 0; i < out.size(); ++i) out[i].index = static_cast<int>(i);
  ip.paths = std::move(out);
}

Status LayerTask::path_level(IslandPlan* ip, PathPlan& p) {
  ctx_.clear_from(Level::Cell);
  if (ip && p.cell >= 0) set_cell_fields(ctx_, ip->cells[static_cast<size_t>(p.cell)]);
  set_path_fields(ctx_, p);
  if (has_repl_path_ || has_exec_ || per_piece_) path_view_.bind(ctx_, p, S.shift);
  if (has_repl_path_) {
    PathReplace api(*this, ip, p);
    auto r = S.rules.replacers->replace(Level::Path, ctx_, api);
    if (!r) return r.error();
    if (*r) {
      p.replaced = true;
      set_path_fields(ctx_, p);  // an altered path is decided again on its new shape
      path_view_.bind(ctx_, p, S.shift);
    } else {
      p.ops.clear();
    }
  }
  return piece_level(p);
}

Status LayerTask::piece_level(PathPlan& p) {
  size_t n = p.piece_count();
  if (need_overhang_ && L > 0 && n > 0) {
    const EdgeGrid& below = nb_.below_grid();
    p.overhang.assign(n, 0.0f);
    double half = 0.5 * p.width * geo::kUnitsPerMm;
    for (size_t i = 0; i < n; ++i) {
      const geo::Point &a = p.pts[i], &b = p.pts[i + 1];
      double dx = double(b.X - a.X), dy = double(b.Y - a.Y), len = std::hypot(dx, dy);
      if (len <= 0) continue;
      double nx = -dy / len * half, ny = dx / len * half;
      double miss = 0;
      constexpr double ts[] = {0.25, 0.5, 0.75};
      for (double t : ts) {
        double mx = double(a.X) + dx * t, my = double(a.Y) + dy * t;
        geo::Point l(std::llround(mx + nx), std::llround(my + ny)),
            r(std::llround(mx - nx), std::llround(my - ny));
        miss += 1.0 - below.inside_fraction(l, r);
      }
      p.overhang[i] = static_cast<float>(miss / 3.0);
    }
  }
  PropertyValues props = p.props;
  if (per_piece_ && n > 0) {
    p.pieces.resize(n);
    for (size_t i = 0; i < n; ++i) {
      set_piece_fields(ctx_, p, i, S.shift);
      props = p.props;
      if (Status s = decide(Stage::Piece, props); !s) return s;
      p.pieces[i] = {static_cast<float>(props[PropId::Speed]), static_cast<float>(props[PropId::Flow])};
    }
    ctx_.clear_from(Level::Piece);
  } else {
    if (Status s = decide(Stage::Piece, props); !s) return s;
    p.pieces.assign(1, {static_cast<float>(props[PropId::Speed]), static_cast<float>(props[PropId::Flow])});
  }
  p.props = props;
  for (Op& op : p.ops) {  // replacer moves without an explicit speed take the decided one
    if (op.kind == Op::Kind::Extrude && op.speed <= 0) op.speed = static_cast<float>(props[PropId::Speed]);
    if (op.kind == Op::Kind::Extrude && op.flow < 0) op.flow = static_cast<float>(props[PropId::Flow]);
  }
  return ok_status();
}

void LayerTask::travel_and_retract() {
  const double before = S.print_props[PropId::RetractBeforeTravel];
  const double longer = S.print_props[PropId::RetractLongTravel];
  const bool can_retract = S.print_props[PropId::RetractLength] > 0;
  geo::Rings material;
  for (const auto& ip : plan_.islands) material.insert(material.end(), ip.shape.begin(), ip.shape.end());
  auto comber = std::make_shared<Comber>(material);
  bool first = true, known = true;
  geo::Point pos;
  // A travel that would leave the part is routed around inside it when that is not much longer;
  // it retracts only if it still leaves the part, or is long. Replacer output moves the nozzle
  // where the plan cannot follow: the travel after it (or into a replaced path) retracts.
  auto visit = [&](PathPlan& p, bool comb) {
    if (p.pts.empty()) return;
    const geo::Point& to = p.pts.front();
    p.via.clear();
    if (first) {
      p.retract = can_retract;  // the layer change: the writer decides (and combs) it
    } else if (!known || p.replaced) {
      p.retract = can_retract;
    } else {
      double len = std::sqrt(dist2(pos, to)) * geo::kMmPerUnit;
      bool leaves = !comb || !comber->direct(pos, to);
      if (leaves && comb && len > before) {
        if (auto via = comber->route(pos, to)) {
          p.via = std::move(*via);
          leaves = false;
          len = Comber::length_mm(pos, p.via, to);
        }
      }
      p.retract = can_retract && (len > longer || (len > before && leaves));
    }
    first = false;
    known = !p.replaced;
    pos = p.pts.back();
  };
  for (auto& p : plan_.skirt) visit(p, false);
  for (auto& ip : plan_.islands) {
    if (ip.replaced) known = false;  // its own moves may come before its paths
    for (auto& p : ip.paths) visit(p, !ip.replaced);
    if (ip.replaced) known = false;
  }
  plan_.comber = std::move(comber);
}

// Time of a layer plan at its decided speeds (the writer's own moves, via walk_layer).
struct TimeVisitor {
  MotionClock clock;
  const PrintSetup& S;
  double height, filament;
  double extrude_s = 0, volume = 0;
  bool started = false;
  geo::Point pos;
  TimeVisitor(const PrintSetup& s, double h, double f) : clock(s.motion), S(s), height(h), filament(f) {}
  void island_begin(const IslandPlan&) {}
  void island_end(const IslandPlan&) {}
  void cell_begin(const IslandPlan&, const CellPlan&) {}
  void cell_end(const IslandPlan&, const CellPlan&) {}
  void path_begin(const IslandPlan*, const PathPlan&) {}
  void path_end(const IslandPlan*, const PathPlan&) {}
  void travel(const geo::Point& to, bool retract) {
    if (!started) {
      clock.start_at(to);  // the travel from the previous layer is counted by the writer
      started = true;
      pos = to;
      return;
    }
    if (retract) clock.pause(2 * S.print_props[PropId::RetractLength] / S.print_props[PropId::RetractSpeed]);
    clock.move(to, S.print_props[PropId::TravelSpeed], false);
    pos = to;
  }
  void extrude(const geo::Point& to, double speed, double mm3) {
    double t0 = clock.seconds();
    clock.move(to, speed, true);
    extrude_s += clock.seconds() - t0;
    volume += mm3;
    pos = to;
  }
  void path_default(const IslandPlan*, const PathPlan& p) {
    if (p.pts.empty()) return;
    if (started && p.retract)
      clock.pause(2 * S.print_props[PropId::RetractLength] / S.print_props[PropId::RetractSpeed]);
    for (const auto& q : p.via) travel(q, false);
    travel(p.pts.front(), false);
    double area = bead_area_mm2(p.width, height);
    for (size_t i = 0; i < p.piece_count(); ++i) {
      const auto& pp = p.piece(i);
      double len = std::sqrt(dist2(p.pts[i], p.pts[i + 1])) * geo::kMmPerUnit;
      extrude(p.pts[i + 1], pp.speed, len * area * pp.flow * p.piece_scale(i));
    }
  }
  void op(const IslandPlan*, const PathPlan*, const Op& op) {
    if (op.kind == Op::Kind::Retract && S.print_props[PropId::RetractLength] > 0) {
      clock.pause(2 * S.print_props[PropId::RetractLength] / S.print_props[PropId::RetractSpeed]);
    } else if (op.kind == Op::Kind::Travel) {
      travel(op.to,
             std::sqrt(dist2(pos, op.to)) * geo::kMmPerUnit > S.print_props[PropId::RetractBeforeTravel]);
    } else if (op.kind == Op::Kind::Extrude) {
      if (!started) travel(op.to, true);
      double len = std::sqrt(dist2(pos, op.to)) * geo::kMmPerUnit;
      extrude(op.to, op.speed, len * bead_area_mm2(op.width, height) * op.flow);
    }
  }
};

void LayerTask::time_and_slowdown() {
  auto estimate = [&]() {
    TimeVisitor tv(S, height_, filament_);
    walk_layer(plan_, tv);
    double total = tv.clock.finish();
    plan_.extruded_mm3 = tv.volume;
    return std::pair<double, double>(total, tv.extrude_s);
  };
  auto [total, extr] = estimate();
  const double min_time = plan_.props[PropId::MinLayerTime];
  const double min_speed = S.print_props[PropId::MinPrintSpeed];
  for (int iter = 0; iter < 2 && min_time > 0 && total < min_time && extr > 0; ++iter) {
    double factor = std::clamp(extr / std::max(extr + (min_time - total), 1e-9), 0.05, 1.0);
    auto slow = [&](PathPlan& p) {
      for (auto& pc : p.pieces)
        pc.speed = static_cast<float>(std::max(std::min<double>(pc.speed, min_speed), pc.speed * factor));
      for (auto& op : p.ops)
        if (op.kind == Op::Kind::Extrude)
          op.speed = static_cast<float>(std::max(std::min<double>(op.speed, min_speed), op.speed * factor));
    };
    for (auto& p : plan_.skirt) slow(p);
    for (auto& ip : plan_.islands) {
      for (auto& p : ip.paths) slow(p);
      for (auto& op : ip.ops)
        if (op.kind == Op::Kind::Extrude)
          op.speed = static_cast<float>(std::max(std::min<double>(op.speed, min_speed), op.speed * factor));
    }
    plan_.slowed = true;
    std::tie(total, extr) = estimate();
  }
  plan_.time_s = total;
}

Status LayerTask::cooling_level() {
  ctx_.clear_from(Level::Island);
  ctx_.set(FieldId::LayerTime, plan_.time_s);
  if (cooling_at_ <= Level::Layer) {
    PropertyValues props = plan_.props;
    if (Status s = decide(Stage::Cooling, props); !s) return s;
    float fan = static_cast<float>(props[PropId::Fan]);
    plan_.props[PropId::Fan] = fan;
    for (auto& p : plan_.skirt) p.fan = fan, p.props[PropId::Fan] = fan;
    for (auto& ip : plan_.islands)
      for (auto& p : ip.paths) p.fan = fan, p.props[PropId::Fan] = fan;
    return ok_status();
  }
  auto one = [&](IslandPlan* ip, PathPlan& p) -> Status {
    ctx_.clear_from(Level::Cell);
    if (ip && p.cell >= 0) set_cell_fields(ctx_, ip->cells[static_cast<size_t>(p.cell)]);
    set_path_fields(ctx_, p);
    PropertyValues props = p.props;
    if (Status s = decide(Stage::Cooling, props); !s) return s;
    p.fan = static_cast<float>(props[PropId::Fan]);
    p.props[PropId::Fan] = p.fan;
    return ok_status();
  };
  for (auto& p : plan_.skirt)
    if (Status s = one(nullptr, p); !s) return s;
  for (auto& ip : plan_.islands) {
    ctx_.clear_from(Level::Island);
    ctx_.set(FieldId::LayerTime, plan_.time_s);
    set_island_fields(ctx_, ip);
    for (auto& p : ip.paths)
      if (Status s = one(&ip, p); !s) return s;
  }
  return ok_status();
}

void IslandReplace::move_to(double x, double y, const ctx::MoveOptions& o) {
  Op op;
  if (!o.travel) {
    auto base = t_.custom_move(ip_.props, false);
    if (!base) {
      status = base.error();
      return;
    }
    op = *base;
  }
  op.kind = o.travel ? Op::Kind::Travel : Op::Kind::Extrude;
  op.to = t_.to_model(x, y);
  if (o.speed) op.speed = static_cast<float>(*o.speed);
  if (o.flow) op.flow = static_cast<float>(*o.flow);
  if (o.width) op.width = static_cast<float>(*o.width);
  ip_.ops.push_back(std::move(op));
}

Status IslandReplace::emit_default() {
  if (altered_) {
    if (Status s = t_.island_decide(ip_); !s) return s;
    altered_ = false;
    built_ = false;
  }
  if (!built_) {
    if (Status s = t_.island_content(ip_); !s) return s;
    built_ = true;
  }
  ip_.ops.push_back({Op::Kind::Default, {}, 0, 1, 0, {}});
  return ok_status();
}

Status IslandReplace::offset(double mm) {
  ip_.shape = toolpath::offset(ip_.shape, mm);
  // The rest of the replacer, and everything after it, sees the altered island: its fields and
  // properties are decided again now (a new generation of the island level).
  if (Status s = t_.island_decide(ip_); !s) return s;
  altered_ = false;
  built_ = false;
  return ok_status();
}

void PathReplace::move_to(double x, double y, const ctx::MoveOptions& o) {
  Op op;
  op.kind = o.travel ? Op::Kind::Travel : Op::Kind::Extrude;
  op.to = t_.to_model(x, y);
  op.width = o.width ? static_cast<float>(*o.width) : p_.width;
  op.speed = o.speed ? static_cast<float>(*o.speed) : 0.0f;  // 0: the path's decided speed
  op.flow = o.flow ? static_cast<float>(*o.flow) : -1.0f;    // <0: the path's decided flow
  p_.ops.push_back(std::move(op));
}

Status PathReplace::reverse() {
  std::reverse(p_.pts.begin(), p_.pts.end());
  std::reverse(p_.border.begin(), p_.border.end());
  std::reverse(p_.overhang.begin(), p_.overhang.end());
  t_.path_altered(p_);
  return ok_status();
}

Status PathReplace::offset(double mm) {
  auto& pts = p_.pts;
  size_t n = pts.size();
  if (n < 2 || mm == 0) return ok_status();
  double d = mm * geo::kUnitsPerMm;
  bool closed = p_.closed && pts.front() == pts.back();
  size_t m = closed ? n - 1 : n;  // distinct points
  auto normal = [&](size_t i) {   // left normal of segment i -> i+1 (cyclic when closed)
    const geo::Point& a = pts[i % m];
    const geo::Point& b = pts[(i + 1) % (closed ? m : n)];
    double dx = double(b.X - a.X), dy = double(b.Y - a.Y), len = std::hypot(dx, dy);
    return len > 0 ? std::pair<double, double>(-dy / len, dx / len) : std::pair<double, double>(0, 0);
  };
  geo::Ring out(n);
  for (size_t i = 0; i < m; ++i) {
    std::pair<double, double> nin, nout;
    if (closed) {
      nin = normal((i + m - 1) % m);
      nout = normal(i);
    } else {
      nin = normal(i == 0 ? 0 : i - 1);
      nout = normal(i + 1 < n ? i : i - 1);
    }
    double sx = nin.first + nout.first, sy = nin.second + nout.second;
    double dot = 1 + nin.first * nout.first + nin.second * nout.second;  // 1 + cos(turn)
    double k = dot > 0.2 ? d * 2 / dot : d * 10;                         // miter, capped at sharp turns
    out[i] = geo::Point(pts[i].X + std::llround(sx * k * 0.5 * (dot > 0.2 ? 1 : 0.2)),
                        pts[i].Y + std::llround(sy * k * 0.5 * (dot > 0.2 ? 1 : 0.2)));
  }
  if (closed) out[n - 1] = out[0];
  pts = std::move(out);
  (void)ip_;
  t_.path_altered(p_);
  return ok_status();
}

}  // namespace

Result<LayerPlan> plan_layer(const PrintSetup& setup, int index, Report& report) {
  LayerTask task(setup, index, report);
  return task.run();
}

}  // namespace tranche::toolpath
