// Internal to the STL loader: the two format parsers produce raw facets (float corners as stored
// in the file); stl.cpp checks normals, welds and reports. Not for use outside geometry/mesh.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "base/report.h"
#include "base/result.h"

namespace tranche::geo::stl {

struct Facet {
  float normal[3];  // as stored; all zero when the file gives none
  float v[9];       // corners a, b, c (x, y, z each), mm
};

// Binary input stays in the file's bytes (`records`, 50 bytes per triangle, corners not yet
// checked for NaN); ASCII input is parsed into `facets`.
struct RawStl {
  std::string_view records;
  std::vector<Facet> facets;
  std::vector<uint32_t> lines;  // ASCII: the line of each facet's `facet` keyword; empty for binary
  std::string name;             // solid name / header text; empty when there is none

  size_t size() const { return records.empty() ? facets.size() : records.size() / kRecordBytes; }
  static constexpr size_t kRecordBytes = 50;
};

// Facet i of a binary STL record block (normal and corners as stored, little-endian float32).
void decode_record(const char* record, Facet& out);

// `file` names the input in messages. Binary needs a size that holds the header's count (extra
// bytes are a warning); ASCII is a hand-written tokenizer over the buffer, linear in its size.
Result<RawStl> parse_binary(std::string_view bytes, const std::string& file, Report& report);
Result<RawStl> parse_ascii(std::string_view bytes, const std::string& file, Report& report);

// The errors of a binary STL's triangle count against the file's size (too short, 0 triangles,
// more than the file holds, more than the welder takes), from the header alone.
Status check_binary_count(uint64_t count, uint64_t size, const std::string& file);
// The warning for bytes after the header's `count` triangles in a file of `size` bytes.
void warn_extra_data(uint64_t count, uint64_t size, const std::string& file, Report& report);
// The header's triangle count (0 when there is no full header).
uint32_t binary_count(std::string_view bytes);

// "model.stl:12" / "model.stl, triangle 40" (triangles are numbered from 1).
std::string at_line(const std::string& file, uint64_t line);
std::string at_triangle(const std::string& file, uint64_t index0);

}  // namespace tranche::geo::stl
