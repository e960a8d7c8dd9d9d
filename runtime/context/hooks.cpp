#include "runtime/context/hooks.h"

#include <algorithm>

namespace tranche::ctx {

Status DeciderChain::decide(schema::Stage stage, const Context& ctx, PropertyValues& props) const {
  for (const Decider* d : chain_) {
    Status s = d->decide(stage, ctx, props);
    if (!s) return s;
  }
  return ok_status();
}

schema::Level DeciderChain::varies_at(schema::Stage stage) const {
  auto level = schema::Level::Print;
  for (const Decider* d : chain_) level = std::max(level, d->varies_at(stage));
  return level;
}

bool DeciderChain::reads(schema::FieldId field) const {
  for (const Decider* d : chain_)
    if (d->reads(field)) return true;
  return false;
}

}  // namespace tranche::ctx
