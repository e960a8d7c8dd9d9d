// Property checks shared by the polygon tests: what every resolution and decomposition must
// satisfy, whatever the input.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "geometry/core/layer.h"
#include "geometry/polygon/contacts.h"
#include "geometry/polygon/exact.h"
#include "geometry/polygon/monotone.h"

namespace tranche::test {

using geo::exact::i128;

inline i128 island_area2(const geo::Island& is) {
  i128 a = geo::exact::area2(is.shape.outer);
  for (const auto& h : is.shape.holes) a += geo::exact::area2(h);
  return a;
}

inline bool has_repeated_point(const geo::Ring& r) {
  std::vector<std::pair<geo::coord_t, geo::coord_t>> pts;
  for (const auto& p : r) pts.emplace_back(p.X, p.Y);
  std::sort(pts.begin(), pts.end());
  return std::adjacent_find(pts.begin(), pts.end()) != pts.end();
}

// An island as resolve.h promises it: outer CCW, holes CW, each ring simple, rings meeting only
// at shared vertices. Returns an empty string or what is wrong.
inline std::string island_problem(const geo::Island& is) {
  if (is.shape.outer.size() < 3 || geo::exact::area2(is.shape.outer) <= 0) return "outer not CCW";
  for (const auto& h : is.shape.holes) {
    if (h.size() < 3 || geo::exact::area2(h) >= 0) return "hole not CW";
  }
  geo::Rings rings{is.shape.outer};
  rings.insert(rings.end(), is.shape.holes.begin(), is.shape.holes.end());
  for (const auto& r : rings) {
    if (has_repeated_point(r)) return "ring visits a point twice";
  }
  for (const auto& c : geo::find_contacts(rings)) {
    if (c.kind != geo::exact::Contact::Touch) return "edges cross or overlap";
    const auto& ra = rings[c.a.ring];
    const auto& rb = rings[c.b.ring];
    const geo::Point a0 = ra[c.a.index], a1 = ra[(c.a.index + 1) % ra.size()];
    const geo::Point b0 = rb[c.b.index], b1 = rb[(c.b.index + 1) % rb.size()];
    if (!(a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1)) return "edges touch away from a shared vertex";
  }
  return "";
}

// Winding number of `ring` around p, p given in doubled coordinates (off the integer grid).
inline int winding_doubled(const geo::Ring& ring, const geo::Point& p) {
  int wn = 0;
  for (size_t i = 0, n = ring.size(); i < n; ++i) {
    const geo::Point a(ring[i].X * 2, ring[i].Y * 2), b(ring[(i + 1) % n].X * 2, ring[(i + 1) % n].Y * 2);
    if (a.Y <= p.Y) {
      if (b.Y > p.Y && geo::exact::orientation(a, b, p) > 0) ++wn;
    } else if (b.Y <= p.Y && geo::exact::orientation(a, b, p) < 0) {
      --wn;
    }
  }
  return wn;
}

inline double distance_doubled(const geo::Ring& ring, const geo::Point& p) {
  double best = 1e300;
  for (size_t i = 0, n = ring.size(); i < n; ++i) {
    const double ax = 2.0 * ring[i].X, ay = 2.0 * ring[i].Y;
    const double bx = 2.0 * ring[(i + 1) % n].X, by = 2.0 * ring[(i + 1) % n].Y;
    const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? ((p.X - ax) * dx + (p.Y - ay) * dy) / len2 : 0;
    t = std::clamp(t, 0.0, 1.0);
    best = std::min(best, std::hypot(p.X - ax - t * dx, p.Y - ay - t * dy));
  }
  return best;
}

using Seg = std::pair<std::pair<geo::coord_t, geo::coord_t>, std::pair<geo::coord_t, geo::coord_t>>;
inline Seg seg(const geo::Point& a, const geo::Point& b) { return {{a.X, a.Y}, {b.X, b.Y}}; }

// Every property of a decomposition; returns an empty string or the first violation.
inline std::string cells_problem(const geo::Island& is, const std::vector<geo::Cell>& cells, double angle,
                                 bool check_overlaps = true, std::mt19937_64* rng = nullptr) {
  if (cells.empty()) return "no cells";
  i128 sum = 0;
  std::multiset<Seg> real, boundary, cuts;
  for (const auto& c : cells) {
    if (c.edges.size() != c.ring.size()) return "edges and ring differ in size";
    if (geo::exact::area2(c.ring) <= 0) return "cell not CCW";
    if (has_repeated_point(c.ring)) return "cell visits a point twice";
    if (!geo::is_monotone(c.ring, angle)) return "cell not monotone";
    if (c.fill_angle_deg != angle) return "cell angle differs";
    sum += geo::exact::area2(c.ring);
    for (size_t i = 0; i < c.ring.size(); ++i) {
      const Seg s = seg(c.ring[i], c.ring[(i + 1) % c.ring.size()]);
      (c.edges[i] == geo::EdgeKind::Real ? real : cuts).insert(s);
    }
  }
  if (sum != island_area2(is)) return "cell areas do not add up to the island's";
  auto add_ring = [&](const geo::Ring& r) {
    for (size_t i = 0; i < r.size(); ++i) boundary.insert(seg(r[i], r[(i + 1) % r.size()]));
  };
  add_ring(is.shape.outer);
  for (const auto& h : is.shape.holes) add_ring(h);
  if (real != boundary) return "real edges are not the island's boundary";
  for (const auto& s : cuts) {
    if (cuts.count({s.second, s.first}) != cuts.count(s)) return "a cut is not shared by two cells";
    if (boundary.count(s) || boundary.count({s.second, s.first})) return "a cut runs along the boundary";
  }
  if (rng) {
    // Exact: sampled points lie in exactly as many cells as the island covers them (0 or 1).
    const geo::BBox2 box = geo::bbox(is.shape.outer);
    std::uniform_int_distribution<geo::coord_t> ux(box.min_x, box.max_x), uy(box.min_y, box.max_y);
    for (int s = 0; s < 32; ++s) {
      const geo::Point p(2 * ux(*rng) + 1, 2 * uy(*rng) + 1);
      bool in = winding_doubled(is.shape.outer, p) != 0;
      for (const auto& h : is.shape.holes) in = in && winding_doubled(h, p) == 0;
      int count = 0;
      for (const auto& c : cells) count += winding_doubled(c.ring, p) != 0;
      if (count != (in ? 1 : 0)) return "a sampled point lies in " + std::to_string(count) + " cells";
    }
  }
  if (check_overlaps) {
    for (size_t i = 0; i < cells.size(); ++i) {
      const geo::BBox2 bi = geo::bbox(cells[i].ring);
      for (size_t j = i + 1; j < cells.size(); ++j) {
        const geo::BBox2 bj = geo::bbox(cells[j].ring);
        if (bi.max_x <= bj.min_x || bj.max_x <= bi.min_x || bi.max_y <= bj.min_y || bj.max_y <= bi.min_y)
          continue;
        ClipperLib::Clipper cl;
        cl.AddPath(cells[i].ring, ClipperLib::ptSubject, true);
        cl.AddPath(cells[j].ring, ClipperLib::ptClip, true);
        geo::Rings out;
        cl.Execute(ClipperLib::ctIntersection, out);
        // Clipper rounds intersection points to the grid: slivers up to ~1 unit thick are its own.
        for (const auto& r : out) {
          if (static_cast<double>(geo::exact::area2(r)) > 2.0 * geo::length_mm(r) * geo::kUnitsPerMm) {
            return "two cells overlap";
          }
        }
      }
    }
  }
  return "";
}

// Samples points and compares "inside an island" with the overlap rule applied to the input
// loops' winding numbers: an oracle independent of any polygon library. Points within a few
// units of an edge are skipped (intersection points are rounded to the grid).
inline std::string coverage_problem(const geo::Rings& loops, bool even_odd,
                                    const std::vector<geo::Island>& islands, std::mt19937_64& rng,
                                    int samples) {
  geo::BBox2 box;
  for (const auto& r : loops) {
    for (const auto& p : r) box.add(p);
  }
  if (box.empty()) return "";
  std::uniform_int_distribution<geo::coord_t> ux(box.min_x, box.max_x), uy(box.min_y, box.max_y);
  for (int s = 0; s < samples; ++s) {
    const geo::Point p(2 * ux(rng) + 1, 2 * uy(rng) + 1);
    bool near = false;
    for (const auto& r : loops) near = near || distance_doubled(r, p) < 8;
    for (const auto& is : islands) {
      near = near || distance_doubled(is.shape.outer, p) < 8;
      for (const auto& h : is.shape.holes) near = near || distance_doubled(h, p) < 8;
    }
    if (near) continue;
    int w = 0;
    for (const auto& r : loops) w += winding_doubled(r, p);
    const bool expected = even_odd ? (w % 2 != 0) : w != 0;
    int inside = 0;
    for (const auto& is : islands) {
      bool in = winding_doubled(is.shape.outer, p) != 0;
      for (const auto& h : is.shape.holes) in = in && winding_doubled(h, p) == 0;
      inside += in;
    }
    if (inside > 1) return "islands overlap";
    if ((inside == 1) != expected) {
      return "a sampled point is " +
             std::string(expected ? "material but outside every island" : "empty but inside an island");
    }
  }
  return "";
}

// Shapes for tests, in units (nm); `grid` snaps coordinates to make degenerate cases common.
inline geo::Ring star(std::mt19937_64& rng, double cx, double cy, double r_min, double r_max, int n,
                      geo::coord_t grid = 1) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> angles(n);
  for (auto& a : angles) a = u(rng) * 2 * M_PI;
  std::sort(angles.begin(), angles.end());
  geo::Ring r;
  for (double a : angles) {
    const double rad = r_min + (r_max - r_min) * u(rng);
    auto snap = [&](double v) { return static_cast<geo::coord_t>(std::llround(v / grid)) * grid; };
    r.emplace_back(snap(cx + rad * std::cos(a)), snap(cy + rad * std::sin(a)));
  }
  return r;
}

inline geo::Ring rect(geo::coord_t x0, geo::coord_t y0, geo::coord_t x1, geo::coord_t y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

inline geo::Ring mm_ring(std::initializer_list<std::pair<double, double>> pts) {
  geo::Ring r;
  for (auto [x, y] : pts) r.push_back(geo::to_point(x, y));
  return r;
}

inline geo::Ring reversed(geo::Ring r) {
  std::reverse(r.begin(), r.end());
  return r;
}

}  // namespace tranche::test
