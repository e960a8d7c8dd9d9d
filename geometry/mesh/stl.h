// STL input (binary and ASCII, auto-detected) and binary output.
#pragma once

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

// Writes a binary STL (normals computed from the triangles).
Status write_stl_binary(const std::string& path, const Mesh& mesh);

}  // namespace tranche::geo
