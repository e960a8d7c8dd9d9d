// Any model file, whatever its name says: STL, 3MF or OBJ, told apart by content
// (detect.h). A file that is none of them is refused with what it is instead.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/report.h"
#include "base/result.h"
#include "geometry/plate/object.h"

namespace tranche::plate {

// The objects of the file at `path` (one for STL and OBJ, one per build item for 3MF), each in
// its own coordinates with the transform its file gives. Errors name the file and what is wrong.
Result<std::vector<Object>> load_model_file(const std::string& path, Report& report);

// Same, from bytes already in memory; `path` names them in messages and gives the objects' names.
Result<std::vector<Object>> parse_model_file(std::string_view bytes, const std::string& path, Report& report);

}  // namespace tranche::plate
