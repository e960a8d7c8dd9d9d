// Random polygon generators shared by the property tests (coordinates in units, nm).
#pragma once

#include <random>

#include "polygon_checks.h"

namespace tranche::test::gen {

using Rng = std::mt19937_64;
using geo::coord_t;
using geo::Ring;
using geo::Rings;

inline double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
inline int pick(Rng& rng, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }

// A star-shaped outline with star-shaped holes cut out (by a Clipper difference, so holes may
// overlap each other and the outline).
inline Rings stars_with_holes(Rng& rng, coord_t grid) {
  const double r = uniform(rng, 5e6, 40e6);
  Rings outer{test::star(rng, 0, 0, r * uniform(rng, 0.2, 0.9), r, pick(rng, 3, 40), grid)};
  Rings holes;
  for (int i = pick(rng, 0, 8); i > 0; --i) {
    const double hr = r * uniform(rng, 0.05, 0.3);
    const double a = uniform(rng, 0, 2 * M_PI), d = uniform(rng, 0, r * 0.7);
    holes.push_back(test::star(rng, d * std::cos(a), d * std::sin(a), hr * uniform(rng, 0.3, 1), hr,
                               pick(rng, 3, 16), grid));
  }
  ClipperLib::Clipper c;
  c.AddPaths(outer, ClipperLib::ptSubject, true);
  c.AddPaths(holes, ClipperLib::ptClip, true);
  Rings out;
  c.Execute(ClipperLib::ctDifference, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return out;
}

// Axis-aligned rectangles on a coarse grid: pinch points, collinear runs, shared edges.
inline Rings rectangles(Rng& rng) {
  const coord_t g = 1000000;
  Rings out;
  for (int i = pick(rng, 1, 12); i > 0; --i) {
    const coord_t x = pick(rng, 0, 10) * g, y = pick(rng, 0, 10) * g;
    out.push_back(test::rect(x, y, x + pick(rng, 1, 5) * g, y + pick(rng, 1, 5) * g));
  }
  return out;
}

// Regular polygons ("circles") of random size, some reversed (holes where they lie inside others).
inline Rings circles(Rng& rng, coord_t grid) {
  Rings out;
  for (int i = pick(rng, 1, 8); i > 0; --i) {
    const double cx = uniform(rng, -20e6, 20e6), cy = uniform(rng, -20e6, 20e6), r = uniform(rng, 1e6, 15e6);
    const int n = pick(rng, 3, 48);
    const double phase = uniform(rng, 0, 1);
    Ring ring;
    for (int k = 0; k < n; ++k) {
      const double t = 2 * M_PI * (k + phase) / n;
      ring.emplace_back(std::llround((cx + r * std::cos(t)) / grid) * grid,
                        std::llround((cy + r * std::sin(t)) / grid) * grid);
    }
    if (pick(rng, 0, 3) == 0) ring = test::reversed(ring);
    out.push_back(ring);
  }
  return out;
}

// Random points: self-intersecting loops of every kind.
inline Rings scribbles(Rng& rng, coord_t grid) {
  Rings out;
  for (int i = pick(rng, 1, 3); i > 0; --i) {
    Ring ring;
    for (int k = pick(rng, 3, 12); k > 0; --k) {
      ring.emplace_back(pick(rng, -10, 10) * grid, pick(rng, -10, 10) * grid);
    }
    out.push_back(ring);
  }
  return out;
}

// Disjoint nested loops (rings of stars around a few centres) with random orientations: inside-out
// shells and same-direction nesting, which the overlap rule decides.
inline Rings nested(Rng& rng) {
  Rings out;
  for (int g = pick(rng, 1, 3); g > 0; --g) {
    const double cx = uniform(rng, -60e6, 60e6), cy = uniform(rng, -60e6, 60e6);
    double r = uniform(rng, 1e6, 3e6);
    for (int k = pick(rng, 1, 5); k > 0; --k) {
      const double r0 = r, r1 = r + uniform(rng, 0.5e6, 3e6);
      Ring ring = test::star(rng, cx, cy, r0, r1, pick(rng, 3, 30));
      if (pick(rng, 0, 1)) ring = test::reversed(ring);
      out.push_back(std::move(ring));
      r = r1 + uniform(rng, 0.2e6, 2e6);
    }
  }
  return out;
}

}  // namespace tranche::test::gen
