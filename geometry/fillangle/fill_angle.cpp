#include "geometry/fillangle/fill_angle.h"

namespace tranche::geo {

double default_fill_angle_deg(int layer_index) { return layer_index % 2 == 0 ? 45.0 : 135.0; }

Status apply_fill_angle_script(FillAngleScript& script, std::vector<Layer>& layers) {
  FillAngleContext ctx;
  ctx.layer_count = static_cast<int>(layers.size());
  for (Layer& layer : layers) {
    ctx.layer_index = layer.index;
    ctx.z = layer.z_top;
    ctx.z_bottom = layer.z_bottom;
    ctx.island_count = static_cast<int>(layer.islands.size());
    for (size_t i = 0; i < layer.islands.size(); ++i) {
      Island& island = layer.islands[i];
      ctx.island_index = static_cast<int>(i);
      ctx.area = island.area_mm2;
      ctx.shape = &island.shape;
      auto a = script.angle(ctx);
      if (!a) return a.error();
      island.fill_angle_deg = *a;
    }
  }
  return ok_status();
}

}  // namespace tranche::geo
