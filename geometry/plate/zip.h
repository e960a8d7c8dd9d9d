// ZIP archives in memory, as 3MF packages are. lib3mf reads the package itself; we read the
// directory to name what is in a file (a 3MF? another ZIP?), the slicers' extra parts
// (Metadata/*.config) and the model parts lib3mf 1.8 cannot follow, and we write the small
// stored archives those parts are re-packed into.
//
//   [local header + data]...  [central directory: one header per entry]  [zip64 end]? [end record]
//
// Every offset and size is checked against the buffer; entries are stored (method 0) or
// deflated (method 8, through libdeflate, which inflates a whole entry in one call about twice as
// fast as zlib, or through ISA-L's streaming inflate when an entry is read in pieces; zlib only
// says why data they refused is damaged), and their CRC-32 is verified.
#pragma once

#include <cstdint>
#include <memory>
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

// The bytes of an entry read by ZipArchive::read_bytes. Large entries (a model part of 150 MB)
// get memory of their own, in huge pages where the system grants them: a fraction of the page
// faults, and no zero-filling before the bytes are written.
class ZipBytes {
 public:
  ZipBytes() = default;
  explicit ZipBytes(size_t size);  // uninitialised
  ZipBytes(ZipBytes&& o) noexcept;
  ZipBytes& operator=(ZipBytes&& o) noexcept;
  ZipBytes(const ZipBytes&) = delete;
  ZipBytes& operator=(const ZipBytes&) = delete;
  ~ZipBytes();

  char* data() { return data_; }
  size_t size() const { return size_; }
  std::string_view view() const { return {data_, size_}; }

 private:
  static constexpr size_t kMapped = size_t{4} << 20;  // from this size on: mapped memory
  void release();
  char* data_ = nullptr;
  size_t size_ = 0;
};

class ZipArchive;

// One entry read front to back in pieces (ZipArchive::stream), so that a large part need never
// be in memory whole: deflate is inflated through ISA-L's streaming inflate, stored data copied.
// The size and CRC-32 the directory gives are checked when the entry ends.
class ZipStream {
 public:
  ZipStream(ZipStream&&) noexcept;
  ZipStream& operator=(ZipStream&&) noexcept;
  ~ZipStream();

  // The next bytes of the entry, at most `n` of them, at `out`: how many (at least 1 while the
  // entry has more; 0 at its end, once its size and CRC have been found right). An error (the
  // data is damaged or truncated, in ZipArchive::read's words) ends the stream.
  Result<size_t> read(char* out, size_t n);

 private:
  friend class ZipArchive;
  struct State;
  explicit ZipStream(std::unique_ptr<State> s);
  std::unique_ptr<State> s_;
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
  // The same, for large entries: memory of their own (ZipBytes).
  Result<ZipBytes> read_bytes(const ZipEntry& entry, uint64_t limit = uint64_t{1} << 31) const;
  // The same, in pieces (ZipStream); the same checks, the data's only when it is read. The archive
  // must outlive the stream.
  Result<ZipStream> stream(const ZipEntry& entry, uint64_t limit = uint64_t{1} << 31) const;

 private:
  // The entry's data in the archive, after every check of its header and sizes.
  Result<std::string_view> data_of(const ZipEntry& entry, uint64_t limit) const;
  // Inflates (or copies) `in`, the data of `entry`, to its `entry.size` bytes at `out`; checks the CRC.
  Status unpack(const ZipEntry& entry, std::string_view in, char* out) const;
  Error damaged(const ZipEntry& entry, const std::string& what) const;
  friend class ZipStream;

  static constexpr uint64_t kPrepared = uint64_t{32} << 20;  // read_bytes: from this size on, pages made ready ahead

  std::string_view bytes_;
  std::string file_;
  std::vector<ZipEntry> entries_;
};

// True when `bytes` starts like a ZIP archive (a local header, or the end record of an empty one).
bool looks_like_zip(std::string_view bytes);

// A ZIP archive of `files` (name, content), stored without compression, in the given order.
std::string write_stored_zip(const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace tranche::plate
