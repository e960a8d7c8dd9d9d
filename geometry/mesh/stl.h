// STL input (binary and ASCII, auto-detected) and binary output.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "geometry/mesh/mesh.h"
#include "base/report.h"
#include "base/result.h"

namespace tranche::geo {

// Loads an STL file into a welded mesh (exactly equal vertices share one id). Binary is chosen
// when the header's triangle count agrees with the file size, even if the file starts with
// "solid". Errors name the file and the place (line for ASCII, triangle index for binary);
// recoverable oddities (wrong normals, endsolid name mismatch...) are warnings in `report`.
Result<Mesh> load_stl(const std::string& path, Report& report);

// Same, from bytes already in memory; `name` is used in messages (fuzzing, tests).
Result<Mesh> parse_stl(std::string_view bytes, const std::string& name, Report& report);

// The checks that need only a file's first bytes (up to 4 KiB) and its size, made before it is
// read whole: a binary STL's triangle count against the size (a 2 GB file whose header says 0
// triangles, or more than it holds, is refused from its header), text that is no STL. Returns how
// many bytes are worth reading: a binary STL's triangles and no more (the bytes after them are
// only counted, in the stl-extra-data warning it adds to `report`). `size` is unknown for a
// stream: then a binary header with no triangles is refused, and its triangles bound the read.
Result<uint64_t> check_stl_head(std::string_view head, std::optional<uint64_t> size, const std::string& name,
                                Report& report);

// Writes a binary STL (normals computed from the triangles).
Status write_stl_binary(const std::string& path, const Mesh& mesh);

}  // namespace tranche::geo
