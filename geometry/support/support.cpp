#include "geometry/support/support.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/edge_grid.h"
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

bool boxes_meet(const geo::BBox2& a, const geo::BBox2& b) {
  return !(a.max_x < b.min_x || a.min_x > b.max_x || a.max_y < b.min_y || a.min_y > b.max_y);
}

// The rings of `b` as the local booleans ask about them: their boxes, their edges on a grid.
class Reach {
 public:
  explicit Reach(const Rings& b) : b_(b), grid_(b) {
    boxes_.reserve(b.size());
    for (const geo::Ring& r : b) {
      boxes_.push_back(geo::bbox(r));
      for (const geo::Point& p : r) all_.add(p);
    }
  }
  // Whether the area `r` encloses may meet the area a ring of b encloses. No only when it cannot:
  // no edge of r touches an edge of b (exact), r's first vertex lies inside no ring of b, and no
  // ring of b has its first vertex inside r (each ring on its own, so b may be any rings: their
  // non-zero region lies within the areas they enclose). A ring touching b counts as meeting it.
  bool may_meet(const geo::Ring& r) const {
    if (r.empty()) return false;
    const geo::BBox2 rb = geo::bbox(r);
    if (!boxes_meet(rb, all_)) return false;
    bool near = false;
    for (size_t j = 0; j < b_.size(); ++j) {
      if (!boxes_meet(rb, boxes_[j])) continue;
      near = true;
      // r inside ring j, or ring j inside r (when no edges meet, either holds of every vertex).
      if (ClipperLib::PointInPolygon(r[0], b_[j]) != 0 || ClipperLib::PointInPolygon(b_[j][0], r) != 0) return true;
    }
    if (!near) return false;
    if (grid_.box_clear(rb.min_x, rb.min_y, rb.max_x, rb.max_y)) return false;
    for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
      const geo::Point &a = r[j], &c = r[i];
      if (std::max(a.X, c.X) < all_.min_x || std::min(a.X, c.X) > all_.max_x || std::max(a.Y, c.Y) < all_.min_y ||
          std::min(a.Y, c.Y) > all_.max_y)
        continue;
      if (grid_.crosses(a, c)) return true;
    }
    return false;
  }

 private:
  const Rings& b_;
  toolpath::EdgeGrid grid_;
  std::vector<geo::BBox2> boxes_;
  geo::BBox2 all_;
};

}  // namespace

// Why the rings set aside are the boolean's: the rings of a region as a boolean leaves it are
// nested, an outer round each hole and a hole round each island inside it, and whatever meets
// a ring's area meets the area of each ring round it. So the rings handed to Clipper are, round
// any point, the outermost ones of the rings that enclose it; those set aside enclose none of b.
// A point of b then lies in no ring set aside, and Clipper decides it as the plain boolean would;
// a point outside b has the winding of the rings handed over made 0 or 1 and that of the rings
// set aside added: 1 inside the region, 0 outside, as before.
namespace {

// difference_local, and how many rings of `a` it set aside.
Rings difference_local(const Rings& a, const Rings& b, size_t& aside) {
  aside = a.size();
  if (a.empty() || b.empty()) return a;
  const Reach reach(b);
  Rings touched, out;
  for (const geo::Ring& r : a) (reach.may_meet(r) ? touched : out).push_back(r);
  aside = out.size();
  if (touched.empty()) return a;
  Rings cut = toolpath::difference(touched, toolpath::near(b, toolpath::bbox(touched)));
  out.insert(out.end(), std::make_move_iterator(cut.begin()), std::make_move_iterator(cut.end()));
  return out;
}

}  // namespace

Rings difference_local(const Rings& a, const Rings& b) {
  size_t aside = 0;
  return difference_local(a, b, aside);
}

Rings intersection_local(const Rings& a, const Rings& b) {
  if (a.empty() || b.empty()) return {};
  const Reach reach(b);
  Rings touched;
  for (const geo::Ring& r : a)
    if (reach.may_meet(r)) touched.push_back(r);
  if (touched.empty()) return {};
  return toolpath::intersection(touched, toolpath::near(b, toolpath::bbox(touched)));
}

namespace {

// (a ∪ add) − cut, on the rings of `a` that `add` or `cut` may meet; `kept` gets the indices in
// `a` of the rings set aside, which come first in the result, in that order.
Rings column_step(const Rings& a, const Rings& add, const Rings& cut, std::vector<size_t>& kept) {
  kept.clear();
  std::optional<Reach> by_add, by_cut;
  if (!add.empty()) by_add.emplace(add);
  if (!cut.empty()) by_cut.emplace(cut);
  Rings touched = add, out;
  for (size_t i = 0; i < a.size(); ++i) {
    if ((by_add && by_add->may_meet(a[i])) || (by_cut && by_cut->may_meet(a[i]))) {
      touched.push_back(a[i]);
    } else {
      out.push_back(a[i]);
      kept.push_back(i);
    }
  }
  if (touched.empty()) return out;
  // One boolean: the subject's non-zero region (the rings handed over and `add`) less `cut`'s.
  // With no ring of `cut` near, a union (difference() would hand back its subject as it is),
  // unless there is nothing to add: the rings handed over are a region already.
  const Rings near_cut = cut.empty() ? Rings{} : toolpath::near(cut, toolpath::bbox(touched));
  Rings u = !near_cut.empty() ? toolpath::difference(touched, near_cut)
            : add.empty()     ? std::move(touched)
                              : toolpath::union_of(touched);
  out.insert(out.end(), std::make_move_iterator(u.begin()), std::make_move_iterator(u.end()));
  return out;
}

// A ring of the column as print_layer cuts it: started at its lowest vertex and simplified for
// printing; empty when it collapses.
geo::Ring print_ring(const geo::Ring& r) {
  geo::Ring s = toolpath::simplify(canonical({r})[0], kPrintSimplify);
  if (s.size() < 3) s.clear();
  return s;
}

}  // namespace

Rings union_difference_local(const Rings& a, const Rings& add, const Rings& cut) {
  std::vector<size_t> kept;
  return column_step(a, add, cut, kept);
}

Rings union_local(const Rings& a, const Rings& b) {
  if (b.empty()) return a;
  if (a.empty()) return toolpath::union_of(b);
  const Reach reach(b);
  Rings touched = b, out;
  for (const geo::Ring& r : a) (reach.may_meet(r) ? touched : out).push_back(r);
  Rings u = toolpath::union_of(touched);
  out.insert(out.end(), std::make_move_iterator(u.begin()), std::make_move_iterator(u.end()));
  return out;
}

namespace {

// What layer k prints of its column: the part and its gaps cut out, the interface under the
// contacts, the rest sparse. Layers are independent here: run in parallel.
// `simplified`: the column's rings as print_ring leaves them (carried from layer to layer with the
// rings the column's step sets aside); `box`: the column's; `touch`: the contacts placed on this
// layer that touch the layer above (support_z_gap 0).
SupportLayer print_layer(const ProjectInput& in, const std::vector<Rings>& material, size_t k, const Rings& simplified,
                         const geo::BBox2& box, const Rings& iface_src, const Rings& touch) {
  SupportLayer out;
  if (simplified.empty()) return out;
  const Rings& keep = k < in.keep_out.size() && !in.keep_out[k].empty() ? in.keep_out[k] : material[k];
  // The column comes simplified; the gaps are cut after (simplifying there would cut chords into them).
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
    Rings above = part_above(material[k + 1], touch, box);
    cut.insert(cut.end(), std::make_move_iterator(above.begin()), std::make_move_iterator(above.end()));
  }
  // Most of a large column lies away from the part: only its rings the cut reaches go through
  // Clipper. The simplification may have made rings that cross (a neck narrower than twice its
  // tolerance), which only the boolean cleans: then the whole goes through it.
  size_t aside = 0;
  Rings printed = difference_local(simplified, cut, aside);
  if (aside > 0 && !toolpath::is_clean_region(printed)) printed = toolpath::difference(simplified, cut);
  // The contacts of a slope are slivers a reach apart: closed, they make one band of interface.
  Rings iface = iface_src.empty() ? Rings{}
                                  : intersection_local(printed, closing(toolpath::union_of(iface_src), 0.5 * in.merge_mm));
  // No opening here (it was two thirds of this function's time): the toolpaths erode each support
  // island by half a bead before filling it (plan::build_support), which removes every sliver
  // narrower than a bead just as an opening would; only specks are dropped now, so that they do
  // not become islands of their own.
  out.interface = drop_specks(std::move(iface), in.min_width_mm);
  // The interface is cut from a column simplified for printing, its sources are not: grown by a
  // little more than that simplification, it leaves no base sliver along its edge.
  const Rings iface_cut = toolpath::offset_coarse(out.interface, 1.2 * geo::to_mm(kPrintSimplify));
  out.base = drop_specks(support::difference_local(printed, iface_cut), in.min_width_mm);
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
  std::vector<Rings> iface_src(n), columns(n), touch(n);  // columns: as printed (print_ring)
  std::vector<geo::BBox2> boxes(n);
  Rings column;
  std::vector<geo::Ring> print;  // print_ring of each ring of the column
  std::vector<size_t> aside;     // the column's rings its step sets aside
  // Top-down, serial: each layer's column is the one above, plus its contacts, less the part. The
  // column stays on the bed (only a contact that reaches past it is clipped to it), and the
  // contacts and the part reach only the column's rings they meet (union_local,
  // difference_local): the same regions as clipping the whole column at each contact and cutting
  // every ring, with fewer booleans and far fewer vertices through Clipper (print_layer starts
  // each ring at a fixed vertex, so the rings' order and first vertices, which differ, change
  // nothing).
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
    if (!in.columns) column.clear(), print.clear(), fresh = iface_src[k];  // the interface alone, layer by layer
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
    Rings next = column_step(column, fresh, part, aside);
    // Simplified for printing only (done on the column itself, it would erode it layer after
    // layer): each ring once, when a boolean makes it.
    std::vector<geo::Ring> next_print(next.size());
    for (size_t i = 0; i < next.size(); ++i) next_print[i] = i < aside.size() ? std::move(print[aside[i]]) : print_ring(next[i]);
    column = std::move(next);
    print = std::move(next_print);
    boxes[k] = toolpath::bbox(column);
    for (const geo::Ring& r : print)
      if (!r.empty()) columns[k].push_back(r);
  }
  tbb::parallel_for(size_t{0}, n, [&](size_t k) {
    res.layers[k] = print_layer(in, material, k, columns[k], boxes[k], iface_src[k], touch[k]);
  });
  return res;
}

Rings part_above(const Rings& above, const Rings& touch, const geo::BBox2& box) {
  Rings near = toolpath::near(above, box);
  return touch.empty() || near.empty() ? near : toolpath::difference(near, touch);
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
