#include "geometry/toolpath/perimeters.h"

#include <algorithm>
#include <cmath>

#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/flow.h"

namespace tranche::toolpath {

namespace {
// Steiner's formula for shrinking a polygon with round joins: as long as no part of it collapses,
// erode(X, d) has area A − P·d + S·d², S = Σ tan(φ/2) over convex turns φ − Σ |φ|/2 over reflex
// ones. A part too thin for the erosion vanishes and leaves the real area above this prediction,
// which detects thin parts without another polygon operation.
struct Steiner {
  double area = 0, perimeter = 0, s = 0;
  explicit Steiner(const geo::Rings& rings) {
    for (const auto& ring : rings) {
      area += geo::area_mm2(ring);
      perimeter += geo::length_mm(ring);
      size_t n = ring.size();
      for (size_t i = 0; i < n; ++i) {
        const auto& a = ring[(i + n - 1) % n];
        const auto& b = ring[i];
        const auto& c = ring[(i + 1) % n];
        double ux = double(b.X - a.X), uy = double(b.Y - a.Y), vx = double(c.X - b.X), vy = double(c.Y - b.Y);
        double phi = std::atan2(ux * vy - uy * vx, ux * vx + uy * vy);  // > 0: convex (material on the left)
        s += phi > 0 ? std::tan(std::min(phi, 3.0) / 2) : phi / 2;
      }
    }
  }
  double eroded_area(double d) const { return area - perimeter * d + s * d * d; }
  // True when erode(X, d) lost parts: its area exceeds the prediction beyond rounding noise.
  bool collapsed(const geo::Rings& eroded, double d) const {
    return area_mm2(eroded) - eroded_area(d) > std::max(0.05, 0.002 * perimeter);
  }
};
}  // namespace

namespace {
// An island thinner than one bead: a single loop around its core (the island shrunk by a
// quarter bead, or the island itself when that leaves nothing), its flow scaled so that the
// plastic laid equals the island's area times the layer height. Parts narrower than the
// minimum feature (a cone's tip, an ear's last layer) are dropped: a loop of nozzle-wide beads
// around them would put most of its plastic outside the part.
Perimeters& thin_wall(const geo::Rings& whole, const PerimeterSpec& spec, Perimeters& out) {
  double w = spec.widths.front();
  geo::Rings island = spec.min_feature > 0 ? offset_open(whole, 0, 0.5 * spec.min_feature) : whole;
  if (island.empty()) return out;
  geo::Rings core = offset(island, -0.25 * w);
  if (core.empty()) core = island;
  double len = 0;
  for (const auto& r : core) len += geo::length_mm(r);
  double area = area_mm2(island);
  if (len <= 0 || area <= 0) return out;
  double scale = std::clamp(area / (len * bead_spacing_mm(w, spec.height)), 0.05, 1.0);
  for (auto& r : core) {
    bool hole = !ClipperLib::Orientation(r);
    out.loops.push_back({std::move(r), 0, hole, scale});
  }
  return out;
}
}  // namespace

Perimeters make_perimeters(const geo::Rings& island, const PerimeterSpec& spec) {
  Perimeters out;
  const double h = spec.height;
  const size_t count = spec.widths.size();
  const double fw = spec.fill_width;
  const double fs = bead_spacing_mm(fw, h);
  const double overlap = spec.infill_overlap * fw;
  if (count == 0) {
    // No loop at all: the fill's own border beads take the outer perimeter's place.
    out.fill_region = offset(island, -0.5 * fw);
    return out;
  }
  // Centreline distances from the outline: d_0 = w_0/2, d_k = d_{k-1} + spacing.
  std::vector<double> dist(count), gap(count);
  for (size_t k = 0; k < count; ++k) {
    dist[k] =
        k == 0 ? 0.5 * spec.widths[0] : dist[k - 1] + bead_spacing_mm(spec.widths[k - 1], spec.widths[k], h);
    gap[k] = k == 0 ? 0.0 : 0.3 * bead_spacing_mm(spec.widths[k - 1], spec.widths[k], h);
  }
  // Fill centrelines stay (half a loop bead + half a fill bead − overlap) from the last loop.
  const double keep_off = 0.5 * bead_spacing_mm(spec.widths.back(), h) + 0.5 * fs - overlap;
  const Steiner steiner(island);
  // Fast path: when even the fill region's offset loses no part of the island, every loop is
  // whole and none needs opening: one offset per loop plus one for the fill.
  geo::Rings fill = offset(island, -(dist.back() + keep_off));
  bool thin = steiner.collapsed(fill, dist.back() + keep_off);
  bool vanished = false;  // a loop that fits only in part of the island leaves a gap
  geo::Rings centrelines;
  for (size_t k = 0; k < count; ++k) {
    geo::Rings rings;
    if (k == 0 || !thin) {
      rings = offset(island, -dist[k]);
    } else {
      // Opened: shrunk by 0.3·spacing more and grown back, so that where a part is too thin
      // for the loop's two sides to stay 0.6·spacing apart, the loop is dropped instead of
      // printed as overlapping beads.
      geo::Rings shrunk = offset(island, -(dist[k] + gap[k]));
      if (steiner.collapsed(shrunk, dist[k] + gap[k])) vanished = true;
      rings = offset(shrunk, gap[k]);
    }
    if (rings.empty() && k == 0) return thin_wall(island, spec, out);
    if (rings.empty()) {
      vanished = true;
      break;
    }
    for (auto& r : rings) {
      bool hole = !ClipperLib::Orientation(r);
      centrelines.push_back(r);
      out.loops.push_back({std::move(r), static_cast<int>(k), hole});
    }
  }
  if (!vanished) {
    out.fill_region = std::move(fill);
    return out;
  }
  // Some loop vanished in thin parts: fill what no bead covers, gaps included, dropping
  // slivers narrower than a fraction of a bead.
  double last_w = spec.widths[static_cast<size_t>(out.loops.back().depth)];
  geo::Rings blocked = buffer_loops(centrelines, 0.5 * bead_spacing_mm(last_w, h) + 0.5 * fs - overlap);
  out.fill_region = offset_open(difference(island, blocked), 0, 0.25 * fs);
  return out;
}

}  // namespace tranche::toolpath
