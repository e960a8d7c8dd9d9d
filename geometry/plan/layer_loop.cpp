#include "geometry/plan/layer_loop.h"

#include <algorithm>

#include "geometry/plan/cooling.h"
#include "geometry/plan/island_content.h"
#include "geometry/plan/nest.h"
#include "geometry/plan/print_order.h"
#include "geometry/plan/replace.h"
#include "geometry/plan/timing.h"
#include "geometry/plan/travel.h"
#include "geometry/support/overhang.h"
#include "geometry/toolpath/relations.h"

namespace tranche::plan {
namespace {

using ctx::PropertyValues;
using schema::FieldId;
using schema::Level;
using schema::PropId;
using schema::Stage;

// One layer's walk. Its state is the nest's context and what the walk has planned so far.
class LayerTask final : public IslandHost {
 public:
  LayerTask(const setup::PrintSetup& s, const ctx::Cascade& c, int index)
      : S(s), nest_(s, c), L(index), nb_(s.layers, index, s.layer_cache.get()) {
    needs_ = IslandNeeds::of(nest_);
    overhang_ = nest_.reads(FieldId::PieceOverhang);
    overhang_beyond_ = nest_.reads_beyond(Stage::Piece, FieldId::PieceOverhang);
  }

  Result<LayerPlan> run() {
    if (Status s = layer_level(); !s) return s.error();
    return std::move(plan_);
  }

  // IslandHost (island replacers).
  Nest& nest() override { return nest_; }
  Status redecide_island(IslandPlan& ip) override {
    measure_island(ip, S.shift, nb_, needs_);
    nest_.enter_island(ip);
    ip.props = plan_.props;
    ip.trace.reset();
    return nest_.decide(Stage::Island, ip.props, ip.trace);
  }
  Status build_island(IslandPlan& ip) override {
    auto& regions = regions_[static_cast<size_t>(ip.index)];
    if (ip.support) return build_support(ip, nest_, plan_.height, support_kind_, support_wall_, regions);
    return plan::build_island(ip, nest_, nb_, plan_.height, regions);
  }

 private:
  Status layer_level();
  Status island_level(IslandPlan& ip);
  Status support_level();
  void order();
  Status path_level(IslandPlan* ip, PathPlan& p);
  Status piece_level(PathPlan& p);

  const setup::PrintSetup& S;
  Nest nest_;
  int L;
  toolpath::Neighbours nb_;
  IslandNeeds needs_;     // costly fields, computed only when read
  bool overhang_ = false;         // piece.overhang is read by some code
  bool overhang_beyond_ = false;  // ... by code other than the piece decisions (then on every path)
  LayerPlan plan_;
  std::vector<std::vector<FillGrid>> regions_;  // per island (by index): its fill regions' edges
  schema::PathKind support_kind_ = schema::PathKind::Support;  // of the support island being built
  bool support_wall_ = false;                                  // a tree branch: a wall round it
};

Status LayerTask::layer_level() {
  const geo::Layer& layer = S.layers[static_cast<size_t>(L)];
  plan_ = layer_shell(S, L);
  nest_.enter_layer(plan_, static_cast<int>(layer.islands.size()));
  plan_.props = S.print_props;
  if (Status s = nest_.decide(Stage::Layer, plan_.props, plan_.trace); !s) return s;

  plan_.islands.resize(layer.islands.size());
  regions_.resize(layer.islands.size());
  for (size_t i = 0; i < layer.islands.size(); ++i) {
    IslandPlan& ip = plan_.islands[i];
    ip = island_shell(S, L, i);
    if (Status s = island_level(ip); !s) return s;
  }
  if (Status s = support_level(); !s) return s;
  if (L == 0)
    if (Status s = build_skirt(plan_, nest_, plan_.height); !s) return s;
  order();
  if (nest_.executes() || nest_.replaces(Level::Path)) nest_.bind_islands(plan_.islands);

  // Path and piece levels, in print order.
  for (auto& sk : plan_.skirt)
    if (Status s = path_level(nullptr, sk); !s) return s;
  for (auto& ip : plan_.islands) {
    nest_.enter_island(ip);
    for (auto& p : ip.paths)
      if (Status s = path_level(&ip, p); !s) return s;
  }
  const TravelPolicy travel = TravelPolicy::of(S.print_props);
  plan_travels(plan_, travel);
  time_and_slow_down(plan_, S.motion, travel, S.print_props[PropId::MinPrintSpeed]);
  return decide_cooling(plan_, nest_);
}

// Support islands follow the part's: each piece of the layer's support (base, then interface)
// is an island of its own (island.support), decided and built like the others.
Status LayerTask::support_level() {
  if (static_cast<size_t>(L) >= S.support.size()) return ok_status();
  const support::SupportLayer& sl = S.support[static_cast<size_t>(L)];
  struct Piece {
    schema::PathKind kind;
    const geo::Rings* region;
    bool wall;
  };
  for (const Piece& pc : {Piece{schema::PathKind::Support, &sl.base, false},
                          Piece{schema::PathKind::SupportInterface, &sl.interface, false},
                          Piece{schema::PathKind::Support, &sl.tree, true}}) {
    support_kind_ = pc.kind;
    support_wall_ = pc.wall;
    const geo::Rings* region = pc.region;
    for (geo::Rings& piece : support::pieces(*region)) {  // booleans' results: no union needed
      IslandPlan ip;
      ip.index = static_cast<int>(plan_.islands.size());
      ip.support = true;
      ip.shape = std::move(piece);
      regions_.emplace_back();
      if (Status s = island_level(ip); !s) return s;
      plan_.islands.push_back(std::move(ip));
    }
  }
  return ok_status();
}

Status LayerTask::island_level(IslandPlan& ip) {
  if (Status s = redecide_island(ip); !s) return s;
  if (nest_.replaces(Level::Island)) {
    IslandReplace api(*this, ip);
    if (ip.trace) nest_.ctx().set_trace(ip.trace.get());
    auto r = nest_.cascade().replacers()->replace(Level::Island, nest_.ctx(), api);
    nest_.ctx().set_trace(nullptr);
    if (!r) return r.error();
    if (!api.status) return api.status;
    if (*r) {
      ip.replaced = true;
      return ok_status();
    }
    ip.ops.clear();
  }
  return build_island(ip);
}

// Skirt, then islands nearest first, starting at the rear of the layer.
void LayerTask::order() {
  geo::Point pos = layer_start(plan_.islands);
  order_skirt(plan_.skirt, pos);
  std::vector<IslandPlan> ordered;
  ordered.reserve(plan_.islands.size());
  for (size_t i : island_order(plan_.islands, pos, L)) {
    IslandPlan& ip = plan_.islands[i];
    order_island(ip, regions_[static_cast<size_t>(ip.index)], plan_.height, pos, SeamFrame{L, S.shift});
    ordered.push_back(std::move(ip));
  }
  plan_.islands = std::move(ordered);
}

Status LayerTask::path_level(IslandPlan* ip, PathPlan& p) {
  nest_.enter_path(ip, p);
  const bool repl = nest_.replaces(Level::Path);
  if (repl || nest_.executes() || nest_.per_piece()) nest_.bind_points(p);
  if (repl) {
    PathReplace api(nest_, p);
    if (p.trace) nest_.ctx().set_trace(p.trace.get());
    auto r = nest_.cascade().replacers()->replace(Level::Path, nest_.ctx(), api);
    nest_.ctx().set_trace(nullptr);
    if (!r) return r.error();
    if (*r) {
      p.replaced = true;
      set_path_fields(nest_.ctx(), p);  // an altered path is decided again on its new shape
      nest_.bind_points(p);
    } else {
      p.ops.clear();
    }
  }
  return piece_level(p);
}

Status LayerTask::piece_level(PathPlan& p) {
  const size_t n = p.piece_count();
  // The rules this path's own fields leave in play say whether speed and flow vary along it and
  // whether piece.overhang is needed (the default overhang steps: on walls only).
  bool vary = false, overhang = overhang_beyond_;
  if (n > 0 && (nest_.per_piece() || (overhang_ && !overhang))) {
    auto dep = nest_.piece_dependence();
    if (!dep) return dep.error();
    vary = nest_.per_piece() && dep->level >= Level::Piece;
    overhang = overhang || (overhang_ && dep->fields[static_cast<size_t>(FieldId::PieceOverhang)]);
  }
  if (overhang && L > 0 && n > 0)
    p.overhang = toolpath::average_along(toolpath::overhang_fractions(p.pts, p.width, nb_.below_grid()), p.pts,
                                         toolpath::kOverhangWindowMm);
  PropertyValues props = p.props;
  if (vary) {
    p.pieces.resize(n);
    if (nest_.provenance()) p.piece_traces.assign(n, nullptr);
    for (size_t i = 0; i < n; ++i) {
      nest_.enter_piece(p, i);
      props = p.props;
      TraceRef unused;
      if (Status s = nest_.decide(Stage::Piece, props, nest_.provenance() ? p.piece_traces[i] : unused); !s) return s;
      p.pieces[i] = {static_cast<float>(props[PropId::Speed]), static_cast<float>(props[PropId::Flow])};
    }
    nest_.ctx().clear_from(Level::Piece);
  } else {
    TraceRef unused;
    if (Status s = nest_.decide(Stage::Piece, props, p.trace ? p.trace : unused); !s) return s;
    p.pieces.assign(1, {static_cast<float>(props[PropId::Speed]), static_cast<float>(props[PropId::Flow])});
  }
  p.props = props;
  for (Op& op : p.ops) {  // replacer moves without an explicit speed take the decided one
    if (op.kind == Op::Kind::Extrude && op.speed <= 0) op.speed = static_cast<float>(props[PropId::Speed]);
    if (op.kind == Op::Kind::Extrude && op.flow < 0) op.flow = static_cast<float>(props[PropId::Flow]);
  }
  return ok_status();
}

}  // namespace

Result<LayerPlan> plan_layer(const setup::PrintSetup& setup, const ctx::Cascade& cascade, int index) {
  LayerTask task(setup, cascade, index);
  return task.run();
}

}  // namespace tranche::plan
