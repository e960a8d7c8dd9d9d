// The one way the tools write a file (G-code, layer exports, bundles, STL): it never looks
// complete unless it is. Bytes go, through a 1 MiB buffer, to a temporary file next to the
// destination, which commit() renames into place. A file that is destroyed without commit() (an
// error, an exception, a crash before rename) leaves the destination as it was and removes its
// temporary.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "base/result.h"

namespace tranche {

class OutputFile {
 public:
  // `what` names the content in messages ("the G-code", "the SVG export").
  static Result<OutputFile> create(const std::string& path, std::string what = "the file");
  OutputFile(OutputFile&& o) noexcept;
  OutputFile& operator=(OutputFile&&) = delete;
  OutputFile(const OutputFile&) = delete;
  ~OutputFile();

  Status write(std::string_view bytes);
  // Bytes written so far (the offset of the next byte).
  uint64_t offset() const { return written_ + buf_.size(); }
  // Overwrites bytes written earlier at `at` (same length), e.g. a header filled in at the end.
  Status patch(uint64_t at, std::string_view bytes);
  // Flushes, closes and renames the temporary file to the destination.
  Status commit();
  const std::string& path() const { return path_; }
  const std::string& temp_path() const { return tmp_; }

 private:
  OutputFile(int fd, std::string path, std::string tmp, std::string what);
  Status flush();
  Error fail(const std::string& what);

  int fd_ = -1;
  std::string path_, tmp_, what_;
  std::string buf_;
  uint64_t written_ = 0;
  bool committed_ = false;
};

}  // namespace tranche
