#include "geometry/mesh/file_bytes.h"

#include <fmt/format.h>

#include <algorithm>
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

Result<FileBytes> read_regular(InputFile& f, const HeadCheck& check_head) {
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
  b.data.reset(new (std::nothrow) char[std::max<uint64_t>(size, 1)]);
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
  b.data.reset(new (std::nothrow) char[capacity]);
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
      auto bigger = std::unique_ptr<char[]>(new (std::nothrow) char[grown]);
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

Result<FileBytes> read_file_bytes(const std::string& path, const HeadCheck& check_head) {
  auto f = InputFile::open(path, kModelInput);
  if (!f) return f.error();
  return f->regular() ? read_regular(*f, check_head) : read_stream(*f, check_head);
}

}  // namespace tranche::geo
