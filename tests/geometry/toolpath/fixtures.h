// Small shapes for the toolpath tests, in model units (1 nm).
#pragma once

#include <cmath>
#include <cstdint>

#include "geometry/core/geom.h"
#include "geometry/core/layer.h"

namespace tranche::test {

inline geo::Ring rect(double x0, double y0, double x1, double y1, bool ccw = true) {
  geo::Ring r{geo::to_point(x0, y0), geo::to_point(x1, y0), geo::to_point(x1, y1), geo::to_point(x0, y1)};
  if (!ccw) ClipperLib::ReversePath(r);
  return r;
}

// A circle of `n` vertices, counter-clockwise.
inline geo::Ring circle(double cx, double cy, double r, int n = 96) {
  geo::Ring c;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    c.push_back(geo::to_point(cx + r * std::cos(a), cy + r * std::sin(a)));
  }
  return c;
}

// A small linear congruential generator: the same numbers on every machine, in [0, 1).
struct Lcg {
  uint32_t seed;
  double operator()() {
    seed = seed * 1664525u + 1013904223u;
    return (seed >> 8) / double(1 << 24);
  }
};

// A layer stack of identical islands (outer + holes) from z = 0, layer height h.
inline std::vector<geo::Layer> stack(int count, double h, const geo::Polygon& shape) {
  std::vector<geo::Layer> layers(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) {
    auto& l = layers[static_cast<size_t>(i)];
    l.index = i;
    l.z_bottom = i * h;
    l.z_top = (i + 1) * h;
    geo::Island isl;
    isl.shape = shape;
    isl.area_mm2 = geo::area_mm2(shape);
    l.islands.push_back(isl);
  }
  return layers;
}

}  // namespace tranche::test
