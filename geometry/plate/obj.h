// Wavefront OBJ input through tinyobjloader: one object per file (all its groups), in mm,
// polygons triangulated; normals, texture coordinates and materials are ignored.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/report.h"
#include "base/result.h"
#include "geometry/plate/object.h"

namespace tranche::plate {

// `file` names the input in messages. Faces are checked first, with their line: fewer than 3
// vertices, or a vertex number that no `v` line defines, is an error.
Result<std::vector<Object>> parse_obj(std::string_view bytes, const std::string& file, Report& report);

}  // namespace tranche::plate
