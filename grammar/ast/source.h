// Source text and positions. Every AST node and every diagnostic points into a SourceMap file
// by a Span: file id, 1-based line and column (in characters; a tab counts as one), byte
// offset and length in bytes.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tranche::ast {

struct Span {
  uint32_t file = 0;
  uint32_t line = 0;  // 1-based; 0 means "no position" (e.g. a whole-file error)
  uint32_t col = 0;   // 1-based, in characters
  uint32_t offset = 0;
  uint32_t length = 0;
  bool valid() const { return line != 0; }
  uint32_t end() const { return offset + length; }
};

// The smallest span covering both (same file); either may be invalid.
Span join(const Span& a, const Span& b);

struct SourceFile {
  std::string path;  // shown in messages: as given on the command line, or resolved from `use`
  std::string text;  // the raw bytes
  bool user = true;  // written by the user (lints apply) rather than found in the stdlib
  std::vector<uint32_t> line_starts;  // byte offset of each line; `\n`, `\r\n` and `\r` end lines
};

class SourceMap {
 public:
  uint32_t add(std::string path, std::string text, bool user = true);
  const SourceFile& file(uint32_t id) const { return *files_.at(id); }
  size_t size() const { return files_.size(); }

  // The span of bytes [begin, end) of file `id` (clamped to the text).
  Span span(uint32_t id, uint32_t begin, uint32_t end) const;
  // 1-based line and character column of a byte offset.
  std::pair<uint32_t, uint32_t> line_col(uint32_t id, uint32_t offset) const;
  // Line `line` (1-based) without its line break.
  std::string_view line_text(uint32_t id, uint32_t line) const;
  // The source text a span covers.
  std::string_view text(const Span& span) const;

 private:
  std::vector<std::unique_ptr<SourceFile>> files_;  // stable addresses for the parser
};

// Number of characters (UTF-8 code points) in `s`; invalid bytes count one each.
uint32_t char_count(std::string_view s);

}  // namespace tranche::ast
