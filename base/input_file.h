// The one way the tools read a file (rules, profiles, bundles, scripts, SVG drawings, models):
// every read has a documented size bound (docs/cli.md, "Files and safety"), a regular file
// larger than its bound is refused from its size before a byte is read, and anything else (a
// pipe, a FIFO, /dev/zero, a terminal) is read with the same bound and refused, with a clear
// message, once it gives more. Every file opened is noted as an input of the current run
// (base/run_files.h), so that no output of the run can replace it.
#pragma once

#include <sys/stat.h>

#include <cstdint>
#include <string>

#include "base/result.h"

namespace tranche {

// What a file is read as: its name in messages and its size bound.
struct InputKind {
  const char* what;    // "the rules file", "the model": "cannot open the model: ..."
  uint64_t max_bytes;  // the bound, for regular files and streams alike
};

inline constexpr uint64_t kMiB = uint64_t{1} << 20;
inline constexpr InputKind kRulesInput{"the rules file", 16 * kMiB};       // .rules, profiles, `use`d files
inline constexpr InputKind kBundleInput{"the rule bundle", 256 * kMiB};    // vm::kMaxBundleBytes
inline constexpr InputKind kScriptInput{"the fill-angle script", 16 * kMiB};
inline constexpr InputKind kSvgInput{"the SVG drawing", 256 * kMiB};
inline constexpr InputKind kModelInput{"the model", 4096 * kMiB};           // STL, 3MF, OBJ

// An open input: regular files report their size; streams do not know it.
class InputFile {
 public:
  static Result<InputFile> open(const std::string& path, const InputKind& kind);
  // An open descriptor (standard input), duplicated; `name` is used in messages ("<stdin>").
  static Result<InputFile> adopt(int fd, const std::string& name, const InputKind& kind);
  InputFile(InputFile&& o) noexcept;
  InputFile& operator=(InputFile&&) = delete;
  InputFile(const InputFile&) = delete;
  ~InputFile();

  bool regular() const { return S_ISREG(st_.st_mode); }
  uint64_t size() const { return static_cast<uint64_t>(st_.st_size); }  // regular files only
  const std::string& path() const { return path_; }

  // Reads up to `n` bytes at the current position; 0 at the end. An error once more than the
  // bound has been read (a stream), or when the read fails.
  Result<size_t> read(char* into, size_t n);
  // Reads up to `n` bytes at `offset` without moving (regular files only): headers.
  Result<size_t> read_at(char* into, size_t n, uint64_t offset);
  // Everything that is left, as a string (up to the bound).
  Result<std::string> read_rest();
  // From now on the file is read as `kind` (its name, its bound, counting what was read): a file
  // that is a bundle or rules text is known after its first bytes.
  void set_kind(const InputKind& kind) { kind_ = kind; }

 private:
  InputFile(int fd, const struct stat& st, std::string path, const InputKind& kind);
  Error too_large() const;

  int fd_ = -1;
  struct stat st_ {};
  std::string path_;
  InputKind kind_;
  uint64_t read_ = 0;
};

// The whole file, up to kind.max_bytes: `read_input(path, kRulesInput)`.
Result<std::string> read_input(const std::string& path, const InputKind& kind);

// "1.5 GiB", "16 MiB", "300 bytes": sizes in messages.
std::string size_text(uint64_t bytes);

}  // namespace tranche
