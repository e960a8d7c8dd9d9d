// The context of one layer task as it walks the nest layer ⊃ island ⊃ cell ⊃ path ⊃ piece:
// entering an element clears the deeper levels and sets the element's fields; decide() asks the
// cascade (the one decision path) for a stage of the element entered last. Every stage of the
// loop that decides (island content, replacers, cooling) does it through the Nest, so a value
// can be followed from the context it was decided in to the plan it lands in.
#pragma once

#include "geometry/plan/context_fill.h"
#include "geometry/plan/plan.h"
#include "geometry/setup/print_setup.h"
#include "runtime/context/cascade.h"

namespace tranche::plan {

class Nest {
 public:
  Nest(const setup::PrintSetup& setup, const ctx::Cascade& cascade);

  const setup::PrintSetup& setup() const { return S; }
  const ctx::Cascade& cascade() const { return C; }
  ctx::Context& ctx() { return ctx_; }

  void enter_layer(const LayerPlan& layer, int islands);
  // The island, as a new element: its fields (and nothing deeper) are set.
  void enter_island(const IslandPlan& island);
  // The path (of island `ip`, or a skirt path when null) and its cell, if any.
  void enter_path(const IslandPlan* ip, const PathPlan& p);
  void enter_piece(const PathPlan& p, size_t i);
  // A fill cell of the island entered last, before its paths exist.
  void enter_cell(const CellPlan& cell);
  // A path of `kind` about to be built (path.kind and path.perimeter known, nothing else).
  void enter_path_plan(schema::PathKind kind, int perimeter);

  // Decides `stage` for the element entered last; `props` holds the earlier stages' values.
  Status decide(schema::Stage stage, ctx::PropertyValues& props) { return C.decide(stage, ctx_, props); }
  // Decides as decide() does, recording into `log` when the run records provenance (a new log
  // is made when `log` is null).
  Status decide(schema::Stage stage, ctx::PropertyValues& props, TraceRef& log);
  bool provenance() const { return S.provenance; }
  // The path-planning stage (width) of a path of `kind` in an island whose props are given;
  // recorded into `log` when given (and the run records provenance).
  Result<ctx::PropertyValues> path_props(const ctx::PropertyValues& island_props, schema::PathKind kind,
                                         int perimeter, TraceRef* log = nullptr);
  // A path's own log, starting with what its path-planning decision recorded (null when not recording).
  TraceRef path_log(const TraceRef& planned) const {
    return S.provenance ? std::make_shared<TraceLog>(planned ? *planned : TraceLog{}) : nullptr;
  }

  // `path.points`/`path.pieces` and `layer.islands` for rules that loop over them.
  void bind_points(const PathPlan& p) { path_view_.bind(ctx_, p, S.shift); }
  void bind_islands(const std::vector<IslandPlan>& islands) { islands_view_.bind(ctx_, islands); }

  // What the rules need, known before the loop starts.
  bool per_piece() const { return per_piece_; }          // speed/flow vary along a path
  bool cell_angles() const { return cell_angles_; }      // fill_angle is decided again per cell
  schema::Level cooling_at() const { return cooling_at_; }  // the deepest level the fan varies at
  bool executes() const { return C.executors() != nullptr; }
  bool replaces(schema::Level level) const { return C.replacers() && C.replacers()->has(level); }
  bool reads(schema::FieldId f) const { return C.reads(f); }
  // Whether code other than the decisions of `stage` reads `f` (Cascade::reads_beyond).
  bool reads_beyond(schema::Stage stage, schema::FieldId f) const { return C.reads_beyond(stage, f); }
  // For the path entered last: what its piece decisions depend on, given which rules its own
  // fields leave in play (Cascade::depends): whether speed and flow vary along it, and which
  // costly piece fields they read.
  Result<ctx::Decider::Dependence> piece_dependence() const { return C.depends(schema::Stage::Piece, ctx_); }

 private:
  const setup::PrintSetup& S;
  const ctx::Cascade& C;
  ctx::Context ctx_;
  PathView path_view_;
  IslandsView islands_view_;
  bool per_piece_ = false;
  bool cell_angles_ = false;
  schema::Level cooling_at_ = schema::Level::Layer;
};

}  // namespace tranche::plan
