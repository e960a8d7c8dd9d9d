#include "geometry/io/svg_paint.h"

#include <algorithm>

namespace tranche::geo::svg {

namespace {

using ClipperLib::Clipper;

// The region a shape fills on its own, under its fill rule: non-overlapping rings, outers CCW.
Rings shape_region(const Shape& s) {
  Clipper c;
  c.PreserveCollinear(true);  // keep the drawing's vertices: a layer stack reads back exactly
  c.AddPaths(s.rings, ClipperLib::ptSubject, true);
  Rings out;
  auto rule = s.evenodd ? ClipperLib::pftEvenOdd : ClipperLib::pftNonZero;
  c.Execute(ClipperLib::ctUnion, out, rule, rule);
  return out;
}

Rings boolean_op(ClipperLib::ClipType op, const Rings& a, const Rings& b) {
  Clipper c;
  c.PreserveCollinear(true);
  c.AddPaths(a, ClipperLib::ptSubject, true);
  c.AddPaths(b, ClipperLib::ptClip, true);
  Rings out;
  c.Execute(op, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return out;
}

bool erases(const Shape& s, SvgOverlap mode, Rgb background) {
  return mode == SvgOverlap::Subtractive && s.fill.kind == Paint::Kind::Color && s.fill.rgb == background;
}

struct Region {
  Rings rings;     // non-overlapping, outers CCW
  coord_t cx = 0;  // bounding box centre x, for the spatial split
  size_t points = 0;
};

Region region_of(const Shape& s) {
  Region r;
  r.rings = shape_region(s);
  BBox2 b;
  for (const Ring& ring : r.rings) {
    for (const Point& p : ring) b.add(p);
    r.points += ring.size();
  }
  r.cx = b.empty() ? 0 : b.min_x / 2 + b.max_x / 2;
  return r;
}

constexpr size_t kLeafPoints = 20'000;

// Combines regions under `rule`: nonzero gives their union, even-odd the parity of the number of
// regions covering each point (each region's own rings never overlap). Large inputs go by halves
// of regions sorted by x: Clipper's sweep costs grow with the edges crossing each scanline, and
// halves in x cross fewer (10 000 scattered discs: 4.2 s in one union, see docs/svg-input.md).
Rings combine(std::vector<Region>::const_iterator first, std::vector<Region>::const_iterator last,
              ClipperLib::PolyFillType rule) {
  size_t points = 0;
  for (auto it = first; it != last; ++it) points += it->points;
  Clipper c;
  c.PreserveCollinear(true);
  if (last - first <= 1 || points <= kLeafPoints) {
    for (auto it = first; it != last; ++it) c.AddPaths(it->rings, ClipperLib::ptSubject, true);
  } else {
    auto mid = first + (last - first) / 2;
    c.AddPaths(combine(first, mid, rule), ClipperLib::ptSubject, true);
    c.AddPaths(combine(mid, last, rule), ClipperLib::ptSubject, true);
  }
  Rings out;
  c.Execute(ClipperLib::ctUnion, out, rule, rule);
  return out;
}

Rings combine(std::vector<Region> regions, ClipperLib::PolyFillType rule) {
  std::stable_sort(regions.begin(), regions.end(),
                   [](const Region& a, const Region& b) { return a.cx < b.cx; });
  return combine(regions.cbegin(), regions.cend(), rule);
}

}  // namespace

Polygons resolve_shapes(const std::vector<Shape>& shapes, SvgOverlap mode, Rgb background) {
  Rings acc;
  if (mode == SvgOverlap::Subtractive) {
    // Each run of adding shapes is one union, each run of erasing shapes one difference.
    size_t i = 0;
    while (i < shapes.size()) {
      bool erase = erases(shapes[i], mode, background);
      std::vector<Region> run;
      for (; i < shapes.size() && erases(shapes[i], mode, background) == erase; ++i)
        run.push_back(region_of(shapes[i]));
      acc = boolean_op(erase ? ClipperLib::ctDifference : ClipperLib::ctUnion, acc,
                       combine(std::move(run), ClipperLib::pftNonZero));
    }
  } else {
    std::vector<Region> regions;
    regions.reserve(shapes.size());
    for (const Shape& s : shapes) regions.push_back(region_of(s));
    acc = combine(std::move(regions),
                  mode == SvgOverlap::Boolean ? ClipperLib::pftEvenOdd : ClipperLib::pftNonZero);
  }
  // acc is non-overlapping now: one more pass only builds the tree of outers and holes.
  Clipper c;
  c.PreserveCollinear(true);
  c.AddPaths(acc, ClipperLib::ptSubject, true);
  ClipperLib::PolyTree tree;
  c.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return to_polygons(tree);
}

}  // namespace tranche::geo::svg
