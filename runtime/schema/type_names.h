// The name of each path kind in the G-code's ;TYPE: comments, PrusaSlicer's (so that its viewer
// and the peers' tools colour our files), shared by the G-code writer and the preview's labels.
#pragma once

#include <string_view>

#include "runtime/schema/schema.h"

namespace tranche::schema {

// "External perimeter", "Internal infill", "Support material", ... Bottom skins are "Solid
// infill", as PrusaSlicer writes them.
std::string_view gcode_type_name(PathKind k);

}  // namespace tranche::schema
