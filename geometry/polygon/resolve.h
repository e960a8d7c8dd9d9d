// Overlap resolution and strictly connected islands (seed section 3): from the closed loops of
// one layer to islands, each a region whose interior is connected, with its holes.
//
//   additive  union of the shells: a point is material when it lies inside any loop (nonzero)
//   boolean   overlaps cancel: material where an odd number of loops cover it (even-odd)
//   (subtractive colours are built on top: paint() below, then resolve the result as additive)
//
// Strict connectivity: regions touching only at a point are separate islands (two cubes touching
// along an edge give two islands per layer); zero-width spikes and zero-area pieces vanish. The
// rings of the result are simple and meet each other only at shared vertices.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "geometry/core/layer.h"
#include "base/report.h"
#include "base/result.h"

namespace tranche::geo {

enum class OverlapMode : uint8_t { Additive, Boolean };

struct ResolveOptions {
  OverlapMode overlap = OverlapMode::Additive;
  bool strict = false;   // the first coherence problem is an Error instead of a warning
  int layer_index = -1;  // named in messages ("layer 7 at (3.20, 4.10) mm"); -1: no layer
};

// Coherence check of sliced loops. Warning codes (each with the layer and a position in mm):
//   degenerate-loop     fewer than 3 distinct points or no area: the loop is ignored
//   loop-spike          a loop runs back over itself (zero-width spike): the spike is removed
//   intersecting-loops  edges cross (one warning per layer, with the count)
//   repaired-loop       the slicer closed the loop by joining a gap (flag from `repaired`)
// `repaired[i]` != 0 flags loop i (may be shorter than `loops`). Strict: the first problem is
// returned as an Error and nothing is reported.
Status check_loops(const Rings& loops, const ResolveOptions& options, Report& report,
                   std::span<const uint8_t> repaired = {});

// check_loops, then the overlap mode, then strict islands, in a canonical form: no vertex where
// a ring runs straight on (unless another ring of the island meets it there), every ring starting
// at its lowest then leftmost vertex, holes and islands sorted by that vertex; area_mm2 set,
// cells left empty. Errors: strict
// mode problems, coordinates beyond ±2147 mm.
Result<std::vector<Island>> resolve_islands(const Rings& loops, const ResolveOptions& options, Report& report,
                                            std::span<const uint8_t> repaired = {});

// Strict islands of rings that already describe material by the nonzero rule (outers CCW, holes
// CW), e.g. a Clipper result; no coherence warnings. Errors as resolve_islands.
Result<std::vector<Island>> strict_islands(const Rings& rings, OverlapMode mode = OverlapMode::Additive);

// Fills layer.islands from layer.loops.
Status resolve_layer(Layer& layer, const ResolveOptions& options, Report& report,
                     std::span<const uint8_t> repaired = {});

// Subtractive colours (SVG): shapes in paint order, each added to what is below it, or erasing it
// when `erase` (painted in the background colour). Returns the painted region as rings (outers
// CCW, holes CW), ready for resolve_islands with OverlapMode::Additive.
struct PaintedShape {
  Rings loops;
  bool erase = false;
  bool even_odd = false;  // the shape's own fill rule (SVG fill-rule="evenodd")
};
Result<Rings> paint(std::span<const PaintedShape> shapes);

}  // namespace tranche::geo
