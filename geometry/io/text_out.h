// What the text exports share: exact decimal millimetres for integer coordinates, JSON strings
// and XML escapes. (Files are written through base/output_file.h.)
#pragma once

#include <string>
#include <string_view>

#include <fmt/format.h>

#include "geometry/core/geom.h"
#include "base/result.h"

namespace tranche::geo {

// Appends `units` (1 unit = 1 nm) as millimetres, exactly: at most 6 decimals, no trailing zeros
// ("12.5", "-0.000001", "3").
void append_mm(fmt::memory_buffer& out, coord_t units);

// Appends `s` as a JSON string literal (quotes included).
void append_json_string(fmt::memory_buffer& out, std::string_view s);

// Appends `s` with the five XML special characters escaped (for attributes and text).
void append_xml_escaped(fmt::memory_buffer& out, std::string_view s);

}  // namespace tranche::geo
