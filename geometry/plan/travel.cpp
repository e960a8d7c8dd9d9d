#include "geometry/plan/travel.h"

#include <cmath>
#include <memory>

#include "geometry/toolpath/order.h"

namespace tranche::plan {

using schema::PropId;

TravelPolicy TravelPolicy::of(const ctx::PropertyValues& P) {
  TravelPolicy t;
  t.retract_mm = P[PropId::RetractLength];
  t.retract_speed = P[PropId::RetractSpeed];
  t.before_mm = P[PropId::RetractBeforeTravel];
  t.long_mm = P[PropId::RetractLongTravel];
  t.travel_speed = P[PropId::TravelSpeed];
  return t;
}

Travel route_travel(const toolpath::Comber* comber, const geo::Point& from, const geo::Point& to,
                    const TravelPolicy& policy, double enter_mm) {
  Travel t;
  t.length_mm = std::sqrt(toolpath::dist2(from, to)) * geo::kMmPerUnit;
  bool leaves = !comber || (enter_mm > 0 && !comber->inside(from)) || !comber->direct(from, to);
  if (leaves && comber && t.length_mm > policy.before_mm) {
    std::optional<geo::Point> in = enter_mm > 0 ? comber->enter(from, enter_mm) : std::optional<geo::Point>(from);
    if (in) {
      if (auto route = comber->route(*in, to)) {
        if (*in != from) t.via.push_back(*in);
        t.via.insert(t.via.end(), route->begin(), route->end());
        leaves = false;
        t.length_mm = toolpath::Comber::length_mm(from, t.via, to);
      }
    }
  }
  t.retract = policy.retracts(t.length_mm, leaves);
  return t;
}

void plan_travels(LayerPlan& plan, const TravelPolicy& policy) {
  geo::Rings material, ready, ready_inner;  // support islands come with their fill region
  for (const auto& ip : plan.islands) {
    if (ip.support) {
      ready.insert(ready.end(), ip.shape.begin(), ip.shape.end());
      ready_inner.insert(ready_inner.end(), ip.fill_region.begin(), ip.fill_region.end());
    } else {
      material.insert(material.end(), ip.shape.begin(), ip.shape.end());
    }
  }
  auto comber = std::make_shared<toolpath::Comber>(material, ready, ready_inner);
  bool first = true, known = true;
  geo::Point pos;
  auto visit = [&](PathPlan& p, bool comb) {
    if (p.pts.empty()) return;
    p.via.clear();
    if (first || !known || p.replaced) {
      p.retract = policy.can_retract();  // the first: the layer change, which the writer decides
    } else {
      Travel t = route_travel(comb ? comber.get() : nullptr, pos, p.pts.front(), policy);
      p.retract = t.retract;
      p.via = std::move(t.via);
    }
    first = false;
    known = !p.replaced;
    pos = p.pts.back();
  };
  for (auto& p : plan.skirt) visit(p, false);
  for (auto& ip : plan.islands) {
    if (ip.replaced) known = false;  // its own moves may come before its paths
    for (auto& p : ip.paths) visit(p, !ip.replaced);
    if (ip.replaced) known = false;
  }
  plan.comber = std::move(comber);
}

}  // namespace tranche::plan
