// 3MF input through lib3mf (the 3MF Consortium's library; Debian 12 ships 1.8): every build item
// becomes an object, with its transform, in the package's units converted to mm; components are
// flattened into their object's mesh; the slicers' extras are handled by threemf_package.h.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/report.h"
#include "base/result.h"
#include "geometry/plate/object.h"

namespace tranche::plate {

// `file` names the input in messages and is each object's `file`. Objects are placed (a 3MF
// build item is a position on the plate) and numbered by instance: a second build item of the
// same object is its copy 1. Errors name the file and the part, item or object at fault.
Result<std::vector<Object>> parse_3mf(std::string_view bytes, const std::string& file, Report& report);

}  // namespace tranche::plate
