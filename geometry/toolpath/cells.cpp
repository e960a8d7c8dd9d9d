#include "geometry/toolpath/cells.h"

#include <cmath>

#include "geometry/polygon/decompose.h"
#include "geometry/polygon/monotone.h"
#include "geometry/polygon/resolve.h"
#include "geometry/toolpath/clip.h"

namespace tranche::toolpath {

namespace {
constexpr geo::coord_t kOnBorderTol = 20;  // units (20 nm): Clipper rounding of shared edges

std::vector<geo::EdgeKind> label(const geo::Ring& ring, const EdgeGrid& border) {
  std::vector<geo::EdgeKind> kinds(ring.size());
  for (size_t i = 0; i < ring.size(); ++i)
    kinds[i] = border.along(ring[i], ring[(i + 1) % ring.size()], kOnBorderTol) ? geo::EdgeKind::Real
                                                                                : geo::EdgeKind::Artificial;
  return kinds;
}
}  // namespace

namespace {
// The region as polygons with holes from one Clipper union. Strictly simple output (rings that
// touch split at the touching vertex) costs a quadratic pass over each ring's vertices, most of
// the slicing time on fine meshes: it is asked for only when decompose() refused the plain one.
std::vector<geo::Polygon> polygons(const geo::Rings& region, bool strictly_simple) {
  ClipperLib::Clipper clip;
  clip.StrictlySimple(strictly_simple);
  clip.AddPaths(region, ClipperLib::ptSubject, true);
  ClipperLib::PolyTree tree;
  clip.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return geo::to_polygons(tree);
}
}  // namespace

std::vector<CellShape> make_cells(const geo::Rings& region, double angle_deg, const EdgeGrid& fill_border,
                                  Report& report, const std::string& where) {
  std::vector<CellShape> out;
  if (region.empty()) return out;
  // `checked`: every cell is known to be monotone (all_monotone ran on them).
  auto add = [&](std::vector<geo::Cell>& cells, bool checked) {
    for (geo::Cell& cell : cells) {
      CellShape c;
      c.area_mm2 = std::abs(geo::area_mm2(cell.ring));
      c.monotone = checked || geo::is_monotone(cell.ring, angle_deg);
      if (!c.monotone)
        report.warn("cell-not-monotone", where,
                    "a fill cell is not monotone for the fill angle; its zig-zag is split where needed");
      // The decomposition calls every edge of the region Real; only those on the island's fill
      // border are (the others separate solid from sparse fill).
      std::vector<geo::EdgeKind> kinds = label(cell.ring, fill_border);
      for (size_t i = 0; i < kinds.size() && i < cell.edges.size(); ++i)
        if (cell.edges[i] == geo::EdgeKind::Artificial) kinds[i] = geo::EdgeKind::Artificial;
      c.shape.rings.push_back(std::move(cell.ring));
      c.shape.kinds.push_back(std::move(kinds));
      out.push_back(std::move(c));
    }
  };
  auto fallback = [&](const geo::Polygon& poly, const std::string& why) {
    // The polygon itself, filled by as many zig-zag runs as it needs (with travel between).
    report.warn("decompose", where,
                "a fill region could not be cut into cells (" + why +
                    "); it is filled with travel moves between lines");
    CellShape c;
    c.shape.rings.push_back(poly.outer);
    for (const auto& h : poly.holes) c.shape.rings.push_back(h);
    for (const auto& r : c.shape.rings) c.shape.kinds.push_back(label(r, fill_border));
    c.area_mm2 = geo::area_mm2(poly);
    c.monotone = false;
    out.push_back(std::move(c));
  };
  auto all_monotone = [&](const std::vector<geo::Cell>& cells) {
    for (const auto& cell : cells)
      if (!geo::is_monotone(cell.ring, angle_deg)) return false;
    return true;
  };
  for (const geo::Polygon& poly : polygons(region, false)) {
    auto cells = geo::decompose(poly, angle_deg);
    // A plain union may have rings touching along an edge, which decompose() does not always
    // refuse: a cell that is not monotone sends it the strict way too.
    if (cells && all_monotone(*cells)) {
      add(*cells, true);
      continue;
    }
    // Rings touching at a vertex or along an edge: the same region as strict islands (the
    // polygon stage's exact resolution, whose output decompose() takes on every layer), then
    // Clipper's strictly simple output, then the fallback.
    geo::Rings rings{poly.outer};
    rings.insert(rings.end(), poly.holes.begin(), poly.holes.end());
    if (auto islands = geo::strict_islands(rings)) {
      bool all = true;
      std::vector<std::vector<geo::Cell>> parts;
      for (const geo::Island& isl : *islands) {
        auto again = geo::decompose(isl.shape, angle_deg);
        if (!again || !all_monotone(*again)) {
          all = false;
          break;
        }
        parts.push_back(std::move(*again));
      }
      if (all) {
        for (auto& part_cells : parts) add(part_cells, true);
        continue;
      }
    }
    for (const geo::Polygon& part : polygons(rings, true)) {
      auto again = geo::decompose(part, angle_deg);
      if (again)
        add(*again, false);
      else
        fallback(part, again.error().message);
    }
  }
  return out;
}

}  // namespace tranche::toolpath
