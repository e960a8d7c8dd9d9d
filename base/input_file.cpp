#include "base/input_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <new>
#include <system_error>

#include "base/run_files.h"

namespace tranche {
namespace {

std::string errno_text(int err) { return std::error_code(err, std::generic_category()).message(); }

std::string type_of(mode_t m) {
  if (S_ISFIFO(m)) return "a pipe or FIFO";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}

}  // namespace

std::string size_text(uint64_t bytes) {
  if (bytes >= (uint64_t{1} << 30) && bytes % (uint64_t{1} << 30) == 0) return fmt::format("{} GiB", bytes >> 30);
  if (bytes >= (uint64_t{1} << 30)) return fmt::format("{:.1f} GiB", static_cast<double>(bytes) / (1 << 30));
  if (bytes >= kMiB && bytes % kMiB == 0) return fmt::format("{} MiB", bytes >> 20);
  if (bytes >= kMiB) return fmt::format("{:.1f} MiB", static_cast<double>(bytes) / kMiB);
  return fmt::format("{} bytes", bytes);
}

Result<InputFile> InputFile::open(const std::string& path, const InputKind& kind) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    return Error{path, fmt::format("cannot open {}: {}{}", kind.what, errno_text(err),
                                   err == ENOENT ? " — check the path" : "")};
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    return Error{path, fmt::format("cannot read {}: {}", kind.what, errno_text(err))};
  }
  InputFile f(fd, st, path, kind);
  if (S_ISDIR(st.st_mode)) return Error{path, fmt::format("is a directory, not {}", kind.what)};
  if (f.regular() && f.size() > kind.max_bytes) return f.too_large();
  RunFiles::note_input(path, st, kind.what);
  return f;
}

Result<InputFile> InputFile::adopt(int fd, const std::string& name, const InputKind& kind) {
  const int own = ::fcntl(fd, F_DUPFD_CLOEXEC, 0);
  struct stat st {};
  if (own < 0 || ::fstat(own, &st) != 0) {
    const int err = errno;
    if (own >= 0) ::close(own);
    return Error{name, fmt::format("cannot read {}: {}", kind.what, errno_text(err))};
  }
  InputFile f(own, st, name, kind);
  if (S_ISDIR(st.st_mode)) return Error{name, fmt::format("is a directory, not {}", kind.what)};
  if (f.regular()) {  // read from where the descriptor stands
    const off_t at = ::lseek(own, 0, SEEK_CUR);
    f.read_ = at > 0 ? static_cast<uint64_t>(at) : 0;
    if (f.size() > kind.max_bytes) return f.too_large();
  }
  return f;
}

InputFile::InputFile(int fd, const struct stat& st, std::string path, const InputKind& kind)
    : fd_(fd), st_(st), path_(std::move(path)), kind_(kind) {}

InputFile::InputFile(InputFile&& o) noexcept
    : fd_(o.fd_), st_(o.st_), path_(std::move(o.path_)), kind_(o.kind_), read_(o.read_) {
  o.fd_ = -1;
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

Error InputFile::too_large() const {
  if (regular())
    return Error{path_, fmt::format("{} is {}, more than the {} read at most (docs/cli.md, \"Files and safety\"); "
                                    "check that this is the right file",
                                    kind_.what, size_text(size()), size_text(kind_.max_bytes))};
  return Error{path_, fmt::format("{} gave more than {}, the most that is read of {} ({}); is this the right "
                                  "file? Save what it should hold to a regular file",
                                  type_of(st_.st_mode), size_text(kind_.max_bytes), kind_.what,
                                  "docs/cli.md, \"Files and safety\"")};
}

Result<size_t> InputFile::read(char* into, size_t n) {
  // A regular file that grows while it is read is taken at the size it had when opened.
  if (regular()) n = static_cast<size_t>(std::min<uint64_t>(n, size() - std::min(read_, size())));
  if (n == 0) return size_t{0};
  for (;;) {
    const ssize_t got = ::read(fd_, into, n);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) return Error{path_, fmt::format("cannot read {}: {}", kind_.what, errno_text(errno))};
    read_ += static_cast<uint64_t>(got);
    if (read_ > kind_.max_bytes) return too_large();
    return static_cast<size_t>(got);
  }
}

Result<size_t> InputFile::read_at(char* into, size_t n, uint64_t offset) {
  size_t done = 0;
  while (done < n) {
    const ssize_t got = ::pread(fd_, into + done, n - done, static_cast<off_t>(offset + done));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) return Error{path_, fmt::format("cannot read {}: {}", kind_.what, errno_text(errno))};
    if (got == 0) break;
    done += static_cast<size_t>(got);
  }
  return done;
}

Result<std::string> InputFile::read_rest() {
  std::string out;
  try {
    if (regular()) out.reserve(static_cast<size_t>(size()));
    size_t chunk = regular() ? static_cast<size_t>(size()) : size_t{64} << 10;
    for (;;) {
      const size_t at = out.size();
      out.resize(at + std::max<size_t>(chunk, 1));
      auto got = read(out.data() + at, out.size() - at);
      if (!got) return got.error();
      out.resize(at + *got);
      if (*got == 0 || (regular() && read_ >= size())) break;
      chunk = std::min<size_t>(out.size(), size_t{16} << 20);  // streams: grow geometrically
    }
  } catch (const std::bad_alloc&) {
    return Error{path_, fmt::format("not enough memory to read {} ({} read)", kind_.what, size_text(out.size()))};
  }
  return out;
}

Result<std::string> read_input(const std::string& path, const InputKind& kind) {
  auto f = InputFile::open(path, kind);
  if (!f) return f.error();
  return f->read_rest();
}

}  // namespace tranche
