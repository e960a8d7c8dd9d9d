#include "geometry/core/geom.h"

namespace tranche::geo {

double area_mm2(const Ring& ring) { return ClipperLib::Area(ring) * kMmPerUnit * kMmPerUnit; }

double area_mm2(const Polygon& poly) {
  double a = std::abs(area_mm2(poly.outer));
  for (const auto& h : poly.holes) a -= std::abs(area_mm2(h));
  return a;
}

double area_mm2(const Polygons& polys) {
  double a = 0;
  for (const auto& p : polys) a += area_mm2(p);
  return a;
}

double length_mm(const Ring& ring) {
  double len = 0;
  for (size_t i = 0, n = ring.size(); i < n; ++i) {
    const Point& a = ring[i];
    const Point& b = ring[(i + 1) % n];
    len += std::hypot(static_cast<double>(b.X - a.X), static_cast<double>(b.Y - a.Y));
  }
  return len * kMmPerUnit;
}

BBox2 bbox(const Ring& ring) {
  BBox2 b;
  for (const auto& p : ring) b.add(p);
  return b;
}

BBox2 bbox(const Polygon& poly) { return bbox(poly.outer); }

Rings to_rings(const Polygons& polys) {
  Rings out;
  for (const auto& p : polys) {
    out.push_back(p.outer);
    for (const auto& h : p.holes) out.push_back(h);
  }
  return out;
}

namespace {
void collect(const ClipperLib::PolyNode& node, Polygons& out) {
  for (const ClipperLib::PolyNode* outer : node.Childs) {
    Polygon poly;
    poly.outer = outer->Contour;
    if (!ClipperLib::Orientation(poly.outer)) ClipperLib::ReversePath(poly.outer);
    for (const ClipperLib::PolyNode* hole : outer->Childs) {
      Ring h = hole->Contour;
      if (ClipperLib::Orientation(h)) ClipperLib::ReversePath(h);
      poly.holes.push_back(std::move(h));
      collect(*hole, out);  // islands inside this hole
    }
    out.push_back(std::move(poly));
  }
}
}  // namespace

Polygons to_polygons(const ClipperLib::PolyTree& tree) {
  Polygons out;
  collect(tree, out);
  return out;
}

}  // namespace tranche::geo
