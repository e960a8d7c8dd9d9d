// Overhanging walls as bridges (overhang_walls = bridge, docs/gcode.md "Overhanging walls"):
// where an island's wall band lies over air wider than a bead, its wall loops would run round in
// the air there, held only where they pass over the layer below, and droop along the whole
// overhanging edge. Instead, that part of the island (its wall band and the fill over air next
// to it) is filled with straight bridge lines in the direction whose lines are best anchored on
// the layer below, and the walls are kept only where they rest on it. Pure geometry: whether to
// do it is the island's `overhang_walls` property (geometry/plan/island_content.cpp).
#pragma once

#include <vector>

#include "geometry/core/geom.h"

namespace tranche::toolpath {

// How far the bridge region reaches from the air into the island over the layer below, so that
// its lines start on material (PrusaSlicer's bridges reach into their anchors likewise).
inline constexpr double kBridgeAnchorMm = 1.5;
// Air nowhere this wide is left to the walls: the crescent a curved underside adds on each layer
// is printed by the walls leaning out, not by lines spanning anything (support's bridge detector,
// geometry/support/overhang.cpp, asks the same of a bridge).
inline constexpr double kMinAirAcrossMm = 2.0;
// Nor is air whose best lines are held by the layer below at one end or both for less than this
// share of their length: lines held nowhere gain nothing over the loops (an island printed
// mostly over nothing, as the Stanford bunny's second layer over its few first-layer specks;
// a cap's brim all round, whose lines in any one direction run along two of its sides). At 0.5
// the bunny's belly layers were bridged: gcheck's band coverage fell to 0.871 on one of them and
// the overflow rose from 0.32 to 2.33 mm², the lines' ends following its ragged outline worse
// than the loops do.
inline constexpr double kMinHeldShare = 0.8;

struct OverhangWallSplit {
  geo::Rings air;     // the island's parts over air (farther than half a bead from the layer below) a bead wide or more
  geo::Rings bridge;  // `air` grown by the anchor, within the island: what the bridge lines fill, where no wall runs
  double angle_deg = 0;  // the lines' direction, counter-clockwise from +x (bridge_angle_deg)
  bool empty() const { return bridge.empty(); }
};

// The split of `island` (outline and holes) over `below` (the layer below's material): empty
// when no part of the island's wall band (its border `band_mm` deep) lies over air at least
// `bead_mm` wide, i.e. when the walls would only lean out a little, as on a slope; also when the
// air is nowhere kMinAirAcrossMm wide or its lines would be held less than kMinHeldShare.
OverhangWallSplit split_overhang_walls(const geo::Rings& island, const geo::Rings& below, double band_mm,
                                       double bead_mm, double anchor_mm = kBridgeAnchorMm);

// Whether `region` less `below` (both rings, non-zero fill) may hold a disc of radius `r_mm`:
// false only when it surely holds none a little smaller (r_mm - kDiscMarginMm), so that
// shrinking their difference by r_mm leaves nothing. No boolean: the stretches of both along
// rows a quarter of the radius apart, a disc's chords on the rows near its centre sought in
// them. split_overhang_walls' early-out: most islands of a curved part rest on the layer below
// all but a crescent nowhere kMinAirAcrossMm wide, and this answers them at a small part of the
// cost of the difference and the shrink.
inline constexpr double kDiscMarginMm = 0.025;  // 5 × the offsets' arc tolerance (geometry/toolpath/clip.cpp)
bool may_hold_disc(const geo::Rings& region, const geo::Rings& below, double r_mm);

// The direction (degrees, 0..180) of straight lines across `air` that are best anchored on
// `below`: in 36 directions, lines across `air` whose ends, carried on by `hold_mm`, land on
// `below` at both ends hang over their length, at one end over twice it (out and back, as a
// zig-zag lays them), at neither over four times the air's extent (held only by their
// neighbours, however short); the direction with the least length-weighted mean wins. A gap held on two sides is crossed; a ledge held along one edge gets lines out
// from that edge (a shelf's wall loops would run along it).
// `held`, if given, receives the share (0..1) of that direction's line length held at one end
// or both.
double bridge_angle_deg(const geo::Rings& air, const geo::Rings& below, double hold_mm, double* held = nullptr);

// The closed loops `loops` (a closing point not repeated) as open polylines, less their parts
// inside `region`; pieces shorter than `min_mm` are dropped.
std::vector<geo::Ring> loops_outside(const std::vector<geo::Ring>& loops, const geo::Rings& region, double min_mm);

}  // namespace tranche::toolpath
