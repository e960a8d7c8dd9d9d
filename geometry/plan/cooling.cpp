#include "geometry/plan/cooling.h"

namespace tranche::plan {

using schema::FieldId;
using schema::Level;
using schema::PropId;
using schema::Stage;

Status decide_cooling(LayerPlan& plan, Nest& nest) {
  ctx::Context& c = nest.ctx();
  c.clear_from(Level::Island);
  c.set(FieldId::LayerTime, plan.time_s);
  if (nest.cooling_at() <= Level::Layer) {
    ctx::PropertyValues props = plan.props;
    if (Status s = nest.decide(Stage::Cooling, props, plan.trace); !s) return s;
    const float fan = static_cast<float>(props[PropId::Fan]);
    plan.props[PropId::Fan] = fan;
    for (auto& p : plan.skirt) p.fan = fan, p.props[PropId::Fan] = fan;
    for (auto& ip : plan.islands)
      for (auto& p : ip.paths) p.fan = fan, p.props[PropId::Fan] = fan;
    return ok_status();
  }
  auto one = [&](IslandPlan* ip, PathPlan& p) -> Status {
    nest.enter_path(ip, p);
    ctx::PropertyValues props = p.props;
    TraceRef unused;
    if (Status s = nest.decide(Stage::Cooling, props, p.trace ? p.trace : unused); !s) return s;
    p.fan = static_cast<float>(props[PropId::Fan]);
    p.props[PropId::Fan] = p.fan;
    return ok_status();
  };
  for (auto& p : plan.skirt)
    if (Status s = one(nullptr, p); !s) return s;
  for (auto& ip : plan.islands) {
    nest.enter_island(ip);
    c.set(FieldId::LayerTime, plan.time_s);
    for (auto& p : ip.paths)
      if (Status s = one(&ip, p); !s) return s;
  }
  return ok_status();
}

}  // namespace tranche::plan
