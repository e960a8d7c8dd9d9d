// What the layer exports share: an output file that appears whole or not at all, and exact
// decimal millimetres for integer coordinates.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "geometry/core/geom.h"
#include "runtime/base/result.h"

namespace tranche::geo {

// Writes go to a temporary file beside `path`; commit() flushes it and renames it over `path`.
// Without a successful commit() the temporary file is removed and `path` is left untouched.
class OutputFile {
 public:
  static Result<OutputFile> open(const std::string& path);
  OutputFile(OutputFile&& other) noexcept;
  OutputFile& operator=(OutputFile&&) = delete;
  OutputFile(const OutputFile&) = delete;
  ~OutputFile();

  Status write(std::string_view bytes);
  Status commit();

 private:
  OutputFile(std::string path, std::string temp, std::FILE* f)
      : path_(std::move(path)), temp_(std::move(temp)), f_(f) {}
  std::string path_, temp_;
  std::FILE* f_ = nullptr;
};

// Appends `units` (1 unit = 1 nm) as millimetres, exactly: at most 6 decimals, no trailing zeros
// ("12.5", "-0.000001", "3").
void append_mm(fmt::memory_buffer& out, coord_t units);

// Appends `s` as a JSON string literal (quotes included).
void append_json_string(fmt::memory_buffer& out, std::string_view s);

// Appends `s` with the five XML special characters escaped (for attributes and text).
void append_xml_escaped(fmt::memory_buffer& out, std::string_view s);

}  // namespace tranche::geo
