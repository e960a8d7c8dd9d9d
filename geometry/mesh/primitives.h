// Closed, welded, consistently oriented meshes generated in code: test fixtures, the demo model
// and benchmark inputs. Every triangle is counter-clockwise seen from outside and every edge is
// shared by exactly two triangles traversing it in opposite directions.
#pragma once

#include <vector>

#include "geometry/mesh/mesh.h"

namespace tranche::geo {

// Axis-aligned box of `size` (mm) with its minimum corner at `origin` (mm): 8 vertices, 12 triangles.
Mesh box(const Vec3& size, const Vec3& origin = {});

// Cylinder of radius `r` (mm, to the polygon's vertices) and height `h` (mm), axis z, base centred
// on the origin at z = 0, approximated by a regular `segments`-gon (≥ 3): 4 × segments triangles.
Mesh cylinder(double r, double h, int segments);

// Cone frustum, axis z, base at z = 0 (radius `r_bottom` mm) to z = `h` (radius `r_top` mm); an
// `r_top` of 0 gives a pointed cone with a single apex vertex. Regular `segments`-gons (≥ 3).
Mesh cone(double r_bottom, double r_top, double h, int segments);

// UV sphere of radius `r` (mm) centred on the origin: `segments` meridians (≥ 3) and `rings`
// parallels bands (≥ 2), one vertex at each pole: 2 × segments × (rings − 1) triangles.
Mesh sphere(double r, int segments, int rings);

// Torus lying flat (axis z) centred on the origin: major radius `R` (mm, centre of the tube),
// tube radius `r` (mm, < R), `segments_major` × `segments_minor` quads (each ≥ 3), i.e.
// 2 × segments_major × segments_minor triangles (1280 × 320 gives 819 200).
Mesh torus(double R, double r, int segments_major, int segments_minor);

// Rectangular plate [0, size_x] × [0, size_y] × [0, thickness] (mm) on a `cols` × `rows` grid of
// cells, with a round through-hole of radius `hole_r` (mm) centred in each cell whose entry in
// `hole_mask` (row-major, cols × rows; empty = every cell) is true. `segments` (a multiple of 4,
// ≥ 4) is the number of sides of each hole; hole_r must stay inside its cell.
Mesh plate_with_holes(double size_x, double size_y, double thickness, int cols, int rows, double hole_r,
                      int segments, const std::vector<bool>& hole_mask = {});

// Appends `part` to `into` as a separate shell (no welding between the two).
void append(Mesh& into, const Mesh& part);

// Moves a mesh by `offset` (mm) in place and returns it, for building scenes in one expression.
Mesh translated(Mesh mesh, const Vec3& offset);

// The demo model of examples/models/demo.stl: a 40 × 40 mm plate with a grid of holes, a round
// boss and an overhanging arch, under 2 000 triangles.
Mesh demo_model();

}  // namespace tranche::geo
