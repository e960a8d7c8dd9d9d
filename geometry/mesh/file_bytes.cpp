#include "geometry/mesh/file_bytes.h"

#include <fmt/format.h>

#include <sys/mman.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <new>

#include "base/input_file.h"

namespace tranche::geo {
namespace {

Error no_memory(const std::string& path, uint64_t bytes) {
  return Error{path, fmt::format("not enough memory to read the model ({}); close other programs, or "
                                 "simplify the model",
                                 size_text(bytes))};
}

constexpr uint64_t kHugeFrom = uint64_t{4} << 20;  // FileMemory::kHugePages from this size on

// Uninitialised room for `size` bytes (at least 1) where `memory` says; null when there is no memory.
std::unique_ptr<char[], FreeFileBytes> room(uint64_t size, FileMemory memory) {
#ifdef MADV_HUGEPAGE
  if (memory == FileMemory::kHugePages && size >= kHugeFrom) {
    char* p = map_huge(size);
    if (!p) return {};
    return std::unique_ptr<char[], FreeFileBytes>(p, FreeFileBytes{huge_length(size)});
  }
#else
  (void)memory;
#endif
  return std::unique_ptr<char[], FreeFileBytes>(new (std::nothrow) char[std::max<uint64_t>(size, 1)]);
}

Result<FileBytes> read_regular(InputFile& f, const HeadCheck& check_head,
                               const std::function<FileMemory()>& memory) {
  uint64_t size = f.size();
  if (check_head) {
    char head[kHeadBytes];
    auto got = f.read_at(head, static_cast<size_t>(std::min<uint64_t>(size, kHeadBytes)), 0);
    if (!got) return got.error();
    auto want = check_head(std::string_view(head, *got), size);
    if (!want) return want.error();
    size = std::min(size, *want);
  }
  FileBytes b;
  b.data = room(size, memory ? memory() : FileMemory::kHeap);
  if (!b.data) return no_memory(f.path(), size);
  while (b.size < size) {
    auto got = f.read(b.data.get() + b.size, static_cast<size_t>(size) - b.size);
    if (!got) return got.error();
    if (*got == 0) break;  // shrunk while being read: what is there
    b.size += *got;
  }
  return b;
}

// A pipe, FIFO or device: chunks into a growing buffer, up to the model bound (InputFile).
Result<FileBytes> read_stream(InputFile& f, const HeadCheck& check_head) {
  FileBytes b;
  size_t capacity = size_t{1} << 20;
  b.data = room(capacity, FileMemory::kHeap);
  if (!b.data) return no_memory(f.path(), capacity);
  bool checked = !check_head;
  uint64_t want = UINT64_MAX;
  for (;;) {
    if (b.size >= want) {  // what the header says is there: the rest of the stream is not read
      b.size = static_cast<size_t>(want);
      return b;
    }
    if (b.size == capacity) {
      // One byte past the bound is enough for InputFile to refuse the stream.
      const size_t grown = static_cast<size_t>(std::min<uint64_t>(uint64_t{capacity} * 2, kModelInput.max_bytes + 1));
      auto bigger = room(grown, FileMemory::kHeap);
      if (!bigger) return no_memory(f.path(), grown);
      std::memcpy(bigger.get(), b.data.get(), b.size);
      b.data = std::move(bigger);
      capacity = grown;
    }
    auto got = f.read(b.data.get() + b.size, capacity - b.size);
    if (!got) return got.error();
    b.size += *got;
    if (!checked && (b.size >= kHeadBytes || *got == 0)) {
      checked = true;
      auto w = check_head(std::string_view(b.data.get(), std::min(b.size, kHeadBytes)), std::nullopt);
      if (!w) return w.error();
      want = *w;
    }
    if (*got == 0) return b;
  }
}

}  // namespace

size_t huge_length(size_t size) {
  constexpr size_t kHuge = size_t{2} << 20;
  return (size + kHuge - 1) / kHuge * kHuge;
}

char* map_huge(size_t size) {
  constexpr size_t kHuge = size_t{2} << 20;
  const size_t length = huge_length(size);
  if (length < size || length + kHuge < length) return nullptr;  // no such room
  // Mapped 2 MiB longer, then the parts before the first boundary and past the room let go.
  void* m = mmap(nullptr, length + kHuge, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (m == MAP_FAILED) return nullptr;
  const uintptr_t at = reinterpret_cast<uintptr_t>(m);
  const uintptr_t aligned = (at + kHuge - 1) & ~uintptr_t{kHuge - 1};
  if (aligned > at) munmap(m, aligned - at);
  if (const size_t after = at + kHuge - aligned; after > 0) munmap(reinterpret_cast<void*>(aligned + length), after);
  char* p = reinterpret_cast<char*>(aligned);
#ifdef MADV_HUGEPAGE
  // Huge pages for the whole 2 MiB the bytes fill; the rest, past them, stays small pages, so that
  // the memory used is what the bytes need (a hint: without huge pages it is ordinary memory).
  if (const size_t whole = size / kHuge * kHuge; whole > 0) madvise(p, whole, MADV_HUGEPAGE);
#endif
  return p;
}

void FreeFileBytes::operator()(char* p) const {
  if (mapped)
    munmap(p, mapped);
  else
    delete[] p;
}

Result<FileBytes> read_file_bytes(const std::string& path, const HeadCheck& check_head,
                                  const std::function<FileMemory()>& memory) {
  auto f = InputFile::open(path, kModelInput);
  if (!f) return f.error();
  return f->regular() ? read_regular(*f, check_head, memory) : read_stream(*f, check_head);
}

}  // namespace tranche::geo
