// Reading a whole model file into memory, for the loaders (STL here, 3MF and OBJ in
// geometry/plate): one read of a regular file, chunks from a pipe, clear errors for a missing
// file, a directory, or a stream too large to buffer.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "base/result.h"

namespace tranche::geo {

struct FileBytes {
  std::unique_ptr<char[]> data;
  size_t size = 0;
  std::string_view view() const { return {data.get(), size}; }
};

// `kind` names what the file should be in the directory message ("an STL file", "a model file").
Result<FileBytes> read_file_bytes(const std::string& path, const std::string& kind);

}  // namespace tranche::geo
