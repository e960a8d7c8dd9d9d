#include "base/run_files.h"

#include <fmt/format.h>

#include <filesystem>
#include <mutex>
#include <vector>

namespace tranche {

struct RunFiles::State {
  struct Entry {
    bool output = false;
    bool has_inode = false;  // false: an output that does not exist yet (compared by `key`)
    dev_t dev{};
    ino_t ino{};
    std::string key;   // the absolute path with symlinks resolved
    std::string path;  // as given, for messages
    std::string what;
  };
  std::vector<Entry> entries;
};

namespace {

std::mutex& mu() {
  static std::mutex m;
  return m;
}
RunFiles* g_current = nullptr;

// Regular files and FIFOs: the files that an output could damage or that would loop.
bool comparable(mode_t m) { return S_ISREG(m) || S_ISFIFO(m); }

std::string resolved(const std::string& path) {
  std::error_code ec;
  auto p = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
  return ec ? std::filesystem::path(path).lexically_normal().string() : p.string();
}

}  // namespace

RunFiles::RunFiles() : state_(new State), outer_(nullptr) {
  std::lock_guard lock(mu());
  outer_ = g_current;
  g_current = this;
}

RunFiles::~RunFiles() {
  {
    std::lock_guard lock(mu());
    g_current = outer_;
  }
  delete state_;
}

void RunFiles::note_input(const std::string& path, const struct stat& st, std::string_view what) {
  if (!comparable(st.st_mode)) return;
  std::lock_guard lock(mu());
  if (!g_current) return;
  for (const auto& e : g_current->state_->entries)
    if (e.has_inode && e.dev == st.st_dev && e.ino == st.st_ino && !e.output) return;
  State::Entry e;
  e.has_inode = true;
  e.dev = st.st_dev;
  e.ino = st.st_ino;
  e.path = path;
  e.what = std::string(what);
  g_current->state_->entries.push_back(std::move(e));
}

void RunFiles::note_input_path(const std::string& path, std::string_view what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) note_input(path, st, what);
}

Status RunFiles::check_output(const std::string& path, std::string_view what) {
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;
  if (exists && !comparable(st.st_mode)) return ok_status();  // a device, a terminal: harmless
  const std::string key = resolved(path);
  std::lock_guard lock(mu());
  if (!g_current) return ok_status();
  for (const auto& e : g_current->state_->entries) {
    const bool same = e.has_inode && exists ? (e.dev == st.st_dev && e.ino == st.st_ino) : (e.output && e.key == key);
    if (!same) continue;
    if (e.output && e.what == what && e.key == key) continue;  // claimed before by the same output
    if (!e.output)
      return Error{path, fmt::format("refusing to write {} here: this file is {} of this run ('{}'), which "
                                     "would be destroyed; choose another output file",
                                     what, e.what, e.path)};
    return Error{path, fmt::format("refusing to write {} here: {} is already written to this file ('{}'); "
                                   "give each output its own file",
                                   what, e.what, e.path)};
  }
  return ok_status();
}

Status RunFiles::claim_output(const std::string& path, std::string_view what) {
  if (Status s = check_output(path, what); !s) return s;
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;
  if (exists && !comparable(st.st_mode)) return ok_status();
  State::Entry e;
  e.output = true;
  e.has_inode = exists;
  e.dev = st.st_dev;
  e.ino = st.st_ino;
  e.key = resolved(path);
  e.path = path;
  e.what = std::string(what);
  std::lock_guard lock(mu());
  if (!g_current) return ok_status();
  for (const auto& other : g_current->state_->entries)
    if (other.output && other.what == e.what && other.key == e.key) return ok_status();
  g_current->state_->entries.push_back(std::move(e));
  return ok_status();
}

}  // namespace tranche
