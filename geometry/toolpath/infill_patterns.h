// Sparse infill patterns other than the zig-zag (infill_pattern): grid, triangles, cubic,
// gyroid, honeycomb and concentric (lightning: geometry/toolpath/lightning.h). Every pattern is laid on a grid fixed to the bed so that its
// lines stand on the lines of the layer below (cubic and gyroid move with z as their 3D cells
// do), clipped to the fill region, and its pieces are joined end to end by links along the
// region's border (zigzag_detail::link_along_border, as the zig-zags' runs are), so that each
// path is as long as the pattern allows. Solid regions never use these: they stay zig-zags.
//
// Density: the length of line per mm² of region is density / spacing (spacing: the distance of
// solid lines, toolpath::bead_spacing_mm), so a pattern extrudes about density × area × height
// of plastic whatever its shape, but for honeycomb and gyroid, which keep PrusaSlicer's meaning of
// the density (honeycomb ρ(4 − ρ)/3 of plastic, 0.253 at 20 %; gyroid 0.951·ρ: plastic_fraction):
//   grid        two sets of lines, at angle and angle + 90°, each 2·spacing/density apart;
//   triangles   three sets at angle, +60°, +120°, each 3·spacing/density apart, all through the
//               nodes of one triangular lattice;
//   cubic       the triangles' three sets, each moved across by z/√2 (sign alternating so that
//               the moves sum to zero): the sections of cubes standing on a corner, edge
//               3·spacing/density·√(2/3);
//   honeycomb   flat-topped hexagons 2·spacing/density between opposite sides (side
//               2·spacing/(√3·density)), drawn as trapezoid waves whose shared flat edges are
//               printed twice, side by side one spacing apart: PrusaSlicer's FillHoneycomb, whose
//               doubled edges lay ρ(4 − ρ)/3 of plastic (about 4/3 × density when sparse, a
//               whole layer at 100 %);
//   gyroid      the section at z of the gyroid sin x cos y + sin y cos z + sin z cos x = 0 with
//               PrusaSlicer's period 2π·spacing/(2.44·density) (its section has 2.45/period of
//               line per mm², averaged over z, from −6 % to +9 % on single layers: 0.951·density
//               of plastic), chords within 50 µm; its lines are joined by links up to 50 mm and
//               free ends anchored 6 widths along the border (PatternSpec::anchor_mm) by the
//               plan (island_content.cpp), as PrusaSlicer's infill_anchor_max / infill_anchor;
//   concentric  loops inside the region's border, spacing/density apart, the first one half a
//               spacing from the border (touching the walls, as PrusaSlicer's), each joined to
//               the next by a short crossing when it stays inside the region.
// The pattern's direction is angle mod 90° (fill_angle: the 45°/135° alternation of the default
// leaves every pattern in place from layer to layer).
#pragma once

#include <vector>

#include "geometry/toolpath/zigzag.h"
#include "runtime/schema/schema.h"

namespace tranche::toolpath {

struct PatternSpec {
  schema::InfillPattern pattern = schema::InfillPattern::Grid;
  double angle_deg = 45;    // direction of the pattern (taken mod 90°)
  double spacing_mm = 0.4;  // distance of solid lines
  double density = 0.2;     // 0 < density < 1
  double z_mm = 0;          // height of the layer's middle (cubic, gyroid)
  // Line ends stop this far short of artificial edges (cuts between the sparse region and a
  // solid one), as the zig-zag's do (FillSpec::artificial_inset_mm).
  double artificial_inset_mm = 0.2;
  double link_max_mm = 0;  // longest link along the border (mm; 0: none)
  // Ends left unlinked run on along the border this far (mm; 0: none), as PrusaSlicer's infill
  // anchors, stopping half a spacing short of the next end, link or anchor.
  double anchor_mm = 0;
};

// The share of a region's area that `pattern` at `density` covers with bead (0 to 1): density,
// but density × (4 − density) / 3 for honeycomb and 0.951 × density for gyroid (see above).
double plastic_fraction(schema::InfillPattern pattern, double density);

// The paths of `pattern` over `shape` (zigzag and lightning: none; see above for the others).
// Each path's area_mm2 is its length times spacing / plastic_fraction(pattern, density).
std::vector<FillPath> pattern_fill(const FillShape& shape, const PatternSpec& spec);

// Open polylines (bed units) clipped to `shape` and joined along its border as the patterns'
// lines are (lightning's branches, geometry/toolpath/lightning.h). Each path's area_mm2 is its
// length times spec.spacing_mm / spec.density.
std::vector<FillPath> clip_fill_lines(const geo::Rings& lines, const FillShape& shape, const PatternSpec& spec);

// The lines of a pattern before clipping, over the box [x0, x1] × [y0, y1] (mm): open polylines
// in bed units. Exposed for tests.
geo::Rings pattern_lines(const PatternSpec& spec, double x0, double y0, double x1, double y1);

}  // namespace tranche::toolpath
