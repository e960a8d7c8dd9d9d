#include "geometry/mesh/file_bytes.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <new>
#include <system_error>

namespace tranche::geo {
namespace {

constexpr uint64_t kPipeLimit = uint64_t{1} << 30;  // bytes read from a pipe or device before giving up

std::string errno_text(int err) { return std::error_code(err, std::generic_category()).message(); }

}  // namespace

Result<FileBytes> read_file_bytes(const std::string& path, const std::string& kind) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    return Error{path, fmt::format("cannot open the model: {}{}", errno_text(err),
                                   err == ENOENT ? " — check the path" : "")};
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) return Error{path, "cannot read the model: " + errno_text(errno)};
  if (S_ISDIR(st.st_mode)) return Error{path, "is a directory, not " + kind};
  const bool regular = S_ISREG(st.st_mode);
  FileBytes b;
  size_t capacity = regular ? static_cast<size_t>(st.st_size) : size_t{1} << 20;
  b.data.reset(new (std::nothrow) char[std::max<size_t>(capacity, 1)]);
  if (!b.data) return Error{path, fmt::format("not enough memory to read the model ({} MB)", capacity >> 20)};
  for (;;) {
    if (b.size == capacity) {
      if (regular) break;  // a file that grows while we read it is taken at its size when opened
      if (capacity >= kPipeLimit) {
        return Error{path, fmt::format("more than {} MiB from a pipe or device; save the model to a file",
                                       kPipeLimit >> 20)};
      }
      auto bigger = std::unique_ptr<char[]>(new (std::nothrow) char[capacity * 2]);
      if (!bigger) return Error{path, "not enough memory to read the model"};
      std::memcpy(bigger.get(), b.data.get(), b.size);
      b.data = std::move(bigger);
      capacity *= 2;
    }
    const ssize_t n = ::read(fd, b.data.get() + b.size, capacity - b.size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return Error{path, "cannot read the model: " + errno_text(errno)};
    }
    if (n == 0) break;
    b.size += static_cast<size_t>(n);
  }
  return b;
}

}  // namespace tranche::geo
