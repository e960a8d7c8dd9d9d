// Print order inside a layer: where closed loops start (the seam) and in which order loops,
// zig-zags and islands are visited, chosen to keep travel short.
//
// Seams: `rear` starts a loop at its vertex of largest y (ties: smallest x); `aligned` does the
// same but prefers sharp corners (concave ones most), which hide the seam, so that a seam found
// on one layer is found again at the same place on the next (the choice depends only on the
// loop's shape, never on the previous layer, so layers stay independent and parallel);
// `nearest` starts at the vertex nearest the nozzle.
// `random` starts at a point drawn uniformly along the loop's length (choose_seam: its nearest
// vertex; the print order inserts a vertex there) from a seed the caller makes of the layer,
// the island and the loop, so the same input gives the same G-code. `sharpest_corner` starts in the loop's sharpest concave corner (a convex corner only
// when it has no concave one, at half the weight), measured over 0.5 mm either side of a vertex
// so that a corner rounded by many short edges counts whole; a loop that turns nowhere by 30° or
// more (a circle) falls back to `aligned`. `point` starts at the vertex nearest a given point.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "geometry/core/geom.h"
#include "runtime/schema/schema.h"

namespace tranche::toolpath {

// Index of the vertex where a closed loop starts.
size_t choose_seam(const geo::Ring& loop, schema::Seam mode, const geo::Point& from);
// The point at a fraction u ∈ [0, 1) of the loop's length from vertex 0 (random seams: the
// print order inserts a vertex there, so a loop of few vertices gets seams along its edges).
geo::Point point_at_fraction(const geo::Ring& loop, double u);
// The fraction of a loop's length `random` draws from a seed.
inline double seam_fraction(uint64_t seed) { return static_cast<double>(seed >> 11) * 0x1.0p-53; }

// What the seam modes other than aligned, nearest and rear need.
struct SeamOptions {
  schema::Seam mode = schema::Seam::Aligned;
  uint64_t seed = 0;   // random: the same seed, the same seam
  geo::Point toward;   // point: the point the seam is drawn toward, in the loop's frame
};
size_t choose_seam(const geo::Ring& loop, const SeamOptions& options, const geo::Point& from);
// A seed for `random` from the layer, the island and the loop within it (a 64-bit mix).
uint64_t seam_seed(int layer, int island, size_t loop);
// The loop as a closed polyline starting and ending at vertex `start`.
geo::Ring open_loop_at(const geo::Ring& loop, size_t start);

// The point of a closed loop nearest `p`, and its squared distance (units²).
std::pair<double, geo::Point> nearest_on_loop(const geo::Ring& loop, const geo::Point& p);
// The same over several closed rings.
std::pair<double, geo::Point> nearest_on_rings(const geo::Rings& rings, const geo::Point& p);
// Index of the loop's vertex at `q` (a point on the loop), inserted on its edge if no vertex is
// within 10 µm of it.
size_t insert_vertex(geo::Ring& loop, const geo::Point& q);

// Squared distance in units².
inline double dist2(const geo::Point& a, const geo::Point& b) {
  double dx = static_cast<double>(a.X - b.X), dy = static_cast<double>(a.Y - b.Y);
  return dx * dx + dy * dy;
}

// Greedy nearest-neighbour order of open paths that may be run either way: returns the order
// as (index, reversed) pairs, starting from `from`.
struct Visit {
  size_t index;
  bool reversed;
};
std::vector<Visit> chain_open(const std::vector<const geo::Ring*>& paths, const geo::Point& from);

// Cost of going from path `i`'s end `a` to path `j`'s start `b` (i = kStart: from the starting
// point); any unit, lower is better.
constexpr size_t kStart = static_cast<size_t>(-1);
using StepCost = std::function<double(size_t i, const geo::Point& a, size_t j, const geo::Point& b)>;
// The cheapest of greedy orders (each step to the cheapest next path and direction) started
// from every path in either direction, when there are at most `max_tries` paths; otherwise the
// one greedy order from `from`. Greedy from the nozzle alone often fills the big cell first and
// is left with a small one across the part; starting elsewhere lets each cell begin where the
// previous one ended.
// `end_cost`, if given, is added for where the last path ends (what comes next starts there).
using EndCost = std::function<double(const geo::Point& end)>;
// `lower`, if given, bounds the step cost from below by the step's length (mm): cost(i, a, j, b)
// ≥ lower(|ab|) for all steps, lower non-decreasing. The greedy order from `from` (with more than
// max_tries paths) then looks at the paths' ends nearest first, over a grid, until lower says
// no further end can be cheaper: the same order, without trying every path at every step.
using LowerCost = std::function<double(double length_mm)>;
std::vector<Visit> chain_open_best(const std::vector<const geo::Ring*>& paths, const geo::Point& from,
                                   const StepCost& cost, size_t max_tries = 48, const EndCost& end_cost = {},
                                   const LowerCost& lower = {}, double cell_mm = 10);

}  // namespace tranche::toolpath
