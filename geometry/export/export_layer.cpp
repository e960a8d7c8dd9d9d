#include "geometry/export/export_layer.h"

namespace tranche::exports {

std::string_view kind_name(schema::PathKind kind) {
  return schema::enum_value_name(schema::EnumType::PathKind, static_cast<int>(kind));
}

ExportLayer planned_layer(const geo::Layer& layer, const plan::LayerPlan& plan,
                          const std::vector<uint32_t>& resolved_index) {
  ExportLayer e;
  e.layer = &layer;
  e.printed.assign(layer.islands.size(), nullptr);
  for (const auto& ip : plan.islands) {
    if (ip.support) {
      e.support.push_back(&ip);
      continue;
    }
    const auto i = static_cast<size_t>(ip.index);
    if (i < resolved_index.size() && resolved_index[i] < e.printed.size()) e.printed[resolved_index[i]] = &ip;
  }
  e.skirt = &plan.skirt;
  return e;
}

}  // namespace tranche::exports
