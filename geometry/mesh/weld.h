// Vertex welding: triangles given as float corners become an indexed mesh in which bitwise-equal
// corners (after folding -0 into +0) share one vertex id.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "geometry/mesh/mesh.h"

namespace tranche::geo {

class Welder {
 public:
  // `triangles` is the number of add() calls to come; the table is sized for all 3·n corners being
  // distinct, so it never rehashes. n must be below 2^32 / 3 (the vertex ids are 32-bit).
  explicit Welder(size_t triangles);

  // Adds one triangle (corners a, b, c in mm, finite, counter-clockwise seen from outside).
  // Returns false, and adds nothing, when two corners weld to the same vertex (degenerate).
  bool add(const float* a, const float* b, const float* c);

  // Moves the vertices and triangles into `mesh` (its name is left alone); the welder is empty after.
  void finish(Mesh& mesh);

  static constexpr uint64_t kMaxTriangles = (uint64_t{1} << 32) / 3 - 1;

 private:
  uint32_t id_of(const float* p);

  std::vector<std::array<uint32_t, 3>> keys_;  // float bit patterns of each vertex, indexed by id
  std::vector<uint32_t> slots_;                // open addressing, linear probing; kEmpty or a vertex id
  std::vector<std::array<uint32_t, 3>> triangles_;
  uint64_t mask_ = 0;
  uint64_t dropped_ = 0;
};

}  // namespace tranche::geo
