#include "geometry/plan/context_fill.h"

#include <cmath>

namespace tranche::plan {

using schema::FieldId;

double PathPlan::length_mm() const {
  double len = 0;
  for (size_t i = 1; i < pts.size(); ++i)
    len += std::hypot(static_cast<double>(pts[i].X - pts[i - 1].X),
                      static_cast<double>(pts[i].Y - pts[i - 1].Y));
  return len * geo::kMmPerUnit;
}

LayerPlan layer_shell(const setup::PrintSetup& S, int L) {
  const geo::Layer& layer = S.layers[static_cast<size_t>(L)];
  LayerPlan p;
  p.index = L;
  p.z_bottom = layer.z_bottom;
  p.z = layer.z_top;
  p.height = layer.height();
  p.max_slope = layer.max_slope;
  p.area = S.table.get(L, FieldId::LayerArea);
  if (static_cast<size_t>(L) < S.support.size()) p.support_area = S.support[static_cast<size_t>(L)].area_mm2;
  return p;
}

IslandPlan island_shell(const setup::PrintSetup& S, int L, size_t i) {
  const auto l = static_cast<size_t>(L);
  const geo::Island& src = S.layers[l].islands[i];
  IslandPlan ip;
  ip.index = static_cast<int>(i);
  ip.object = src.object;
  const auto k = static_cast<size_t>(src.object);
  ip.object_text = k < S.object_texts.size() ? S.object_texts[k] : -1;
  ip.shape = geo::to_rings({src.shape});
  if (l < S.wall_outlines.size() && i < S.wall_outlines[l].size()) ip.wall_outline = S.wall_outlines[l][i];
  if (l < S.overhang_area.size() && i < S.overhang_area[l].size()) ip.overhang_area = S.overhang_area[l][i];
  return ip;
}

void set_layer_fields(ctx::Context& c, const LayerPlan& l, int islands) {
  c.set(FieldId::LayerIndex, l.index);
  c.set(FieldId::LayerZBottom, l.z_bottom);
  c.set(FieldId::LayerZ, l.z);
  c.set(FieldId::LayerHeight, l.height);
  c.set(FieldId::LayerArea, l.area);
  c.set(FieldId::LayerIslands, islands);
  c.set(FieldId::LayerSupportArea, l.support_area);
  c.set(FieldId::LayerMaxSlope, l.max_slope);
}

void set_island_fields(ctx::Context& c, const IslandPlan& i) {
  c.set(FieldId::IslandIndex, i.index);
  c.set(FieldId::IslandArea, i.area);
  c.set(FieldId::IslandBorderLength, i.border_length);
  c.set(FieldId::IslandHoles, i.holes);
  c.set(FieldId::IslandSupported, i.supported);
  c.set(FieldId::IslandCovered, i.covered);
  c.set(FieldId::IslandSizeX, i.size_x);
  c.set(FieldId::IslandSizeY, i.size_y);
  c.set(FieldId::IslandCenterX, i.center_x);
  c.set(FieldId::IslandCenterY, i.center_y);
  c.set(FieldId::IslandCells, static_cast<double>(i.cells.size()));
  c.set(FieldId::ObjectIndex, i.object);
  c.set(FieldId::IslandLongestEdgeAngle, i.longest_edge_angle);
  c.set(FieldId::IslandMinWidth, i.min_width);
  c.set(FieldId::IslandConvex, i.convex ? 1 : 0);
  c.set(FieldId::IslandBelowArea, i.below_area);
  c.set(FieldId::IslandBelowSupported, i.below_supported);
  c.set(FieldId::ObjectName, i.object_text);
  c.set(FieldId::IslandSupport, i.support ? 1 : 0);
  c.set(FieldId::IslandOverhangArea, i.overhang_area);
}

void set_cell_fields(ctx::Context& c, const CellPlan& cell) {
  c.set(FieldId::CellIndex, cell.index);
  c.set(FieldId::CellArea, cell.area_mm2);
  c.set(FieldId::CellFillAngle, cell.fill_angle_deg);
  c.set(FieldId::CellSolid, cell.solid ? 1 : 0);
}

void set_path_fields(ctx::Context& c, const PathPlan& p) {
  c.set(FieldId::PathKind, static_cast<double>(p.kind));
  c.set(FieldId::PathPerimeter, p.perimeter);
  c.set(FieldId::PathIndex, p.index);
  c.set(FieldId::PathLength, p.length_mm());
  c.set(FieldId::PathClosed, p.closed ? 1 : 0);
  c.set(FieldId::PathPieces, static_cast<double>(p.piece_count()));
}

namespace {
double piece_field(const PathPlan& p, size_t i, FieldId f, const geo::Point& shift) {
  switch (f) {
    case FieldId::PieceIndex:
      return static_cast<double>(i);
    case FieldId::PieceLength:
      return geo::kMmPerUnit * std::hypot(static_cast<double>(p.pts[i + 1].X - p.pts[i].X),
                                          static_cast<double>(p.pts[i + 1].Y - p.pts[i].Y));
    case FieldId::PieceBorder:
      return i < p.border.size() ? static_cast<double>(p.border[i]) : 0.0;
    case FieldId::PieceX:
      return geo::to_mm(p.pts[i].X + shift.X);
    case FieldId::PieceY:
      return geo::to_mm(p.pts[i].Y + shift.Y);
    case FieldId::PieceOverhang:
      return i < p.overhang.size() ? p.overhang[i] : 0.0;
    case FieldId::PieceWidth:
      return p.piece_width(i);
    default:
      return 0.0;
  }
}
}  // namespace

void set_piece_fields(ctx::Context& c, const PathPlan& p, size_t i, const geo::Point& shift) {
  for (FieldId f : {FieldId::PieceIndex, FieldId::PieceLength, FieldId::PieceBorder, FieldId::PieceX,
                    FieldId::PieceY, FieldId::PieceOverhang, FieldId::PieceWidth})
    c.set(f, piece_field(p, i, f, shift));
}

void PathView::bind(ctx::Context& c, const PathPlan& p, const geo::Point& bed_shift) {
  path = &p;
  shift = bed_shift;
  points.clear();
  points.reserve(p.pts.size());
  for (const auto& q : p.pts) points.push_back({geo::to_mm(q.X + shift.X), geo::to_mm(q.Y + shift.Y)});
  c.set_points(points);
  c.set_pieces(ctx::Collection(this, p.piece_count(), [](const void* d, size_t i, FieldId f) {
    const auto* v = static_cast<const PathView*>(d);
    return piece_field(*v->path, i, f, v->shift);
  }));
}

void IslandsView::bind(ctx::Context& c, const std::vector<IslandPlan>& list) {
  islands = &list;
  c.set_islands(ctx::Collection(this, list.size(), [](const void* d, size_t i, FieldId f) {
    const auto& isl = (*static_cast<const IslandsView*>(d)->islands)[i];
    switch (f) {
      case FieldId::IslandIndex:
        return static_cast<double>(isl.index);
      case FieldId::IslandArea:
        return isl.area;
      case FieldId::IslandBorderLength:
        return isl.border_length;
      case FieldId::IslandHoles:
        return static_cast<double>(isl.holes);
      case FieldId::IslandSupported:
        return isl.supported;
      case FieldId::IslandCovered:
        return isl.covered;
      case FieldId::IslandSizeX:
        return isl.size_x;
      case FieldId::IslandSizeY:
        return isl.size_y;
      case FieldId::IslandCenterX:
        return isl.center_x;
      case FieldId::IslandCenterY:
        return isl.center_y;
      case FieldId::IslandCells:
        return static_cast<double>(isl.cells.size());
      case FieldId::ObjectIndex:
        return static_cast<double>(isl.object);
      case FieldId::IslandLongestEdgeAngle:
        return isl.longest_edge_angle;
      case FieldId::IslandMinWidth:
        return isl.min_width;
      case FieldId::IslandConvex:
        return isl.convex ? 1.0 : 0.0;
      case FieldId::IslandBelowArea:
        return isl.below_area;
      case FieldId::IslandBelowSupported:
        return isl.below_supported;
      case FieldId::ObjectName:
        return static_cast<double>(isl.object_text);
      default:
        return 0.0;
    }
  }));
}

}  // namespace tranche::plan
