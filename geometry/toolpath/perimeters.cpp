#include "geometry/toolpath/perimeters.h"

#include <algorithm>
#include <cmath>
#include <optional>

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
  // A convex corner sharper than 60°: the loops' corners stop short of its tip (a wedge's by
  // millimetres), which gap fill must reach even when no part collapses.
  bool sharp = false;
  int outlines = 0;
  explicit Steiner(const geo::Rings& rings) {
    for (const auto& ring : rings) {
      outlines += ClipperLib::Orientation(ring) ? 1 : 0;
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
        if (phi > M_PI * 2 / 3) sharp = true;
      }
    }
  }
  double eroded_area(double d) const { return area - perimeter * d + s * d * d; }
  // True when erode(X, d) lost parts: its area exceeds the prediction beyond rounding noise, or
  // it has fewer outlines (a part eroded past its own size, where the quadratic formula turns
  // positive again: a 0.5 × 2 mm bar shrunk by 1 mm is predicted (0.5 − 2)(2 − 2) + ... ≥ 0).
  bool collapsed(const geo::Rings& eroded, double d) const {
    int left = 0;
    for (const auto& r : eroded) left += ClipperLib::Orientation(r) ? 1 : 0;
    if (left < outlines) return true;
    return area_mm2(eroded) - eroded_area(d) > std::max(0.05, 0.002 * perimeter);
  }
};
}  // namespace

namespace {
// Grows a region shrunk by `d + gap` (round joins) back by `gap` with mitred joins: parts where
// the centreline's two sides would come closer than 2·gap have vanished, and the convex corners
// the shrink kept sharp stay sharp (a round grow-back would cut them and leave the corner
// unprinted).
geo::Rings grow_mitred(const geo::Rings& shrunk, double gap) {
  if (shrunk.empty()) return shrunk;
  // Miter limit 2: corners sharper than 60° are squared off 2·gap from the shrunk tip, where the
  // loop's sides are still apart (gap fill reaches the tip).
  ClipperLib::ClipperOffset co(2.0, 5000);
  co.AddPaths(shrunk, ClipperLib::jtMiter, ClipperLib::etClosedPolygon);
  geo::Rings out;
  co.Execute(out, gap * geo::kUnitsPerMm);
  return out;
}

// Beads along the axis of what neither the loops (`centrelines`, each with its width) nor the fill
// region covers.
std::vector<VarBead> gap_beads(const geo::Rings& island, const std::vector<geo::Rings>& centrelines,
                               const std::vector<double>& widths, const geo::Rings& fill_region,
                               const PerimeterSpec& spec) {
  const double h = spec.height;
  // The beads' areas side by side (outers positive): the difference's non-zero clip unites them.
  geo::Rings covered;
  auto add = [&](geo::Rings r) { covered.insert(covered.end(), r.begin(), r.end()); };
  for (size_t k = 0; k < centrelines.size(); ++k)
    if (!centrelines[k].empty()) add(buffer_loops(centrelines[k], 0.5 * bead_spacing_mm(widths[k], h)));
  if (!fill_region.empty()) add(offset(fill_region, 0.5 * bead_spacing_mm(spec.fill_width, h)));
  geo::Rings gaps = uncovered(island, covered, spec.min_bead_width);
  if (gaps.empty()) return {};
  BeadSpec bs;
  bs.min_width = spec.min_bead_width;
  bs.max_width = spec.max_bead_width;
  bs.height = h;
  bs.max_beads = spec.mode == WallMode::Variable ? 8 : 1;
  return axis_beads(gaps, bs);
}
}  // namespace

Perimeters make_perimeters(const geo::Rings& island, const PerimeterSpec& spec, const geo::Rings* wall_outline) {
  Perimeters out;
  const double h = spec.height;
  const size_t count = spec.widths.size();
  const double fw = spec.fill_width;
  const double fs = bead_spacing_mm(fw, h);
  const double overlap = spec.infill_overlap * fw;
  const bool variable = spec.mode == WallMode::Variable;
  if (count == 0) {
    // No loop at all: the fill's own border beads take the outer perimeter's place.
    out.fill_region = offset(island, -0.5 * fw);
    return out;
  }
  // Centreline distances from the outline: d_0 = w_0/2, d_k = d_{k-1} + spacing.
  std::vector<double> dist(count), gap(count);
  for (size_t k = 0; k < count; ++k)
    dist[k] =
        k == 0 ? 0.5 * spec.widths[0] : dist[k - 1] + bead_spacing_mm(spec.widths[k - 1], spec.widths[k], h);
  // How far each loop is opened (see perimeters.h): classic, loop 0 by half a spacing (its sides
  // stay a spacing apart), the others by 0.3·spacing; variable, every loop so that it survives
  // only where the innermost one has a spacing between its sides.
  const double last_s = bead_spacing_mm(spec.widths.back(), h);
  for (size_t k = 0; k < count; ++k) {
    if (variable)
      gap[k] = dist.back() - dist[k] + 0.5 * last_s;
    else
      gap[k] = k == 0 ? 0.5 * bead_spacing_mm(spec.widths[0], h)
                      : 0.3 * bead_spacing_mm(spec.widths[k - 1], spec.widths[k], h);
  }
  // Fill centrelines stay (half a loop bead + half a fill bead − overlap) from the last loop.
  const double keep_off = 0.5 * last_s + 0.5 * fs - overlap;
  const Steiner steiner(island);
  // Fast path: when even the fill region's offset loses no part of the island, every loop is
  // whole and none needs opening: one offset per loop plus one for the fill.
  geo::Rings fill = offset(island, -(dist.back() + keep_off));
  bool thin = steiner.collapsed(fill, dist.back() + keep_off) || steiner.sharp;
  bool vanished = false;  // a loop that fits only in part of the island leaves a gap
  geo::Rings centrelines;
  std::vector<geo::Rings> by_depth(count);
  for (size_t k = 0; k < count; ++k) {
    geo::Rings rings;
    const geo::Rings& from = k == 0 && wall_outline ? *wall_outline : island;
    if (!thin) {
      rings = offset(from, -dist[k]);
    } else {
      // Opened: where a part is too thin for the loop's two sides to stay 2·gap apart, the loop
      // is dropped instead of printed as overlapping beads.
      geo::Rings shrunk = offset(from, -(dist[k] + gap[k]));
      // The prediction from the rings shrunk (the wall outline's area exceeds the island's).
      std::optional<Steiner> own;
      if (&from != &island) own.emplace(from);
      if ((own ? *own : steiner).collapsed(shrunk, dist[k] + gap[k])) vanished = true;
      // Loop 0 keeps its corners (mitred grow-back); inner loops are rounded (they face the fill).
      rings = k == 0 || variable ? grow_mitred(shrunk, gap[k]) : offset(shrunk, gap[k]);
    }
    if (rings.empty()) {
      vanished = true;
      break;
    }
    for (auto& r : rings) {
      bool hole = !ClipperLib::Orientation(r);
      centrelines.push_back(r);
      by_depth[k].push_back(r);
      out.loops.push_back({std::move(r), static_cast<int>(k), hole});
    }
  }
  if (!thin) {
    out.fill_region = std::move(fill);
    return out;
  }
  // Some loop vanished in thin parts: fill what no bead covers, gaps wider than two fill beads
  // included; the narrower ones (and the parts too thin for any loop, and sharp corners' tips)
  // get beads along their axis.
  if (!vanished) {
    out.fill_region = std::move(fill);
  } else if (!out.loops.empty()) {
    double last_w = spec.widths[static_cast<size_t>(out.loops.back().depth)];
    geo::Rings blocked = buffer_loops(centrelines, 0.5 * bead_spacing_mm(last_w, h) + 0.5 * fs - overlap);
    // Where even loop 0 vanished the fill keeps off the outline as if it were there: that part
    // is a thin wall, for beads along its axis.
    geo::Rings inside = offset(island, -(dist[0] + 0.5 * bead_spacing_mm(spec.widths[0], h) + 0.5 * fs - overlap));
    // Variable walls: parts of the fill narrower than two fill beads go to the beads too (their
    // count follows the width; sparse fill would leave such a strip nearly empty).
    out.fill_region = offset_open(difference(inside, blocked), 0, (variable ? 1.0 : 0.5) * fs);
  }
  // The gaps reach the outline the outer loop follows (a thin part's beads fill it as it is).
  out.beads = gap_beads(wall_outline ? *wall_outline : island, by_depth, spec.widths, out.fill_region, spec);
  return out;
}

}  // namespace tranche::toolpath
