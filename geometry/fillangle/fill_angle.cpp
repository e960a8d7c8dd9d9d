#include "geometry/fillangle/fill_angle.h"

namespace tranche::geo {

using schema::FieldId;

Result<std::unique_ptr<ScriptAngles>> ScriptAngles::compute(FillAngleScript& script, std::span<const Layer> layers,
                                                            const ctx::Cascade& cascade,
                                                            const ctx::Context& print_ctx,
                                                            const ctx::PropertyValues& print_props) {
  auto out = std::make_unique<ScriptAngles>();
  out->angles_.resize(layers.size());
  FillAngleContext fc;
  fc.layer_count = static_cast<int>(layers.size());
  ctx::Context c = print_ctx;
  for (size_t l = 0; l < layers.size(); ++l) {
    const Layer& layer = layers[l];
    fc.layer_index = layer.index;
    fc.z = layer.z_top;
    fc.z_bottom = layer.z_bottom;
    fc.island_count = static_cast<int>(layer.islands.size());
    c.clear_from(schema::Level::Layer);
    c.set(FieldId::LayerIndex, layer.index);
    c.set(FieldId::LayerZBottom, layer.z_bottom);
    c.set(FieldId::LayerMaxSlope, layer.max_slope);
    c.set(FieldId::LayerZ, layer.z_top);
    c.set(FieldId::LayerHeight, layer.height());
    c.set(FieldId::LayerIslands, static_cast<double>(layer.islands.size()));
    for (size_t i = 0; i < layer.islands.size(); ++i) {
      const Island& island = layer.islands[i];
      c.clear_from(schema::Level::Island);
      c.set(FieldId::IslandIndex, static_cast<double>(i));
      c.set(FieldId::IslandArea, island.area_mm2);
      ctx::PropertyValues props = print_props;
      if (Status s = cascade.decide_defaults(schema::Stage::Island, c, props); !s) return s.error();
      fc.island_index = static_cast<int>(i);
      fc.area = island.area_mm2;
      fc.shape = &island.shape;
      fc.default_angle = props[schema::PropId::FillAngle];
      auto a = script.angle(fc);
      if (!a) return a.error();
      out->angles_[l].push_back(*a);
    }
  }
  return out;
}

Status ScriptAngles::decide(schema::Stage stage, const ctx::Context& ctx, ctx::PropertyValues& props) const {
  if (stage != schema::Stage::Island) return ok_status();
  auto l = static_cast<size_t>(ctx.get(FieldId::LayerIndex));
  auto i = static_cast<size_t>(ctx.get(FieldId::IslandIndex));
  if (l < angles_.size() && i < angles_[l].size()) {
    props[schema::PropId::FillAngle] = angles_[l][i];
    if (ctx::Trace* t = ctx.trace())
      t->step({schema::PropId::FillAngle, ctx::TraceStep::Source::Middle, UINT32_MAX, UINT32_MAX, angles_[l][i], 0});
  }
  return ok_status();
}

schema::Level ScriptAngles::varies_at(schema::Stage stage) const {
  return stage == schema::Stage::Island ? schema::Level::Island : schema::Level::Print;
}

bool ScriptAngles::reads(FieldId field) const {
  return field == FieldId::LayerIndex || field == FieldId::IslandIndex;
}

}  // namespace tranche::geo
