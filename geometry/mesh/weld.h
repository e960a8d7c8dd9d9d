// Vertex welding: triangles given as float corners become an indexed mesh in which bitwise-equal
// corners (after folding -0 into +0) share one vertex id.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/report.h"
#include "base/result.h"
#include "geometry/mesh/mesh.h"

namespace tranche::geo {

class Welder {
 public:
  // `triangles` is the total number of triangles to come; the table is sized for all 3·n corners
  // being distinct, so it never rehashes. n must be at most kMaxTriangles (vertex ids are 32-bit).
  explicit Welder(size_t triangles);

  // Adds n triangles: corners[9i .. 9i+8] are corners a, b, c (x, y, z each, mm, finite),
  // counter-clockwise seen from outside. Sets dropped[i] to 1, and adds nothing, where two
  // corners weld to the same vertex (a degenerate triangle), else to 0. Batches let lookups be
  // prefetched: a few thousand triangles per call is best.
  void add(const float* corners, size_t n, uint8_t* dropped);

  // Moves the vertices and triangles into `mesh` (its name is left alone); the welder is empty after.
  void finish(Mesh& mesh);

  static constexpr uint64_t kMaxTriangles = (uint64_t{1} << 32) / 3 - 1;

 private:
  using Key = std::array<uint32_t, 3>;  // float bit patterns of one vertex

  std::vector<Key> keys_;        // by vertex id
  std::vector<uint32_t> slots_;  // open addressing, linear probing; kEmpty or a vertex id
  std::vector<std::array<uint32_t, 3>> triangles_;
  std::vector<Key> batch_keys_;
  std::vector<uint64_t> batch_hashes_;
  std::vector<uint32_t> batch_ids_;
  uint64_t mask_ = 0;
  uint64_t dropped_ = 0;
};

// The whole welding of loaders that gather float corners (3MF, OBJ): 9 floats per triangle, mm.
// Errors: a coordinate that is not finite, too many triangles, only degenerate triangles; the
// degenerate ones dropped are a warning (code "mesh-degenerate") at `where`.
Result<Mesh> weld_corners(const std::vector<float>& corners, const std::string& where, Report& report);

// The same welding for loaders that gather indexed triangles (3MF): `vertices` holds x, y, z of
// each vertex (mm), `triangles` three vertex indices each (all below vertices.size() / 3, the
// caller's check). The result, warnings and errors are those of weld_corners on the triangles'
// corners, vertex ids included, but only the vertices are hashed, not every corner.
Result<Mesh> weld_indexed(const std::vector<float>& vertices, const std::vector<uint32_t>& triangles,
                          const std::string& where, Report& report);
// The same, on triangles as vertex id triples whose storage the result takes over.
Result<Mesh> weld_indexed(const std::vector<float>& vertices, std::vector<std::array<uint32_t, 3>>&& triangles,
                          const std::string& where, Report& report);

// weld_indexed in two steps, so that a loader can take the first while a mesh is still in its
// cache and the second later, without a copy of the mesh (the 3MF loader: threemf_meshes.h).
//
// The first step, order_by_first_use: an indexed mesh of finite vertices (x, y, z each at
// `vertices`, `nv` of them; `triangles` in range, the caller's check) in the welder's order:
// exactly equal vertices (-0 folded into +0) merged, the vertices in the order the triangles first
// use them, those no triangle uses left out. `out` gets the vertices as the welded mesh keeps
// them (doubles of the floats; -0 is +0), `triangles` their new ids in place; degenerate triangles are kept (the second step
// drops them, as the welder does, after numbering their corners). `scratch` is working memory a
// loader may keep from mesh to mesh.
struct WeldScratch {
  std::vector<uint32_t> first;   // by input vertex: the first vertex of its value
  std::vector<uint32_t> id;      // by input vertex: its id in `out`
  std::vector<uint64_t> slots;   // hash table of input vertices: fingerprint << 32 | vertex
};
// Returns how many triangles are degenerate (two corners with the same new id), for weld_ordered.
size_t order_by_first_use(const float* vertices, size_t nv, std::vector<std::array<uint32_t, 3>>& triangles,
                          std::vector<Vec3>& out, WeldScratch& scratch);

// The second step, on a mesh order_by_first_use gave: degenerate triangles dropped (a warning,
// "mesh-degenerate"; all of them: an error), the vertices only they use left out, the storage of
// both taken over. The result is weld_indexed's on the mesh before the first step. `degenerate`:
// how many triangles are, when the caller knows (order_by_first_use's count); 0 spares the look
// at every triangle.
Result<Mesh> weld_ordered(std::vector<Vec3>&& vertices, std::vector<std::array<uint32_t, 3>>&& triangles,
                          const std::string& where, Report& report, std::optional<size_t> degenerate = {});

}  // namespace tranche::geo
