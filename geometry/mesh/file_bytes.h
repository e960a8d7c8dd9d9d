// Reading a whole model file into memory, for the loaders (STL here, 3MF and OBJ in
// geometry/plate), through the one input reader (base/input_file.h): the model's size bound
// (kModelInput), one read of a regular file, chunks from a pipe or device up to the same bound,
// clear errors for a missing file or a directory. A header check sees the first bytes before the
// rest is read, so a file refused from its header (a binary STL whose triangle count does not
// fit its size) costs no memory.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "base/result.h"

namespace tranche::geo {

// Frees a file's bytes: delete[], or munmap of `mapped` bytes (memory of their own, FileMemory::kHugePages).
struct FreeFileBytes {
  size_t mapped = 0;
  void operator()(char* p) const;
};

struct FileBytes {
  std::unique_ptr<char[], FreeFileBytes> data;
  size_t size = 0;
  std::string_view view() const { return {data.get(), size}; }
};

// Where a regular file's bytes are kept: on the heap, or, from 4 MiB on, in memory mapped for
// them alone, in huge pages where the system grants them (a few page faults instead of one per
// 4 KiB, which a fresh process pays in full; but never memory the heap has freed before, which a
// loader reading file after file reuses: the STL loader keeps the heap).
enum class FileMemory { kHeap, kHugePages };

// Room for `size` bytes (uninitialised) mapped on its own, beginning at a 2 MiB boundary, its
// length (huge_length(size)) rounded up to whole 2 MiB, and the whole 2 MiB the bytes fill marked
// for huge pages: so that each of those, the first too, takes one page fault instead of 512 (an
// anonymous mapping is otherwise placed anywhere, and the part of its first 2 MiB it holds stays
// small pages). The rest past them stays small pages: the memory used is what the bytes need,
// the rounding address space only. Null when there is no memory; freed by munmap(p,
// huge_length(size)). Where the system has no huge pages it is ordinary memory.
char* map_huge(size_t size);
size_t huge_length(size_t size);

// Sees the first bytes of a file (up to kHeadBytes; all of it when shorter) and its size (regular
// files; nothing for a stream), and returns how many bytes are worth reading (the rest is left
// unread; UINT64_MAX: all). An error stops the read.
using HeadCheck = std::function<Result<uint64_t>(std::string_view head, std::optional<uint64_t> size)>;
inline constexpr size_t kHeadBytes = 4096;

// `memory` (asked after the head check, so that it may depend on what the check saw): where the
// bytes of a regular file are kept; a stream's are on the heap.
Result<FileBytes> read_file_bytes(const std::string& path, const HeadCheck& check_head = {},
                                  const std::function<FileMemory()>& memory = {});

}  // namespace tranche::geo
