#include "runtime/context/cascade.h"

#include <algorithm>

namespace tranche::ctx {

Result<std::unique_ptr<Cascade>> Cascade::create(const std::vector<std::pair<std::string, std::string>>& sets,
                                                 const Decider* rules, const Executors* executors,
                                                 const Replacers* replacers) {
  auto o = Overrides::parse(sets);
  if (!o) return o.error();
  std::unique_ptr<Cascade> c(new Cascade());
  c->overrides_ = std::move(*o);
  c->rules_ = rules;
  c->executors_ = executors;
  c->replacers_ = replacers;
  return c;
}

Status Cascade::decide(schema::Stage stage, Context& c, PropertyValues& props) const {
  c.set_props(&props);
  if (Trace* t = c.trace())
    for (const auto& info : schema::properties())
      if (info.stage == stage) t->step({info.id, TraceStep::Source::Start, UINT32_MAX, UINT32_MAX, props[info.id], 0});
  for (const Decider* d : {static_cast<const Decider*>(&defaults_), middle_, rules_,
                           static_cast<const Decider*>(&overrides_)})
    if (d)
      if (Status s = d->decide(stage, c, props); !s) return s;
  return ok_status();
}

Status Cascade::decide_defaults(schema::Stage stage, Context& c, PropertyValues& props) const {
  c.set_props(&props);
  return defaults_.decide(stage, c, props);
}

schema::Level Cascade::varies_at(schema::Stage stage) const {
  schema::Level l = schema::Level::Print;
  for (const Decider* d : {static_cast<const Decider*>(&defaults_), middle_, rules_,
                           static_cast<const Decider*>(&overrides_)})
    if (d) l = std::max(l, d->varies_at(stage));
  return l;
}

Result<Decider::Dependence> Decider::depends(schema::Stage stage, const Context&) const {
  Dependence d;
  d.level = varies_at(stage);
  if (d.level >= schema::stage_level(stage)) d.fields.set();
  return d;
}

Result<Decider::Dependence> Cascade::depends(schema::Stage stage, const Context& c) const {
  Decider::Dependence all;
  for (const Decider* d : {static_cast<const Decider*>(&defaults_), middle_, rules_,
                           static_cast<const Decider*>(&overrides_)}) {
    if (!d) continue;
    auto r = d->depends(stage, c);
    if (!r) return r.error();
    all.level = std::max(all.level, r->level);
    all.fields |= r->fields;
  }
  return all;
}

bool Cascade::reads_beyond(schema::Stage stage, schema::FieldId field) const {
  for (const Decider* d : {static_cast<const Decider*>(&defaults_), middle_, static_cast<const Decider*>(&overrides_)})
    if (d && d->reads(field)) return true;
  if (rules_ && rules_->reads_beyond(stage, field)) return true;
  // The rules usually also execute and replace: their reads_beyond() has counted those already.
  const void* rules = rules_ ? dynamic_cast<const void*>(rules_) : nullptr;
  if (executors_ && dynamic_cast<const void*>(executors_) != rules && executors_->reads(field)) return true;
  if (replacers_ && dynamic_cast<const void*>(replacers_) != rules && replacers_->reads(field)) return true;
  return false;
}

bool Cascade::reads(schema::FieldId field) const {
  for (const Decider* d : {static_cast<const Decider*>(&defaults_), middle_, rules_,
                           static_cast<const Decider*>(&overrides_)})
    if (d && d->reads(field)) return true;
  return (executors_ && executors_->reads(field)) || (replacers_ && replacers_->reads(field));
}

Result<PropertyValues> Cascade::print_props(const Context& print_ctx) const {
  PropertyValues p = PropertyValues::schema_defaults();
  Context c = print_ctx;
  if (Status s = decide(schema::Stage::Print, c, p); !s) return s.error();
  return p;
}

Result<double> Cascade::layer_height(const Context& print_ctx, const PropertyValues& print, int index, double z_bottom,
                                     double max_slope, double planned) const {
  Context c = print_ctx;
  c.clear_from(schema::Level::Layer);
  c.set(schema::FieldId::LayerIndex, index);
  c.set(schema::FieldId::LayerZBottom, z_bottom);
  c.set(schema::FieldId::LayerMaxSlope, max_slope);
  PropertyValues p = print;
  // The built-in "rule when layer.index == 0 { layer_height = first_layer_height }".
  if (index == 0)
    p[PropId::LayerHeight] = print[PropId::FirstLayerHeight];
  else if (planned > 0)
    p[PropId::LayerHeight] = planned;
  if (Status s = decide(schema::Stage::LayerPlan, c, p); !s) return s.error();
  return p[PropId::LayerHeight];
}

}  // namespace tranche::ctx
