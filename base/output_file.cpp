#include "base/output_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "base/input_file.h"
#include "base/run_files.h"
#include "base/temp_files.h"

namespace tranche {

namespace fs = std::filesystem;

struct OutputFile::State {
  int fd = -1;         // the temporary file (regular destination) or the spool (device, FIFO)
  int device_fd = -1;  // a device or FIFO, open for writing; -1 for a regular destination
  std::string path, target, tmp, what;  // target: the file renamed over (symlinks resolved)
  std::string buf;
  uint64_t written = 0, limit = 0;
  std::string limit_advice;
  mode_t mode = 0644;
  bool chown = false;
  uid_t uid = 0;
  gid_t gid = 0;
  int temp_slot = -1;
  bool committed = false;

  ~State() {
    if (fd >= 0) ::close(fd);
    if (device_fd >= 0) ::close(device_fd);
    if (!committed && !tmp.empty()) ::unlink(tmp.c_str());
    temp_files::remove(temp_slot);
  }
};

namespace {

constexpr size_t kBuffer = 1 << 20;

std::string errno_text(int err) { return std::strerror(err); }

// The process's umask, without changing it for other threads where /proc tells it.
mode_t current_umask() {
  if (FILE* f = std::fopen("/proc/self/status", "re")) {
    char line[256];
    unsigned mask = 0;
    bool found = false;
    while (!found && std::fgets(line, sizeof line, f)) found = std::sscanf(line, "Umask: %o", &mask) == 1;
    std::fclose(f);
    if (found) return static_cast<mode_t>(mask);
  }
  const mode_t m = ::umask(022);
  ::umask(m);
  return m;
}

// The file a path names once every symlink is followed, for a path that does not exist as a
// file: either nothing is there, or a chain of links ends at a missing file (created there).
Result<std::string> missing_target(const std::string& path) {
  std::string p = path;
  for (int hops = 0; hops < 40; ++hops) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p;
    char link[PATH_MAX];
    const ssize_t n = ::readlink(p.c_str(), link, sizeof link - 1);
    if (n < 0) return Error{path, "cannot read the symbolic link: " + errno_text(errno)};
    fs::path to(std::string(link, static_cast<size_t>(n)));
    p = to.is_absolute() ? to.string() : (fs::path(p).parent_path() / to).string();
  }
  return Error{path, "too many levels of symbolic links; check where the link points"};
}

std::string folder_of(const std::string& file) {
  fs::path p(file);
  return p.has_parent_path() ? p.parent_path().string() : std::string(".");
}

// An unnamed temporary file for a device's bytes: gone when closed, whatever happens.
int open_spool() {
  const char* dir = std::getenv("TMPDIR");
  if (!dir || !*dir) dir = "/tmp";
  int fd = ::open(dir, O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (fd >= 0) return fd;
  std::string tmpl = std::string(dir) + "/tranche-spool-XXXXXX";
  fd = ::mkostemp(tmpl.data(), O_CLOEXEC);
  if (fd >= 0) ::unlink(tmpl.c_str());
  return fd;
}

}  // namespace

Result<OutputFile> OutputFile::create(const std::string& path, std::string what) {
  if (path.empty()) return Error{"", "no file name given for " + what};
  auto s = std::make_unique<State>();
  s->path = path;
  s->what = std::move(what);
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;
  if (!exists && errno != ENOENT) {
    return Error{path, fmt::format("cannot write {} here: {}", s->what, errno_text(errno))};
  }
  if (exists && S_ISDIR(st.st_mode)) return Error{path, "is a folder; give a file name for " + s->what};
  if (exists && S_ISSOCK(st.st_mode))
    return Error{path, "is a socket; " + s->what + " can go to a file, a device or a FIFO"};
  if (Status c = RunFiles::claim_output(path, s->what); !c) return c.error();
  if (exists && (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) || S_ISFIFO(st.st_mode))) {
    const bool fifo = S_ISFIFO(st.st_mode);
    s->device_fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY | (fifo ? O_NONBLOCK : 0));
    if (s->device_fd < 0 && fifo && errno == ENXIO)
      return Error{path, "this FIFO has no reader: start the program that reads it, then run again"};
    if (s->device_fd < 0) return Error{path, fmt::format("cannot open it for {}: {}", s->what, errno_text(errno))};
    if (fifo) ::fcntl(s->device_fd, F_SETFL, ::fcntl(s->device_fd, F_GETFL) & ~O_NONBLOCK);
    s->fd = open_spool();
    if (s->fd < 0) return Error{path, "cannot create a temporary file for " + s->what + ": " + errno_text(errno)};
    return OutputFile(std::move(s));
  }
  if (exists) {
    char real[PATH_MAX];
    s->target = ::realpath(path.c_str(), real) ? std::string(real) : path;
    if (::access(s->target.c_str(), W_OK) != 0 && errno == EACCES)
      return Error{path, "is read-only; make it writable (chmod u+w) or choose another file for " + s->what};
    s->mode = st.st_mode & 0777;
    s->chown = st.st_uid != ::geteuid() || st.st_gid != ::getegid();
    s->uid = st.st_uid;
    s->gid = st.st_gid;
  } else {
    auto target = missing_target(path);
    if (!target) return target.error();
    s->target = *target;
    s->mode = 0666 & ~current_umask();
  }
  const std::string dir = folder_of(s->target);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    return Error{path, fmt::format("the folder '{}' does not exist; create it or choose another output path", dir)};
  }
  std::string tmpl = (fs::path(dir) / ("." + fs::path(s->target).filename().string() + ".tmp-XXXXXX")).string();
  s->fd = ::mkostemp(tmpl.data(), O_CLOEXEC);
  if (s->fd < 0)
    return Error{path, fmt::format("cannot write in the folder '{}': {} (the file is written there first, then "
                                   "renamed into place)",
                                   dir, errno_text(errno))};
  s->tmp = tmpl;
  s->temp_slot = temp_files::add(s->tmp.c_str());
  return OutputFile(std::move(s));
}

OutputFile::OutputFile(std::unique_ptr<State> s) : s_(std::move(s)) { s_->buf.reserve(kBuffer); }
OutputFile::OutputFile(OutputFile&& o) noexcept = default;
OutputFile::~OutputFile() = default;

const std::string& OutputFile::path() const { return s_->path; }
const std::string& OutputFile::temp_path() const { return s_->tmp; }
bool OutputFile::direct() const { return s_->device_fd >= 0; }
uint64_t OutputFile::offset() const { return s_->written + s_->buf.size(); }

void OutputFile::set_limit(uint64_t max_bytes, std::string advice) {
  s_->limit = max_bytes;
  s_->limit_advice = std::move(advice);
}

Error OutputFile::fail(const std::string& what) const {
  return Error{s_->path, fmt::format("{}: {} (nothing was written to {})", what, errno_text(errno), s_->path)};
}

Status OutputFile::flush() {
  size_t done = 0;
  while (done < s_->buf.size()) {
    ssize_t n = ::write(s_->fd, s_->buf.data() + done, s_->buf.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return fail("cannot write " + s_->what);
    }
    done += static_cast<size_t>(n);
  }
  s_->written += s_->buf.size();
  s_->buf.clear();
  return ok_status();
}

Status OutputFile::write(std::string_view bytes) {
  if (s_->fd < 0) return Error{s_->path, "write after the file was closed"};
  if (s_->limit && offset() + bytes.size() > s_->limit)
    return Error{s_->path, fmt::format("{} would be larger than {}{}; nothing was written", s_->what,
                                       size_text(s_->limit), s_->limit_advice)};
  if (s_->buf.size() + bytes.size() > kBuffer) {
    if (Status s = flush(); !s) return s;
    if (bytes.size() > kBuffer) {
      s_->buf.assign(bytes);
      return flush();
    }
  }
  s_->buf.append(bytes);
  return ok_status();
}

Status OutputFile::patch(uint64_t at, std::string_view bytes) {
  if (at >= s_->written) {  // still in the buffer
    size_t off = static_cast<size_t>(at - s_->written);
    if (off + bytes.size() > s_->buf.size()) return Error{s_->path, "patch beyond the written bytes"};
    s_->buf.replace(off, bytes.size(), bytes);
    return ok_status();
  }
  if (Status s = flush(); !s) return s;
  if (::pwrite(s_->fd, bytes.data(), bytes.size(), static_cast<off_t>(at)) != static_cast<ssize_t>(bytes.size()))
    return fail("cannot update " + s_->what);
  return ok_status();
}

namespace {

// Copies the spool to the device or FIFO, from its start.
Status copy_spool(int from, int to, const std::string& path, const std::string& what) {
  if (::lseek(from, 0, SEEK_SET) != 0) return Error{path, "cannot read back " + what + ": " + errno_text(errno)};
  std::string buf(kBuffer, '\0');
  for (;;) {
    ssize_t n = ::read(from, buf.data(), buf.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return Error{path, "cannot read back " + what + ": " + errno_text(errno)};
    if (n == 0) return ok_status();
    for (ssize_t done = 0; done < n;) {
      ssize_t w = ::write(to, buf.data() + done, static_cast<size_t>(n - done));
      if (w < 0 && errno == EINTR) continue;
      if (w < 0 && errno == EPIPE)
        return Error{path, "the reader went away before it had all of " + what + " (broken pipe)"};
      if (w < 0) return Error{path, "cannot write " + what + ": " + errno_text(errno)};
      done += w;
    }
  }
}

}  // namespace

Status OutputFile::commit() {
  State& s = *s_;
  if (s.committed || s.fd < 0) return Error{s.path, "commit after the file was closed"};
  if (Status st = flush(); !st) return st;
  if (s.device_fd >= 0) {
    if (Status st = copy_spool(s.fd, s.device_fd, s.path, s.what); !st) return st;
    const int closed = ::close(s.device_fd);
    s.device_fd = -1;
    if (closed != 0) return fail("cannot finish writing " + s.what);
    ::close(s.fd);
    s.fd = -1;
    s.committed = true;
    return ok_status();
  }
  if (s.chown && ::fchown(s.fd, s.uid, s.gid) != 0) {
    // Not allowed (not root, not the group's member): the new file is ours, with the old mode.
  }
  if (::fchmod(s.fd, s.mode) != 0) return fail("cannot set the permissions of " + s.what);
  if (::fsync(s.fd) != 0) return fail("cannot finish writing " + s.what);
  const int closed = ::close(s.fd);
  s.fd = -1;
  if (closed != 0) return fail("cannot finish writing " + s.what);
  if (std::rename(s.tmp.c_str(), s.target.c_str()) != 0) return fail("cannot move " + s.what + " into place");
  s.committed = true;
  temp_files::remove(s.temp_slot);
  s.temp_slot = -1;
  return ok_status();
}

}  // namespace tranche
