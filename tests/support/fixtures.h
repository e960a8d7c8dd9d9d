// Helpers shared by the test suites: where the checkout and the build are, temp files.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace tranche::test {

// The checkout root (set by CTest; falls back to the compile-time path).
inline std::filesystem::path source_dir() {
  if (const char* s = std::getenv("TRANCHE_SOURCE_DIR")) return s;
  return TRANCHE_SOURCE_DIR_DEFAULT;
}

inline std::filesystem::path binary_dir() {
  if (const char* s = std::getenv("TRANCHE_BINARY_DIR")) return s;
  return TRANCHE_BINARY_DIR_DEFAULT;
}

// A file's bytes ("" when it cannot be read).
inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A fresh directory for one test's files, removed at scope exit.
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    // The process id keeps suites that CTest runs at once apart (rand() starts alike in each).
    path_ = std::filesystem::temp_directory_path() / ("tranche-test-" + tag + "-" + std::to_string(::getpid()) +
                                                      "-" + std::to_string(counter()++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  static int& counter() {
    static int c = 0;
    return c;
  }
  std::filesystem::path path_;
};

}  // namespace tranche::test
