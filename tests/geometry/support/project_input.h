// The support tests' input: a layer stack's contacts by layer, its keep-out the part grown by the
// xy gap (as plan/support_pass makes it); a mushroom-shaped stack.
#pragma once

#include <vector>

#include "geometry/support/support.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/relations.h"
#include "tests/geometry/toolpath/fixtures.h"

namespace tranche::test {

inline support::ProjectInput project_input(const std::vector<geo::Layer>& layers, double xy_gap = 0.5) {
  support::ProjectInput in;
  in.layers = layers;
  in.contacts.resize(layers.size());
  for (const auto& l : layers) in.keep_out.push_back(toolpath::offset(toolpath::material(l), xy_gap));
  return in;
}

// 0.2 mm layers: `stem` on the first `stem_layers`, `cap` on the `cap_layers` above.
inline std::vector<geo::Layer> mushroom_stack(int stem_layers, int cap_layers, const geo::Ring& stem,
                                              const geo::Ring& cap) {
  auto layers = stack(stem_layers + cap_layers, 0.2, geo::Polygon{stem, {}});
  for (size_t k = static_cast<size_t>(stem_layers); k < layers.size(); ++k) layers[k].islands[0].shape.outer = cap;
  return layers;
}

}  // namespace tranche::test
