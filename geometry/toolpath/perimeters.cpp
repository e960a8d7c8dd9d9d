#include "geometry/toolpath/perimeters.h"

#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/flow.h"

namespace tranche::toolpath {

Perimeters make_perimeters(const geo::Rings& island, const PerimeterSpec& spec) {
  Perimeters out;
  const double h = spec.height;
  geo::Rings centrelines;  // every loop, for the fill region
  double d = 0, prev_w = 0;
  for (size_t k = 0; k < spec.widths.size(); ++k) {
    double w = spec.widths[k];
    geo::Rings rings;
    if (k == 0) {
      d = 0.5 * w;
      rings = offset(island, -d);
    } else {
      double s = bead_spacing_mm(prev_w, w, h);
      d += s;
      rings = offset_open(island, -d, 0.3 * s);
    }
    if (rings.empty()) break;
    for (auto& r : rings) {
      bool hole = !ClipperLib::Orientation(r);
      centrelines.push_back(r);
      out.loops.push_back({std::move(r), static_cast<int>(k), hole});
    }
    prev_w = w;
  }
  const double fw = spec.fill_width;
  const double fs = bead_spacing_mm(fw, h);
  const double overlap = spec.infill_overlap * fw;
  if (out.loops.empty()) {
    // No loop at all: the fill's own border beads take the outer perimeter's place.
    out.fill_region = offset(island, -0.5 * fw);
    return out;
  }
  // Fill centrelines stay (half a loop bead + half a fill bead − overlap) from every loop.
  double keep_off = 0.5 * bead_spacing_mm(prev_w, h) + 0.5 * fs - overlap;
  geo::Rings blocked = buffer_loops(centrelines, keep_off);
  geo::Rings free = difference(island, blocked);
  // Slivers narrower than a fraction of a bead are not worth a path.
  out.fill_region = offset_open(free, 0, 0.25 * fs);
  return out;
}

}  // namespace tranche::toolpath
