// 3MF output through lib3mf: each object a mesh object and a build item with its transform.
// For test fixtures, benchmarks and the fuzz corpus today; a plate export tomorrow.
#pragma once

#include <string>
#include <vector>

#include "base/result.h"
#include "geometry/plate/object.h"

namespace tranche::plate {

// The 3MF package (millimetres) as bytes. Errors: lib3mf's, or a transform that is not affine.
Result<std::string> write_3mf_bytes(const std::vector<Object>& objects);

// Same, into the file at `path` (written whole, or not at all).
Status write_3mf(const std::string& path, const std::vector<Object>& objects);

}  // namespace tranche::plate
