#include "geometry/support/support.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/relations.h"

namespace tranche::support {

using geo::Rings;

namespace {

constexpr geo::coord_t kSimplify = 12500;     // 12.5 µm, the islands' own resolution: the columns
constexpr geo::coord_t kPrintSimplify = 50000;  // 50 µm: what support prints (a bead is 450 µm)

Rings closing(const Rings& r, double mm) {
  return mm > 0 ? toolpath::offset_coarse(toolpath::offset_coarse(r, mm), -mm) : r;
}

// `r` without its rings of less than a bead's square: outlines no bead fits in, and holes too small
// to matter (the part's own holes in support are at least its xy gap across, twice; a hole in a
// dropped outline is smaller still, and must go with it).
Rings drop_specks(Rings r, double bead_mm) {
  const double min_area = bead_mm * bead_mm * geo::kUnitsPerMm * geo::kUnitsPerMm;
  std::erase_if(r, [&](const geo::Ring& ring) { return std::abs(ClipperLib::Area(ring)) < min_area; });
  return r;
}

// Each ring started at its lowest vertex (least y, then x): simplify() keeps a ring's first
// vertex, so the same outline simplifies the same whichever boolean last wrote it.
Rings canonical(Rings r) {
  for (geo::Ring& ring : r) {
    auto low = std::min_element(ring.begin(), ring.end(), [](const geo::Point& a, const geo::Point& b) {
      return a.Y != b.Y ? a.Y < b.Y : a.X < b.X;
    });
    std::rotate(ring.begin(), low, ring.end());
  }
  return r;
}

// Union of the part below each layer (0..k), for bed-only contacts: computed only when one asks.
std::vector<Rings> footprints(std::span<const geo::Layer> layers) {
  std::vector<Rings> out(layers.size());
  Rings acc;
  for (size_t k = 0; k < layers.size(); ++k) {
    acc = toolpath::simplify(toolpath::union_of(acc, toolpath::material(layers[k])), kSimplify);
    out[k] = acc;
  }
  return out;
}

// a − b, Clipper run only on the rings of `a` whose box meets the box of a ring of `b`: a ring
// whose box meets none of them lies outside b and crosses none of its rings, so the difference
// would give it back as it is. `a` must be a boolean's result (rings that do not cross, under
// non-zero fill): a hole that meets nothing of b stays aside even when its outer is cut, and
// still cancels that outer inside it (what b cuts lies outside the hole's box).
Rings difference_near(const Rings& a, const Rings& b) {
  if (a.empty() || b.empty()) return a;
  std::vector<geo::BBox2> boxes;
  boxes.reserve(b.size());
  for (const geo::Ring& r : b) boxes.push_back(geo::bbox(r));
  Rings touched, out;
  for (const geo::Ring& r : a) {
    const geo::BBox2 ra = geo::bbox(r);
    const bool meets = std::any_of(boxes.begin(), boxes.end(), [&](const geo::BBox2& x) {
      return !(x.max_x < ra.min_x || x.min_x > ra.max_x || x.max_y < ra.min_y || x.min_y > ra.max_y);
    });
    (meets ? touched : out).push_back(r);
  }
  if (touched.empty()) return a;
  Rings cut = toolpath::difference(touched, b);
  out.insert(out.end(), std::make_move_iterator(cut.begin()), std::make_move_iterator(cut.end()));
  return out;
}

// Whether `box` lies inside `bed` when that is one convex ring (bed_region's rectangle or
// circle): its four corners do. false when unsure (then the caller clips).
bool within_convex(const Rings& bed, const geo::BBox2& box) {
  if (bed.size() != 1 || bed[0].size() < 3 || box.empty()) return false;
  const geo::Ring& r = bed[0];
  const double sign = ClipperLib::Area(r) > 0 ? 1.0 : -1.0;
  for (geo::coord_t x : {box.min_x, box.max_x})
    for (geo::coord_t y : {box.min_y, box.max_y})
      for (size_t i = 0; i < r.size(); ++i) {
        const geo::Point& a = r[i];
        const geo::Point& b = r[(i + 1) % r.size()];
        const double cross = static_cast<double>(b.X - a.X) * static_cast<double>(y - a.Y) -
                             static_cast<double>(b.Y - a.Y) * static_cast<double>(x - a.X);
        if (sign * cross < 0) return false;
      }
  return true;
}

}  // namespace

namespace {

// What layer k prints of its column: the part and its gaps cut out, the interface under the
// contacts, the rest sparse. Layers are independent here: run in parallel.
SupportLayer print_layer(const ProjectInput& in, const std::vector<Rings>& material, size_t k, const Rings& column,
                         const Rings& iface_src, const Rings& touch) {
  SupportLayer out;
  if (column.empty()) return out;
  const geo::BBox2 box = toolpath::bbox(column);
  const Rings& keep = k < in.keep_out.size() && !in.keep_out[k].empty() ? in.keep_out[k] : material[k];
  // Simplified for printing only: done on the column itself, it would erode it layer after layer.
  // (The gaps are cut after: simplifying there would cut chords into them.)
  // One boolean cuts the keep-out and the part below (the bottom gap): its clip rings' union
  // under non-zero fill.
  Rings cut = toolpath::near(keep, box);
  for (int g = 1; g <= in.bottom_gap_layers && static_cast<int>(k) - g >= 0; ++g) {
    Rings below = toolpath::near(material[k - static_cast<size_t>(g)], box);
    cut.insert(cut.end(), std::make_move_iterator(below.begin()), std::make_move_iterator(below.end()));
  }
  // Nor under the part of the layer right above (the top gap): a column comes down round a speck
  // of the part too small to be an overhang of its own, or under the edge of a slope's next layer
  // (a contact reaches a little inside its island). Only a contact that asks to touch (z gap 0)
  // lies under the part above it.
  if (k + 1 < material.size()) {
    Rings above = toolpath::near(material[k + 1], box);
    if (!touch.empty() && !above.empty()) above = toolpath::difference(above, touch);
    cut.insert(cut.end(), std::make_move_iterator(above.begin()), std::make_move_iterator(above.end()));
  }
  Rings printed = toolpath::difference(toolpath::simplify(canonical(column), kPrintSimplify), cut);
  // The contacts of a slope are slivers a reach apart: closed, they make one band of interface.
  Rings iface = iface_src.empty() ? Rings{}
                                  : toolpath::intersection(printed, closing(toolpath::union_of(iface_src), 0.5 * in.merge_mm));
  // No opening here (it was two thirds of this function's time): the toolpaths erode each support
  // island by half a bead before filling it (plan::build_support), which removes every sliver
  // narrower than a bead just as an opening would; only specks are dropped now, so that they do
  // not become islands of their own.
  out.interface = drop_specks(std::move(iface), in.min_width_mm);
  // The interface is cut from a column simplified for printing, its sources are not: grown by a
  // little more than that simplification, it leaves no base sliver along its edge.
  const Rings iface_cut = toolpath::offset_coarse(out.interface, 1.2 * geo::to_mm(kPrintSimplify));
  out.base = drop_specks(toolpath::difference(printed, iface_cut), in.min_width_mm);
  out.area_mm2 = toolpath::area_mm2(out.base) + toolpath::area_mm2(out.interface);
  return out;
}

}  // namespace

ProjectResult project(const ProjectInput& in) {
  const size_t n = in.layers.size();
  std::vector<Rings> material(n);  // each layer's, computed once
  tbb::parallel_for(size_t{0}, n, [&](size_t k) { material[k] = toolpath::material(in.layers[k]); });
  ProjectResult res;
  res.layers.resize(n);
  const bool any_bed_only = std::any_of(in.contacts.begin(), in.contacts.end(), [](const auto& cs) {
    return std::any_of(cs.begin(), cs.end(), [](const Contact& c) { return c.bed_only; });
  });
  const std::vector<Rings> foot = any_bed_only ? footprints(in.layers) : std::vector<Rings>{};
  std::vector<Rings> iface_src(n), columns(n), touch(n);
  Rings column;
  // Top-down, serial: each layer's column is the one above, plus its contacts, less the part. The
  // column stays on the bed (only a contact that reaches past it is clipped to it), and the part
  // is cut only from the column's rings near it: the same regions as clipping the whole column
  // at each contact and cutting every ring, with fewer booleans (print_layer starts each ring at
  // a fixed vertex, so the rings' order and first vertices, which differ, change nothing).
  for (size_t k = n; k-- > 0;) {
    Rings fresh;  // this layer's contacts
    if (k < in.contacts.size())
      for (const Contact& c : in.contacts[k]) {
        Rings r = toolpath::simplify(c.region, kSimplify);  // once: slope slivers carry arcs of the reach
        if (c.bed_only) {
          Rings kept = toolpath::difference(r, foot[k]);
          res.blocked_mm2 += std::max(0.0, toolpath::area_mm2(r) - toolpath::area_mm2(kept));
          r = std::move(kept);
        }
        if (r.empty()) continue;
        if (c.touching) touch[k].insert(touch[k].end(), r.begin(), r.end());
        if (in.columns) fresh.insert(fresh.end(), r.begin(), r.end());
        for (int j = 0; j < c.interface_layers && static_cast<int>(k) - j >= 0; ++j)
          iface_src[k - static_cast<size_t>(j)].insert(iface_src[k - static_cast<size_t>(j)].end(), r.begin(), r.end());
      }
    if (!in.columns) column.clear(), fresh = iface_src[k];  // the interface alone, layer by layer
    if (column.empty() && fresh.empty()) continue;
    geo::BBox2 box = toolpath::bbox(column);
    for (const geo::Ring& r : fresh)
      for (const geo::Point& p : r) box.add(p);
    const Rings part = toolpath::near(material[k], box);
    if (!fresh.empty() && !in.bed.empty() && !within_convex(in.bed, toolpath::bbox(fresh))) {
      // What reaches past the bed, less the part, is left out and said.
      Rings all = toolpath::union_of(fresh);
      Rings off = toolpath::difference(toolpath::difference(all, in.bed), part);
      res.off_bed_mm2 += toolpath::area_mm2(off);
      fresh = toolpath::intersection(all, in.bed);
    }
    if (fresh.empty()) {
      column = difference_near(column, part);
    } else {
      column.insert(column.end(), std::make_move_iterator(fresh.begin()), std::make_move_iterator(fresh.end()));
      column = difference_near(toolpath::union_of(column), part);
    }
    columns[k] = column;
  }
  tbb::parallel_for(size_t{0}, n, [&](size_t k) { res.layers[k] = print_layer(in, material, k, columns[k], iface_src[k], touch[k]); });
  return res;
}

Rings bed_region(bool circular, double min_x, double min_y, double max_x, double max_y, const geo::Point& shift) {
  geo::Ring r;
  if (!circular) {
    for (auto [x, y] : {std::pair{min_x, min_y}, {max_x, min_y}, {max_x, max_y}, {min_x, max_y}})
      r.push_back(geo::Point(geo::to_units(x) - shift.X, geo::to_units(y) - shift.Y));
  } else {
    const double cx = 0.5 * (min_x + max_x), cy = 0.5 * (min_y + max_y), rad = 0.5 * (max_x - min_x);
    for (int i = 0; i < 256; ++i) {
      const double a = 2 * std::numbers::pi * i / 256;  // inscribed: never past the real bed
      r.push_back(geo::Point(geo::to_units(cx + rad * std::cos(a)) - shift.X, geo::to_units(cy + rad * std::sin(a)) - shift.Y));
    }
  }
  return {r};
}

}  // namespace tranche::support
