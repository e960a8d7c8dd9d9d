// Visits a layer plan in print order, the one traversal shared by the time estimate and the
// G-code writer so that both see exactly the same moves. The visitor provides:
//   island_begin/end(const IslandPlan&), cell_begin/end(const IslandPlan&, const CellPlan&),
//   path_begin/end(const IslandPlan*, const PathPlan&), path_default(const IslandPlan*, const PathPlan&),
//   op(const IslandPlan*, const PathPlan*, const Op&)   (replacer output other than `default`)
#pragma once

#include "geometry/plan/plan.h"

namespace tranche::plan {

template <class V>
void walk_path(const IslandPlan* isl, const PathPlan& p, V& v) {
  v.path_begin(isl, p);
  if (p.replaced) {
    // A replacer starts where the default would: when its first move extrudes, the nozzle first
    // travels to the path's start (as for the default), so `for p in path.points { move to ... }`
    // does not extrude a line from wherever the previous path ended.
    for (const Op& op : p.ops) {
      if (op.kind == Op::Kind::Text) continue;
      if (op.kind == Op::Kind::Extrude && !p.pts.empty()) {
        Op start;
        start.kind = Op::Kind::Travel;
        start.to = p.pts.front();
        v.op(isl, &p, start);
      }
      break;
    }
    for (const Op& op : p.ops) {
      if (op.kind == Op::Kind::Default)
        v.path_default(isl, p);
      else
        v.op(isl, &p, op);
    }
  } else {
    v.path_default(isl, p);
  }
  v.path_end(isl, p);
}

template <class V>
void walk_island_content(const IslandPlan& isl, V& v) {
  int cell = -1;
  for (const PathPlan& p : isl.paths) {
    if (p.cell != cell) {
      if (cell >= 0) v.cell_end(isl, isl.cells[static_cast<size_t>(cell)]);
      cell = p.cell;
      if (cell >= 0) v.cell_begin(isl, isl.cells[static_cast<size_t>(cell)]);
    }
    walk_path(&isl, p, v);
  }
  if (cell >= 0) v.cell_end(isl, isl.cells[static_cast<size_t>(cell)]);
}

template <class V>
void walk_layer(const LayerPlan& layer, V& v) {
  for (const PathPlan& p : layer.skirt) walk_path(nullptr, p, v);
  for (const IslandPlan& isl : layer.islands) {
    v.island_begin(isl);
    if (isl.replaced) {
      for (const Op& op : isl.ops) {
        if (op.kind == Op::Kind::Default)
          walk_island_content(isl, v);
        else
          v.op(&isl, nullptr, op);
      }
    } else {
      walk_island_content(isl, v);
    }
    v.island_end(isl);
  }
}

}  // namespace tranche::plan
