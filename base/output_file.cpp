#include "base/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace tranche {

namespace {
constexpr size_t kBuffer = 1 << 20;
}

Result<OutputFile> OutputFile::create(const std::string& path, std::string what) {
  namespace fs = std::filesystem;
  fs::path dest(path);
  fs::path dir = dest.has_parent_path() ? dest.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    std::string msg = "the folder '";
    msg.append(dir.string()).append("' does not exist; create it or choose another output path");
    return Error{path, msg};
  }
  if (fs::is_directory(dest, ec)) return Error{path, "is a folder; give a file name for " + what};
  std::string name = ".";
  name.append(dest.filename().string()).append(".tmp-XXXXXX");
  std::string tmpl = (dir / name).string();
  int fd = mkstemp(tmpl.data());
  if (fd < 0) return Error{path, std::string("cannot write in this folder: ").append(std::strerror(errno))};
  return OutputFile(fd, path, tmpl, std::move(what));
}

OutputFile::OutputFile(int fd, std::string path, std::string tmp, std::string what)
    : fd_(fd), path_(std::move(path)), tmp_(std::move(tmp)), what_(std::move(what)) {
  buf_.reserve(kBuffer);
}

OutputFile::OutputFile(OutputFile&& o) noexcept
    : fd_(o.fd_),
      path_(std::move(o.path_)),
      tmp_(std::move(o.tmp_)),
      what_(std::move(o.what_)),
      buf_(std::move(o.buf_)),
      written_(o.written_),
      committed_(o.committed_) {
  o.fd_ = -1;
  o.committed_ = true;
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !tmp_.empty()) ::unlink(tmp_.c_str());
}

Error OutputFile::fail(const std::string& what) {
  std::string msg = what;
  msg.append(": ").append(std::strerror(errno)).append(" (nothing was written to ").append(path_).append(")");
  return Error{path_, msg};
}

Status OutputFile::flush() {
  size_t done = 0;
  while (done < buf_.size()) {
    ssize_t n = ::write(fd_, buf_.data() + done, buf_.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return fail("cannot write " + what_);
    }
    done += static_cast<size_t>(n);
  }
  written_ += buf_.size();
  buf_.clear();
  return ok_status();
}

Status OutputFile::write(std::string_view bytes) {
  if (fd_ < 0) return Error{path_, "write after the file was closed"};
  if (buf_.size() + bytes.size() > kBuffer) {
    if (Status s = flush(); !s) return s;
    if (bytes.size() > kBuffer) {
      buf_.assign(bytes);
      return flush();
    }
  }
  buf_.append(bytes);
  return ok_status();
}

Status OutputFile::patch(uint64_t at, std::string_view bytes) {
  if (at >= written_) {  // still in the buffer
    size_t off = static_cast<size_t>(at - written_);
    if (off + bytes.size() > buf_.size()) return Error{path_, "patch beyond the written bytes"};
    buf_.replace(off, bytes.size(), bytes);
    return ok_status();
  }
  if (Status s = flush(); !s) return s;
  if (::pwrite(fd_, bytes.data(), bytes.size(), static_cast<off_t>(at)) != static_cast<ssize_t>(bytes.size()))
    return fail("cannot update " + what_);
  return ok_status();
}

Status OutputFile::commit() {
  if (Status s = flush(); !s) return s;
  if (::fchmod(fd_, 0644) != 0) return fail("cannot set the permissions of " + what_);
  if (::close(fd_) != 0) {
    fd_ = -1;
    return fail("cannot finish writing " + what_);
  }
  fd_ = -1;
  if (std::rename(tmp_.c_str(), path_.c_str()) != 0) return fail("cannot move " + what_ + " into place");
  committed_ = true;
  return ok_status();
}

}  // namespace tranche
