// The one way the tools write a file (G-code, layer exports, the preview, bundles, formatted
// rules, STL and 3MF): it never destroys anything and never looks complete unless it is.
//
// - A regular file (or a new one) is written, through a 1 MiB buffer, to a hidden temporary
//   `.NAME.tmp-XXXXXX` in the destination's folder, which commit() syncs and renames into place.
//   The new file keeps the permission bits of the file it replaces (and its owner, where the
//   system allows); a new file gets 0666 less the umask. A read-only destination is refused.
// - A symlink is written through: its final target is replaced (in the target's folder), the link
//   stays. A link to a missing file creates that file.
// - A character or block device or a FIFO is written directly: opened for writing without
//   truncation, never renamed or replaced. The bytes are spooled to an unnamed temporary file
//   first and copied to the device at commit(), so a failed run sends nothing (a printer behind a
//   FIFO never receives half a job). A FIFO without a reader is an error, not a hang.
// - A destination that is an input of the current run, or another output of it, is refused with
//   a message naming both (base/run_files.h).
// - The temporary file is removed when the object is destroyed without commit() (an error, an
//   exception) and when the process is ended by a signal (base/temp_files.h).
#pragma once

#include <cstdint>
#include <memory>
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

  // At most `max_bytes` may be written (0: no limit); a write beyond is an error that says
  // "<what> would be larger than <max>" followed by `advice` (e.g. which option raises it).
  void set_limit(uint64_t max_bytes, std::string advice);

  Status write(std::string_view bytes);
  // Bytes written so far (the offset of the next byte).
  uint64_t offset() const;
  // Overwrites bytes written earlier at `at` (same length), e.g. a header filled in at the end.
  Status patch(uint64_t at, std::string_view bytes);
  // Flushes, syncs and renames the temporary file into place (or copies the spool to the device).
  Status commit();

  const std::string& path() const;
  // The hidden temporary next to the destination; empty for a device or FIFO.
  const std::string& temp_path() const;
  // Whether the destination is a device or FIFO, written directly.
  bool direct() const;

 private:
  struct State;
  explicit OutputFile(std::unique_ptr<State> s);
  Status flush();
  Error fail(const std::string& what) const;
  std::unique_ptr<State> s_;
};

}  // namespace tranche
