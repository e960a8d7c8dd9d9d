// ZIP archives in memory, as 3MF packages are. lib3mf reads the package itself; we read the
// directory to name what is in a file (a 3MF? another ZIP?), the slicers' extra parts
// (Metadata/*.config) and the model parts lib3mf 1.8 cannot follow, and we write the small
// stored archives those parts are re-packed into.
//
//   [local header + data]...  [central directory: one header per entry]  [zip64 end]? [end record]
//
// Every offset and size is checked against the buffer; entries are stored (method 0) or
// deflated (method 8, through zlib), and their CRC-32 is verified.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/result.h"

namespace tranche::plate {

struct ZipEntry {
  std::string name;           // as stored, '/' separated, no leading '/'
  uint16_t method = 0;        // 0 stored, 8 deflated
  uint16_t flags = 0;         // bit 0: encrypted
  uint32_t crc = 0;           // CRC-32 of the uncompressed bytes
  uint64_t compressed = 0;    // bytes in the archive
  uint64_t size = 0;          // bytes once inflated
  uint64_t local_offset = 0;  // of the entry's local header
};

class ZipArchive {
 public:
  // Reads the central directory of `bytes`, which must outlive the archive. Errors (`file`
  // names the input): not a ZIP archive, truncated, a directory that points outside the file.
  static Result<ZipArchive> open(std::string_view bytes, const std::string& file);

  const std::vector<ZipEntry>& entries() const { return entries_; }
  // The entry named `name` (a leading '/' is ignored; ASCII case-insensitive, as OPC part names are).
  const ZipEntry* find(std::string_view name) const;
  // The entry's bytes, inflated and checked; entries larger than `limit` bytes are refused.
  Result<std::string> read(const ZipEntry& entry, uint64_t limit = uint64_t{1} << 31) const;

 private:
  std::string_view bytes_;
  std::string file_;
  std::vector<ZipEntry> entries_;
};

// True when `bytes` starts like a ZIP archive (a local header, or the end record of an empty one).
bool looks_like_zip(std::string_view bytes);

// A ZIP archive of `files` (name, content), stored without compression, in the given order.
std::string write_stored_zip(const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace tranche::plate
