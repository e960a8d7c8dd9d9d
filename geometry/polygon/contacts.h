// Which edges of a set of rings meet: crossings, overlaps and touches, found by a sweep over the
// edges' x-extents with exact tests. Used by the coherence check of sliced loops and to make the
// resolved rings meet only at shared vertices.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/core/geom.h"
#include "geometry/polygon/exact.h"

namespace tranche::geo {

struct EdgeRef {
  uint32_t ring = 0, index = 0;  // the edge rings[ring][index] -> rings[ring][index + 1]
};

struct EdgeContact {
  EdgeRef a, b;
  exact::Contact kind = exact::Contact::None;
};

// Pairs of edges that share a point, except consecutive edges of one ring meeting only at their
// common vertex. Stops after `limit` contacts. Rings need no repeated consecutive points.
std::vector<EdgeContact> find_contacts(const Rings& rings, size_t limit = SIZE_MAX);

// A point where the two edges of a contact meet (for messages): the crossing point rounded to
// units for crossings, a shared point otherwise.
Point contact_point(const Rings& rings, const EdgeContact& c);

// Inserts a vertex into every edge whose interior passes through a vertex of any ring, so that
// rings meet only at shared vertices. Returns the number of vertices inserted.
size_t split_at_touching_vertices(Rings& rings);

}  // namespace tranche::geo
