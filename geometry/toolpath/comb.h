// Combing: travel moves routed inside the part instead of straight across a hole or a notch, so
// that they need no retraction. A travel that leaves an island's interior is replaced by one
// that follows the island's border (kept a little inside it) around the obstacle, then pulled
// tight so that it has as few moves as it can. The edge grids and the shrunk material are
// built on first use: most layers need few travels checked and fewer routed.
#pragma once

#include <mutex>
#include <optional>

#include "geometry/core/geom.h"
#include "geometry/toolpath/edge_grid.h"

namespace tranche::toolpath {

class Comber {
 public:
  Comber() = default;
  // `material`: the layer's islands (outer CCW, holes CW). Routes stay `margin_mm` inside them.
  explicit Comber(const geo::Rings& material, double margin_mm = 0.1);
  // The same with more islands, `ready`, whose shrunk regions are known (`ready_inner`, at least
  // the margin inside them: a support island's fill region), so they are not shrunk again.
  Comber(const geo::Rings& material, const geo::Rings& ready, const geo::Rings& ready_inner, double margin_mm = 0.1);

  // Whether the straight move ab stays inside the material (crosses no border).
  bool direct(const geo::Point& a, const geo::Point& b) const { return !border().crosses(a, b); }
  bool inside(const geo::Point& p) const { return border().inside(p); }
  // The intermediate points of a travel from a to b that stays inside one island, or nothing
  // when a or b is not well inside, they lie in different islands, or the detour would be
  // longer than max(2 × the straight distance, straight + `slack_mm`).
  std::optional<geo::Ring> route(const geo::Point& a, const geo::Point& b, double slack_mm = 15) const;

  // A point well inside the material next to `a`: `a` itself when it is, else the nearest point
  // of the shrunk material pushed 5 µm further in, if it is within `tol_mm` of `a`. The layer
  // change starts from the last point of the layer below, which lies outside this layer where
  // the wall slopes inward: stepping in there crosses no more than the bead just printed.
  std::optional<geo::Point> enter(const geo::Point& a, double tol_mm) const;

  // Length in mm of the travel a → via... → b.
  static double length_mm(const geo::Point& a, const geo::Ring& via, const geo::Point& b);

 private:
  const EdgeGrid& border() const;
  void build_comb() const;

  geo::Rings material_;  // to shrink, then the ready islands
  size_t shrink_count_ = 0;  // how many of material_'s rings are shrunk
  geo::Rings ready_inner_;
  double margin_mm_ = 0.1;
  mutable std::once_flag border_once_, comb_once_;
  mutable EdgeGrid border_;     // edges of the material itself
  mutable geo::Rings comb_;     // the material shrunk by the margin: routes follow these rings
  mutable EdgeGrid comb_grid_;  // edges of comb_
};

}  // namespace tranche::toolpath
