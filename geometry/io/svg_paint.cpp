#include "geometry/io/svg_paint.h"

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

}  // namespace

Polygons resolve_shapes(const std::vector<Shape>& shapes, SvgOverlap mode, Rgb background) {
  Rings acc;
  if (mode == SvgOverlap::Subtractive) {
    // Runs of adding shapes are merged in one union; each erasing run is one difference.
    size_t i = 0;
    while (i < shapes.size()) {
      bool erase = erases(shapes[i], mode, background);
      Rings run;
      for (; i < shapes.size() && erases(shapes[i], mode, background) == erase; ++i) {
        Rings r = shape_region(shapes[i]);
        run.insert(run.end(), r.begin(), r.end());
      }
      acc = boolean_op(erase ? ClipperLib::ctDifference : ClipperLib::ctUnion, acc, run);
    }
  } else {
    // Each region's rings are nested without overlap, so even-odd over all of them counts, at
    // every point, the parity of the number of shapes covering it.
    for (const Shape& s : shapes) {
      Rings r = shape_region(s);
      acc.insert(acc.end(), r.begin(), r.end());
    }
  }
  Clipper c;
  c.PreserveCollinear(true);
  c.AddPaths(acc, ClipperLib::ptSubject, true);
  ClipperLib::PolyTree tree;
  auto rule = mode == SvgOverlap::Boolean ? ClipperLib::pftEvenOdd : ClipperLib::pftNonZero;
  c.Execute(ClipperLib::ctUnion, tree, rule, rule);
  return to_polygons(tree);
}

}  // namespace tranche::geo::svg
