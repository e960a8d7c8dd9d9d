// Extrusion flow math, the field standard (Slic3r/PrusaSlicer): a bead of width w and height h
// has a rounded-rectangle ("stadium") cross-section of area A = (w − h)·h + π·(h/2)², so two
// adjacent beads sit A/h = w − h·(1 − π/4) apart and overlap exactly where their round sides
// meet. Filament of diameter d feeds A·flow / (π·(d/2)²) mm of E per mm of bead.
#pragma once

namespace tranche::toolpath {

// Cross-section of a bead in mm² (width and height in mm). Beads narrower than they are high
// are taken as round (π·(w/2)²).
double bead_area_mm2(double width_mm, double height_mm);
// Distance between the centrelines of two adjacent beads of the same width and height, mm.
double bead_spacing_mm(double width_mm, double height_mm);
// Centreline distance between adjacent beads of widths w1 and w2 at height h, mm.
double bead_spacing_mm(double w1_mm, double w2_mm, double height_mm);
// Cross-section of the filament, mm².
double filament_area_mm2(double filament_diameter_mm);
// Filament length (mm of E) per mm of bead for this bead, flow multiplier and filament.
double e_per_mm(double width_mm, double height_mm, double flow, double filament_diameter_mm);

}  // namespace tranche::toolpath
