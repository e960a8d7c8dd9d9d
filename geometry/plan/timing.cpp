#include "geometry/plan/timing.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "geometry/plan/walk.h"
#include "geometry/toolpath/flow.h"
#include "geometry/toolpath/order.h"

namespace tranche::plan {

using schema::PropId;
using toolpath::dist2;

namespace {

// Visits a layer plan's moves (walk_layer) into a MotionClock.
struct TimeVisitor {
  toolpath::MotionClock clock;
  const TravelPolicy& policy;
  double height;
  double volume = 0;
  bool started = false;
  geo::Point pos;
  TimeVisitor(const toolpath::MotionLimits& m, const TravelPolicy& p, double h) : clock(m), policy(p), height(h) {}
  void island_begin(const IslandPlan&) {}
  void island_end(const IslandPlan&) {}
  void cell_begin(const IslandPlan&, const CellPlan&) {}
  void cell_end(const IslandPlan&, const CellPlan&) {}
  void path_begin(const IslandPlan*, const PathPlan&) {}
  void path_end(const IslandPlan*, const PathPlan&) {}
  void retract() {
    if (policy.can_retract()) clock.pause(policy.retract_time_s());
  }
  void travel(const geo::Point& to, bool retract_first) {
    if (!started) {
      clock.start_at(to);  // the travel from the previous layer is counted by the writer
      started = true;
      pos = to;
      return;
    }
    if (retract_first) clock.pause(policy.retract_time_s());
    clock.move(to, policy.travel_speed, false);
    pos = to;
  }
  void extrude(const geo::Point& to, double speed, double mm3) {
    clock.move(to, speed, true);
    volume += mm3;
    pos = to;
  }
  void path_default(const IslandPlan*, const PathPlan& p) {
    if (p.pts.empty()) return;
    if (started && p.retract) clock.pause(policy.retract_time_s());
    for (const auto& q : p.via) travel(q, false);
    travel(p.pts.front(), false);
    double area = toolpath::bead_area_mm2(p.width, height);
    for (size_t i = 0; i < p.piece_count(); ++i) {
      const auto& pp = p.piece(i);
      double len = std::sqrt(dist2(p.pts[i], p.pts[i + 1])) * geo::kMmPerUnit;
      if (!p.widths.empty()) area = toolpath::bead_area_mm2(p.piece_width(i), height);
      extrude(p.pts[i + 1], pp.speed, len * area * pp.flow * p.piece_scale(i));
    }
  }
  void op(const IslandPlan*, const PathPlan*, const Op& op) {
    if (op.kind == Op::Kind::Retract) {
      retract();
    } else if (op.kind == Op::Kind::Travel) {
      travel(op.to, std::sqrt(dist2(pos, op.to)) * geo::kMmPerUnit > policy.before_mm);
    } else if (op.kind == Op::Kind::Extrude) {
      if (!started) travel(op.to, true);
      double len = std::sqrt(dist2(pos, op.to)) * geo::kMmPerUnit;
      extrude(op.to, op.speed, len * toolpath::bead_area_mm2(op.width, height) * op.flow);
    }
  }
};

}  // namespace

LayerTime layer_time(const LayerPlan& plan, const toolpath::MotionLimits& motion, const TravelPolicy& policy,
                     double height_mm) {
  TimeVisitor tv(motion, policy, height_mm);
  walk_layer(plan, tv);
  LayerTime t;
  t.total_s = tv.clock.finish();
  t.extrude_s = tv.clock.extruding_seconds();
  t.volume_mm3 = tv.volume;
  return t;
}

double layer_change_time(const geo::Point* from, const geo::Ring& via, const geo::Point& to, bool retract,
                         double height_mm, const toolpath::MotionLimits& motion, const TravelPolicy& policy) {
  double t = 0;
  if (retract) t += policy.retract_time_s();
  t += height_mm / motion.z_speed;
  if (from) {
    geo::Point prev = *from;
    auto leg = [&](const geo::Point& q) {
      double len = std::hypot(double(q.X - prev.X), double(q.Y - prev.Y)) * geo::kMmPerUnit;
      t += toolpath::trapezoid_time(len, policy.travel_speed, 0, 0, motion.travel_accel);
      prev = q;
    };
    for (const auto& q : via) leg(q);
    leg(to);
  }
  return t;
}

float slowed(float speed, double factor, double min_speed) {
  return static_cast<float>(std::max(std::min<double>(speed, min_speed), speed * factor));
}

void time_and_slow_down(LayerPlan& plan, const toolpath::MotionLimits& motion, const TravelPolicy& policy,
                        double min_speed) {
  LayerTime t = layer_time(plan, motion, policy, plan.height);
  const double min_time = plan.props[PropId::MinLayerTime];
  for (int iter = 0; iter < 2 && min_time > 0 && t.total_s < min_time && t.extrude_s > 0; ++iter) {
    const double factor = std::clamp(t.extrude_s / std::max(t.extrude_s + (min_time - t.total_s), 1e-9), 0.05, 1.0);
    auto slow_ops = [&](std::vector<Op>& ops) {
      for (auto& op : ops)
        if (op.kind == Op::Kind::Extrude) op.speed = slowed(op.speed, factor, min_speed);
    };
    auto slow = [&](PathPlan& p) {
      for (auto& pc : p.pieces) pc.speed = slowed(pc.speed, factor, min_speed);
      slow_ops(p.ops);
    };
    for (auto& p : plan.skirt) slow(p);
    for (auto& ip : plan.islands) {
      for (auto& p : ip.paths) slow(p);
      slow_ops(ip.ops);
    }
    plan.slowed = true;
    t = layer_time(plan, motion, policy, plan.height);
  }
  plan.time_s = t.total_s;
  plan.extruded_mm3 = t.volume_mm3;
}

}  // namespace tranche::plan
