#include "runtime/context/cascade.h"

namespace tranche::ctx {

Result<std::unique_ptr<Cascade>> Cascade::create(const std::vector<std::pair<std::string, std::string>>& sets,
                                                 const Decider* rules, const Executors* executors,
                                                 const Replacers* replacers) {
  auto o = Overrides::parse(sets);
  if (!o) return o.error();
  std::unique_ptr<Cascade> c(new Cascade());
  c->overrides_ = std::move(*o);
  c->chain_.add(rules);
  c->chain_.add(&c->overrides_);
  c->rules_.executors = executors;
  c->rules_.replacers = replacers;
  c->rules_.defaults = &c->defaults_;
  c->rules_.decider = &c->chain_;
  return c;
}

Status Cascade::decide(schema::Stage stage, const Context& c, PropertyValues& props) const {
  Context cc = c;
  cc.set_props(&props);
  if (rules_.defaults)
    if (Status s = rules_.defaults->decide(stage, cc, props); !s) return s;
  if (rules_.decider)
    if (Status s = rules_.decider->decide(stage, cc, props); !s) return s;
  return ok_status();
}

Result<PropertyValues> Cascade::print_props(const Context& print_ctx) const {
  PropertyValues p = PropertyValues::schema_defaults();
  if (Status s = decide(schema::Stage::Print, print_ctx, p); !s) return s.error();
  return p;
}

Result<double> Cascade::layer_height(const Context& print_ctx, const PropertyValues& print, int index,
                                     double z_bottom) const {
  Context c = print_ctx;
  c.clear_from(schema::Level::Layer);
  c.set(schema::FieldId::LayerIndex, index);
  c.set(schema::FieldId::LayerZBottom, z_bottom);
  PropertyValues p = print;
  // The built-in "rule when layer.index == 0 { layer_height = first_layer_height }".
  if (index == 0) p[PropId::LayerHeight] = print[PropId::FirstLayerHeight];
  if (Status s = decide(schema::Stage::LayerPlan, c, p); !s) return s.error();
  return p[PropId::LayerHeight];
}

}  // namespace tranche::ctx
