#include "geometry/plan/replace.h"

#include <fmt/format.h>

#include <algorithm>

#include "geometry/toolpath/clip.h"

namespace tranche::plan {

using ctx::PropertyValues;
using schema::FieldId;
using schema::Level;
using schema::PathKind;
using schema::PropId;
using schema::Stage;

geo::Point to_model(const Nest& nest, double x_mm, double y_mm) {
  const geo::Point& shift = nest.setup().shift;
  return geo::Point(geo::to_units(x_mm) - shift.X, geo::to_units(y_mm) - shift.Y);
}

namespace {

// Speed, flow and width of an island replacer's `move to`: a path of kind `custom` in the island.
Result<Op> custom_move(Nest& nest, const PropertyValues& island_props) {
  PropertyValues p = island_props;
  nest.enter_path_plan(PathKind::Custom, -1);
  if (Status s = nest.decide(Stage::PathPlan, p); !s) return s.error();
  if (Status s = nest.decide(Stage::Piece, p); !s) return s.error();
  Op op;
  op.speed = static_cast<float>(p[PropId::Speed]);
  op.flow = static_cast<float>(p[PropId::Flow]);
  op.width = static_cast<float>(p[PropId::Width]);
  return op;
}

}  // namespace

void IslandReplace::move_to(double x, double y, const ctx::MoveOptions& o) {
  Op op;
  if (!o.travel) {
    auto base = custom_move(host_.nest(), ip_.props);
    if (!base) {
      status = base.error();
      return;
    }
    op = *base;
  }
  op.kind = o.travel ? Op::Kind::Travel : Op::Kind::Extrude;
  op.to = to_model(host_.nest(), x, y);
  if (o.speed) op.speed = static_cast<float>(*o.speed);
  if (o.flow) op.flow = static_cast<float>(*o.flow);
  if (o.width) op.width = static_cast<float>(*o.width);
  ip_.ops.push_back(std::move(op));
}

void IslandReplace::comment(std::string_view text) { gcode(fmt::format("; {}", text)); }

Status IslandReplace::emit_default() {
  if (!built_) {
    if (Status s = host_.build_island(ip_); !s) return s;
    built_ = true;
  }
  ip_.ops.push_back(Op::of(Op::Kind::Default));
  return ok_status();
}

Status IslandReplace::offset(double mm) {
  ip_.shape = toolpath::offset(ip_.shape, mm);
  ip_.wall_outline.clear();  // the walls follow the island as offset
  // The rest of the replacer, and everything after it, sees the altered island: its fields and
  // properties are decided again now (a new generation of the island level).
  if (Status s = host_.redecide_island(ip_); !s) return s;
  built_ = false;
  return ok_status();
}

void PathReplace::move_to(double x, double y, const ctx::MoveOptions& o) {
  Op op;
  op.kind = o.travel ? Op::Kind::Travel : Op::Kind::Extrude;
  op.to = to_model(nest_, x, y);
  op.width = o.width ? static_cast<float>(*o.width) : p_.width;
  op.speed = o.speed ? static_cast<float>(*o.speed) : 0.0f;  // 0: the path's decided speed
  op.flow = o.flow ? static_cast<float>(*o.flow) : -1.0f;    // <0: the path's decided flow
  p_.ops.push_back(std::move(op));
}

void PathReplace::comment(std::string_view text) { gcode(fmt::format("; {}", text)); }

void PathReplace::altered() {
  nest_.ctx().clear_from(Level::Path);
  set_path_fields(nest_.ctx(), p_);
  nest_.bind_points(p_);
}

Status PathReplace::reverse() {
  std::reverse(p_.pts.begin(), p_.pts.end());
  std::reverse(p_.border.begin(), p_.border.end());
  std::reverse(p_.overhang.begin(), p_.overhang.end());
  std::reverse(p_.widths.begin(), p_.widths.end());
  altered();
  return ok_status();
}

Status PathReplace::offset(double mm) {
  if (p_.pts.size() < 2 || mm == 0) return ok_status();
  p_.pts = toolpath::offset_polyline(p_.pts, p_.closed, mm);
  altered();
  return ok_status();
}

}  // namespace tranche::plan
