// Minimal fixed-point number formatting for G-code words: no trailing zeros ("X12.5", "Z1",
// "E0.01234"), computed exactly from integers so that a value always prints the same way.
#pragma once

#include <cstdint>
#include <string>

namespace tranche::gcode {

// Appends `scaled` / 10^decimals with at most `decimals` decimals, trailing zeros removed.
void append_fixed(std::string& out, int64_t scaled, int decimals);
// Appends a non-negative integer.
void append_int(std::string& out, int64_t v);

}  // namespace tranche::gcode
