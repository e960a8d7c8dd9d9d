// Combing: travel moves routed inside the part instead of straight across a hole or a notch, so
// that they need no retraction. A travel that leaves an island's interior is replaced by one
// that follows the island's border (kept a little inside it) around the obstacle, then pulled
// tight so that it has as few moves as it can.
#pragma once

#include <optional>

#include "geometry/core/geom.h"
#include "geometry/toolpath/edge_grid.h"

namespace tranche::toolpath {

class Comber {
 public:
  Comber() = default;
  // `material`: the layer's islands (outer CCW, holes CW). Routes stay `margin_mm` inside them.
  explicit Comber(const geo::Rings& material, double margin_mm = 0.1);

  // Whether the straight move ab stays inside the material (crosses no border).
  bool direct(const geo::Point& a, const geo::Point& b) const { return !border_.crosses(a, b); }
  bool inside(const geo::Point& p) const { return border_.inside(p); }
  // The intermediate points of a travel from a to b that stays inside one island, or nothing
  // when a or b is not well inside, they lie in different islands, or the detour would be
  // longer than max(2 × the straight distance, straight + `slack_mm`).
  std::optional<geo::Ring> route(const geo::Point& a, const geo::Point& b, double slack_mm = 15) const;

  // Length in mm of the travel a → via... → b.
  static double length_mm(const geo::Point& a, const geo::Ring& via, const geo::Point& b);

 private:
  geo::Rings comb_;     // the material shrunk by the margin: routes follow these rings
  EdgeGrid comb_grid_;  // edges of comb_
  EdgeGrid border_;     // edges of the material itself
};

}  // namespace tranche::toolpath
