// Mesh → closed loops per layer: each layer's plane (its mid z) cuts the triangles it crosses,
// and the segments are chained into loops by mesh topology. See docs/slicing.md.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "geometry/core/layer.h"
#include "geometry/mesh/mesh.h"
#include "geometry/slice/topology.h"
#include "base/report.h"
#include "base/result.h"

namespace tranche::geo {

// Where a cut enters or leaves a triangle.
struct Crossing {
  enum Kind : uint8_t { Edge, Vertex };
  Kind kind = Edge;
  int index = 0;        // Edge: the edge from vertex index to (index + 1) % 3; Vertex: the vertex
  double x = 0, y = 0;  // mm
};

// One triangle's piece of a layer's outline, oriented so that the material is on its left seen
// from above (outer boundaries run counter-clockwise).
struct TriangleCut {
  Crossing from, to;
};

// The case analysis for the triangle v (counter-clockwise seen from outside) and the plane at
// height z (mm). A vertex counts as below when v.z < z and as above otherwise (on the plane is
// "above": the plane is taken infinitesimally low), which settles every tie consistently:
//  - no vertex below, or all three below (including a triangle lying in the plane): no cut;
//  - two vertices on the plane and the third below: the edge between them (so an edge lying in
//    the plane is counted once, by the triangle on its lower side);
//  - one vertex on the plane: the segment from it to the crossing of the opposite edge when the
//    other two lie on opposite sides; nothing when both are below or both above;
//  - otherwise the two edge crossings.
// An edge crossing is interpolated from the edge's lower vertex to its upper vertex, so both
// triangles sharing the edge compute the bit-identical point.
std::optional<TriangleCut> cut_triangle(const std::array<Vec3, 3>& v, double z);

struct SliceParams {
  // Open ends of loops closer than this (mm) are joined, nearest first; a negative value means
  // twice the layer's height (about one extrusion width: a narrower gap cannot print anyway).
  double gap_tolerance = -1;
  // Called from worker threads with the number of layers finished so far.
  std::function<void(size_t layers_done)> progress;
};

struct SliceStats {
  size_t segments = 0;     // triangle cuts, all layers
  size_t loops = 0;        // loops kept, all layers
  size_t gaps_joined = 0;  // open ends joined to another end within the gap tolerance
  size_t open_loops = 0;   // chains closed on themselves across a wider gap ("open-loop" warnings)
};

// Fills layers[i].loops for every planned layer (bottom to top, as from plan_layer_heights), cutting
// the mesh at each layer's z_slice(). Loops are in integer units (geom.h), counter-clockwise
// around material and clockwise around holes, following the mesh's winding. A chain that cannot
// be closed within the gap tolerance is closed on itself with a straight edge and reported as an
// "open-loop" warning naming the layer and the position. Parallel over layers; warnings are
// reported in layer order. Errors: non-finite coordinates or coordinates beyond ±1 000 000 mm.
Result<SliceStats> slice_mesh(const Mesh& mesh, const MeshTopology& topology, std::vector<Layer>& layers,
                              const SliceParams& params, Report& report);

// Same, building the topology first.
Result<SliceStats> slice_mesh(const Mesh& mesh, std::vector<Layer>& layers, const SliceParams& params,
                              Report& report);

}  // namespace tranche::geo
