// Arrangement: objects without a place are put on the bed beside each other, by their convex
// hulls, `spacing` mm apart, around the objects that keep their place.
//
// Largest first, each object goes to the feasible position that keeps the pile of placed
// objects smallest (its bounding box, kept in the bed's proportions), the first one at the
// bed's centre. The feasible positions are those where its hull overlaps no placed hull (grown
// by the spacing) and stays on the bed: the no-fit polygons of convex hulls are convex (one
// Minkowski sum each), and the best position lies on a vertex of one of them, of the bed's
// inner-fit polygon, or where two of their edges cross: those are the candidates tried.
// Without fixed objects, the finished pile is centred on the bed. Arranged objects keep the bed's
// margin (the skirt's reach) from its edges.
#pragma once

#include <cstddef>
#include <vector>

#include "geometry/plate/bed.h"
#include "geometry/plate/hull.h"

namespace tranche::plate {

struct ArrangeItem {
  Convex hull;         // where the object stands now, mm
  bool fixed = false;  // keeps its place; the others go around it
};

struct Arrangement {
  std::vector<Vec2> moves;   // per item, mm (zero for fixed items and those that do not fit)
  std::vector<size_t> unfit;  // items for which no place on the bed was left
};

Arrangement arrange(const std::vector<ArrangeItem>& items, const Bed& bed, double spacing_mm);

}  // namespace tranche::plate
