// Internal to the 3MF loader: the meshes of a model part, read by a scanner of their own.
//
// lib3mf 1.8's XML reader builds an object per element: a model of 2 000 000 triangles takes it
// seconds, about 18 times the load of the same meshes as binary STL (bench/bench_plate.sh). So the
// loader reads each plain mesh here (`<mesh><vertices><vertex x y z/>...</vertices><triangles>
// <triangle v1 v2 v3 .../>...</triangles></mesh>`, in the model's unit) and hands lib3mf the
// model with those meshes replaced by a one-triangle placeholder that carries the object's id;
// lib3mf still reads everything else (objects, components, build items, transforms, units,
// metadata) and checks the package. A mesh the scanner does not follow (another namespace prefix,
// a comment, an extension's element, an attribute value it cannot read, a coordinate that is no
// finite number, an index out of range) is left in place for lib3mf, which reads it, or says what
// is wrong with it, as before.
//
// The objects' meshes are read in parallel (TBB), with the result one pass in order would give;
// numbers are read to the value std::from_chars gives (the common forms without it: indices eight
// digits at a time, coordinates with SSSE3 where the CPU has it, their 16 bytes at once; the
// others by it). Elements in the plain form are read whole with AVX2 where the CPU has it (each
// from one look at its 64 bytes), the others attribute after attribute, to the same values.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/mesh/mesh.h"

namespace tranche::plate::threemf {

// A mesh the scanner read is in the welder's order (geo::order_by_first_use, while the mesh is
// still in the cache): exactly equal vertices merged, the vertices in the order the triangles
// first use them, unused ones left out, every triangle kept (degenerate ones too: PrusaSlicer's
// volumes count them). What the 3MF reads is unchanged; the welding after is only its last step.
struct MeshData {
  std::vector<geo::Vec3> vertices;                 // in the model's unit (floats, as the file's are read)
  std::vector<std::array<uint32_t, 3>> triangles;  // vertex indices of each triangle, in range
  bool ordered = false;                            // in the welder's order (the scanner's meshes)
  size_t degenerate = 0;                           // then: its degenerate triangles (order_by_first_use)
};

struct SplitModel {
  std::string model;                    // the model part, the meshes read here replaced by placeholders
  std::map<uint32_t, MeshData> meshes;  // by the id of their object
  // Not empty: a mesh holds a value that neither the scanner nor lib3mf would read as a number
  // (lib3mf 1.8 reads "abc" or "" as 0): where and what, `line 12, object 1: vertex 3 has the
  // coordinate x="abc", which is not a number`. The load fails with it.
  std::string bad;
};

// Reads the plain meshes of the model part `xml`; `meshes` is empty when there was none.
SplitModel split_meshes(std::string_view xml);

// Where a model part read in pieces comes from: its next bytes, at most `n` of them, at `out`; how
// many (0: the end of the text); nothing when it cannot be read.
using Pull = std::function<std::optional<size_t>(char* out, size_t n)>;

// split_meshes on a model part read in pieces from `pull`, never whole in memory (a window of about
// 1 MiB): the result split_meshes gives on the whole text, or nothing where the whole text is
// needed to say it (an object whose mesh would be left to lib3mf, an id given twice, an element
// longer than 64 KiB, a value that is no number, a text that cannot be read); the caller then
// reads the part whole.
std::optional<SplitModel> split_meshes_streamed(const Pull& pull);

// A model part another thread reads ahead, in chunks the scanner reads where they are (no copy
// but of the few bytes of an element cut by a chunk's end, into the room before the next chunk).
class Chunks {
 public:
  static constexpr size_t kRoom = size_t{64} << 10;  // before each chunk's text
  struct Chunk {
    char* data = nullptr;  // the text is at data + kRoom
    size_t size = 0;       // 0: the text has ended
  };
  virtual ~Chunks() = default;
  // The next chunk; nothing when the text cannot be read.
  virtual std::optional<Chunk> next() = 0;
  // A chunk next() gave, no longer read.
  virtual void give_back(char* data) = 0;
};

// split_meshes_streamed on chunks: the same result, or nothing where it gives nothing.
std::optional<SplitModel> split_meshes_streamed(Chunks& chunks);

// The most of the CPU's vector instructions the scanner may use where the CPU has them: none;
// SSSE3 for coordinates; and AVX2 for whole plain elements (the default). The results are the
// same at every level, which the tests check at each.
enum class Simd { kNone, kSsse3, kAvx2 };
void limit_simd(Simd most);

// The id of the object whose placeholder lib3mf read as the mesh of the one triangle a, b, c
// (x, y, z each), if it is one.
std::optional<uint32_t> placeholder_id(const float* a, const float* b, const float* c);

}  // namespace tranche::plate::threemf
