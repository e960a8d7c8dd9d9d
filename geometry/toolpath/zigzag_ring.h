// Internal to the zig-zag fill and the infill patterns (zigzag.cpp, zigzag_links.cpp, infill_patterns.cpp): points and rings in the frame
// rotated so that the fill lines are horizontal, walks round a ring, and the polylines the runs
// of lines become. Not for use outside geometry/toolpath.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/core/layer.h"
#include "geometry/toolpath/zigzag.h"
#include "runtime/schema/schema.h"

namespace tranche::toolpath::zigzag_detail {

// A point in the rotated frame: u along the lines, v across them (units).
struct UV {
  double u, v;
};

struct Ring2 {
  std::vector<UV> pts;               // inset vertices in the rotated frame (units)
  std::vector<geo::EdgeKind> kinds;  // per edge
};

// Walking round a ring of n vertices from a point on edge `from` (forward: increasing indices),
// `count` vertices: calls f(vertex, edge just walked along) for each, and stops early, returning
// false, when f does. `steps` counts the vertices between a point on edge `from` and one on edge
// `to` (0 on the same edge).
inline uint32_t steps(uint32_t n, uint32_t from, uint32_t to, bool forward) {
  return forward ? (to + n - from) % n : (from + n - to) % n;
}
template <class F>
bool walk_ring(uint32_t n, uint32_t from, uint32_t count, bool forward, F&& f) {
  for (uint32_t k = 0; k < count; ++k) {
    uint32_t v = forward ? (from + 1 + k) % n : (from + n - k) % n;
    if (!f(v, forward ? (v + n - 1) % n : v)) return false;
  }
  return true;
}

inline schema::Border border_of(geo::EdgeKind k) {
  return k == geo::EdgeKind::Real ? schema::Border::Real : schema::Border::Artificial;
}

// A polyline's end: the ring edge it lies on.
struct End {
  uint32_t ring, edge;
  UV p;
};

// A run of lines as a polyline, still in the rotated frame.
struct Poly {
  std::vector<UV> pts;
  std::vector<schema::Border> border;  // per piece
  End first, last;
  double area = 0;  // units²
  int runs = 1;
};

// Polylines joined end to start by links along the border of `rings` at most `limit` units long
// (FillSpec::link_max_mm), greedily from each polyline in turn; `polys` unchanged when limit <= 0.
// With many polylines (more than 64) their ends are looked up on a grid of cells `limit` wide:
// the same links as trying every end (index = false, for tests), without the quadratic cost.
// With anchor > 0, each end left free on a ring then runs on along it by up to `anchor` units
// (PrusaSlicer's infill anchors), the way round with more room, stopping `clearance` short of
// any other end, link or anchor on that ring.
std::vector<Poly> link_along_border(std::vector<Poly> polys, const std::vector<Ring2>& rings, double limit,
                                    bool index = true, double anchor = 0, double clearance = 0);

// Polylines to paths, each point through `to_point` (UV -> bed point), points that round
// together merged; paths of fewer than two points dropped.
template <class ToPoint>
std::vector<FillPath> to_fill_paths(const std::vector<Poly>& polys, ToPoint to_point) {
  std::vector<FillPath> out;
  for (const Poly& P : polys) {
    FillPath fp;
    for (size_t k = 0; k < P.pts.size(); ++k) {
      const geo::Point q = to_point(P.pts[k]);
      if (!fp.pts.empty()) {
        if (fp.pts.back() == q) continue;
        fp.border.push_back(P.border[k - 1]);
      }
      fp.pts.push_back(q);
    }
    fp.area_mm2 = P.area * geo::kMmPerUnit * geo::kMmPerUnit;
    fp.runs = P.runs;
    if (fp.pts.size() >= 2) out.push_back(std::move(fp));
  }
  return out;
}

}  // namespace tranche::toolpath::zigzag_detail
