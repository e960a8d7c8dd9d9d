#include "geometry/plan/nest.h"

namespace tranche::plan {

using schema::FieldId;
using schema::Level;
using schema::Stage;

Nest::Nest(const setup::PrintSetup& setup, const ctx::Cascade& cascade)
    : S(setup), C(cascade), ctx_(setup.print_ctx) {
  per_piece_ = C.varies_at(Stage::Piece) == Level::Piece;
  cooling_at_ = C.varies_at(Stage::Cooling);
  cell_angles_ = C.varies_at(Stage::Cell) >= Level::Cell;
}

void Nest::enter_layer(const LayerPlan& layer, int islands) {
  ctx_.clear_from(Level::Layer);
  set_layer_fields(ctx_, layer, islands);
}

void Nest::enter_island(const IslandPlan& island) {
  ctx_.clear_from(Level::Island);
  set_island_fields(ctx_, island);
}

void Nest::enter_path(const IslandPlan* ip, const PathPlan& p) {
  ctx_.clear_from(Level::Cell);
  if (ip && p.cell >= 0) set_cell_fields(ctx_, ip->cells[static_cast<size_t>(p.cell)]);
  set_path_fields(ctx_, p);
}

void Nest::enter_cell(const CellPlan& cell) {
  ctx_.clear_from(Level::Cell);
  set_cell_fields(ctx_, cell);
}

void Nest::enter_piece(const PathPlan& p, size_t i) { set_piece_fields(ctx_, p, i, S.shift); }

void Nest::enter_path_plan(schema::PathKind kind, int perimeter) {
  ctx_.clear_from(Level::Cell);
  ctx_.set(FieldId::PathKind, static_cast<double>(kind));
  ctx_.set(FieldId::PathPerimeter, perimeter);
}

Status Nest::decide(schema::Stage stage, ctx::PropertyValues& props, TraceRef& log) {
  if (!S.provenance) return decide(stage, props);
  if (!log) log = std::make_shared<TraceLog>();
  ctx_.set_trace(log.get());
  Status s = decide(stage, props);
  ctx_.set_trace(nullptr);
  return s;
}

Result<ctx::PropertyValues> Nest::path_props(const ctx::PropertyValues& island_props, schema::PathKind kind,
                                             int perimeter, TraceRef* log) {
  enter_path_plan(kind, perimeter);
  ctx::PropertyValues p = island_props;
  TraceRef unused;
  if (Status s = decide(Stage::PathPlan, p, log ? *log : unused); !s) return s.error();
  return p;
}

}  // namespace tranche::plan
