// The support tests' input: a layer stack's contacts by layer, its keep-out the part grown by the
// xy gap (as plan/support_pass makes it).
#pragma once

#include <vector>

#include "geometry/support/support.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/relations.h"

namespace tranche::test {

inline support::ProjectInput project_input(const std::vector<geo::Layer>& layers, double xy_gap = 0.5) {
  support::ProjectInput in;
  in.layers = layers;
  in.contacts.resize(layers.size());
  for (const auto& l : layers) in.keep_out.push_back(toolpath::offset(toolpath::material(l), xy_gap));
  return in;
}

}  // namespace tranche::test
