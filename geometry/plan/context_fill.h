// Filling the context's field slots from plans: the same values whether the loop is deciding
// properties (layer_loop) or writing G-code with executors (geometry/gcode).
#pragma once

#include <vector>

#include "geometry/plan/plan.h"
#include "geometry/setup/print_setup.h"
#include "runtime/context/context.h"

namespace tranche::plan {

// Layer L of `setup` as the loop enters it: index, z, height, area, support area (no decisions).
LayerPlan layer_shell(const setup::PrintSetup& setup, int L);
// Island i of layer L as the loop enters it: index, object (and its name's text), shape, overhang.
IslandPlan island_shell(const setup::PrintSetup& setup, int L, size_t i);

void set_layer_fields(ctx::Context& c, const LayerPlan& layer, int islands);
void set_island_fields(ctx::Context& c, const IslandPlan& island);
void set_cell_fields(ctx::Context& c, const CellPlan& cell);
// Path fields (kind, perimeter, index, length, closed, pieces).
void set_path_fields(ctx::Context& c, const PathPlan& path);
// Piece fields of piece i of `path`; `shift` turns model units into bed units.
void set_piece_fields(ctx::Context& c, const PathPlan& path, size_t i, const geo::Point& shift);

// `path.pieces` and `path.points` for `for` loops; the views must outlive their use.
struct PathView {
  const PathPlan* path = nullptr;
  geo::Point shift;
  std::vector<ctx::PointMm> points;  // bed coordinates, mm
  void bind(ctx::Context& c, const PathPlan& p, const geo::Point& bed_shift);
};
// `layer.islands`.
struct IslandsView {
  const std::vector<IslandPlan>* islands = nullptr;
  void bind(ctx::Context& c, const std::vector<IslandPlan>& list);
};

}  // namespace tranche::plan
