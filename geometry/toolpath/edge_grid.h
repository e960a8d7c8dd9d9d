// A uniform grid over the edges of closed rings, for the geometric questions the toolpath stage
// asks many times per layer: does a travel cross a border, does a segment run along a border,
// is a point inside, how much of a bead's width lies over material. Exact integer predicates.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/core/geom.h"

namespace tranche::toolpath {

class EdgeGrid {
 public:
  EdgeGrid() = default;
  // `cell` is the grid pitch in units (1 nm); 0 picks one from the edge count and extent.
  explicit EdgeGrid(const geo::Rings& rings, geo::coord_t cell = 0);

  bool empty() const { return edges_.empty(); }
  // Whether segment ab touches or crosses any edge.
  bool crosses(const geo::Point& a, const geo::Point& b) const;
  // Whether segment ab lies along an edge: both ends within `tol` units of one edge's line and
  // its midpoint projects inside that edge.
  bool along(const geo::Point& a, const geo::Point& b, geo::coord_t tol) const;
  // Even-odd point in polygon over all rings (points on an edge count as either).
  bool inside(const geo::Point& p) const;
  // Fraction (0..1) of segment ab lying inside the rings (even-odd).
  double inside_fraction(const geo::Point& a, const geo::Point& b) const;
  // 1 when every cell the box [x0, x1] × [y0, y1] meets holds no edge and lies inside, 0 when
  // every one holds none and lies outside (the box is then wholly inside, resp. outside), -1
  // otherwise. A few cells' flags, for many small questions about a region's interior.
  int box_state(geo::coord_t x0, geo::coord_t y0, geo::coord_t x1, geo::coord_t y1) const;
  // Whether no edge meets the closed box [x0, x1] × [y0, y1] (exact): all of it is then on one
  // side, inside or outside, as any point of it.
  bool box_clear(geo::coord_t x0, geo::coord_t y0, geo::coord_t x1, geo::coord_t y1) const;

  // Where segment ab crosses edges: parameter t along ab (0..1), the ring and the edge's index in
  // it (edge i runs from ring[i] to ring[i + 1]). Sorted by t; collinear overlaps are left out.
  struct Hit {
    double t;
    uint32_t ring, edge;
  };
  std::vector<Hit> hits(const geo::Point& a, const geo::Point& b) const;

 private:
  struct Edge {
    geo::Point a, b;
  };
  template <class F>
  void visit_segment_cells(const geo::Point& a, const geo::Point& b, F&& f) const;
  int cx(geo::coord_t x) const;
  int cy(geo::coord_t y) const;

  std::vector<Edge> edges_;
  std::vector<uint32_t> ring_start_;  // edges of ring k are edges_[ring_start_[k] .. ring_start_[k+1])
  geo::coord_t x0_ = 0, y0_ = 0, x1_ = 0, y1_ = 0, cell_ = 1;  // x1_, y1_: the edges' bounding box
  int nx_ = 0, ny_ = 0;
  std::vector<uint32_t> start_;  // CSR: edges of cell i are items_[start_[i] .. start_[i+1])
  std::vector<uint32_t> items_;
  std::vector<int8_t> empty_in_;  // per cell: 1 inside, 0 outside when no edge passes through it; -1 else
};

// std::llround(v) for |v| < 2^52, inlined (v - trunc(v) is exact there): half away from zero.
inline geo::coord_t round_units(double v) {
  geo::coord_t r = static_cast<geo::coord_t>(v);
  const double f = v - static_cast<double>(r);
  if (f >= 0.5) ++r;
  else if (f <= -0.5) --r;
  return r;
}

// Exact orientation of c relative to the directed line ab: >0 left, <0 right, 0 collinear.
int orient(const geo::Point& a, const geo::Point& b, const geo::Point& c);
// Whether closed segments ab and cd share a point.
bool segments_meet(const geo::Point& a, const geo::Point& b, const geo::Point& c, const geo::Point& d);

// The stretches inside `grid`'s region of parallel lines in the unit direction (dx, dy), `pitch`
// units apart across the disc of radius `half` round (cx, cy), shifted 37 units off the grid of
// vertices so that none runs through a vertex (a line grazing one anyway says nothing: skipped):
// chord(x0, y0, x1, y1, length) for each, in units, in order along each line. The bridge tests'
// sampling (support::is_bridge, the overhanging walls' direction).
template <class Chord>
void for_each_chord(const EdgeGrid& grid, double cx, double cy, double half, double pitch, double dx, double dy,
                    Chord&& chord) {
  auto at = [](double x, double y) { return geo::Point(std::llround(x), std::llround(y)); };
  for (double off = -half + 0.5 * pitch + 37; off < half; off += pitch) {
    const double ox = cx - dy * off, oy = cy + dx * off;
    const geo::Point A = at(ox - dx * half, oy - dy * half), B = at(ox + dx * half, oy + dy * half);
    const auto hits = grid.hits(A, B);
    if (hits.size() % 2 != 0) continue;
    const double len = std::hypot(double(B.X - A.X), double(B.Y - A.Y));
    for (size_t i = 0; i + 1 < hits.size(); i += 2) {
      const double t0 = hits[i].t, t1 = hits[i + 1].t;
      chord(double(A.X) + (double(B.X) - double(A.X)) * t0, double(A.Y) + (double(B.Y) - double(A.Y)) * t0,
            double(A.X) + (double(B.X) - double(A.X)) * t1, double(A.Y) + (double(B.Y) - double(A.Y)) * t1,
            (t1 - t0) * len);
    }
  }
}

}  // namespace tranche::toolpath
