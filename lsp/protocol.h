// The Language Server Protocol's transport and positions: JSON-RPC messages framed by a
// `Content-Length` header, and positions as LSP counts them (0-based lines, columns in UTF-16
// code units) against byte offsets of UTF-8 text.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tranche::lsp {

// The body of the next message, or nothing at the end of the input or on a broken header.
std::optional<std::string> read_message(std::istream& in);
void write_message(std::ostream& out, std::string_view body);

struct Position {
  uint32_t line = 0;       // 0-based
  uint32_t character = 0;  // UTF-16 code units from the start of the line
};

// Where the lines of a text start, to convert between byte offsets and positions. The text
// must outlive the index. Lines end at `\n`, `\r\n` or `\r`, as in the compiler.
class LineIndex {
 public:
  explicit LineIndex(std::string_view text);
  Position position(uint32_t offset) const;
  uint32_t offset(Position p) const;  // clamped to the line and the text
  uint32_t lines() const { return static_cast<uint32_t>(starts_.size()); }

 private:
  std::string_view text_;
  std::vector<uint32_t> starts_;
};

// `file:///a/b%20c.rules` <-> `/a/b c.rules`.
std::string uri_to_path(std::string_view uri);
std::string path_to_uri(std::string_view path);

}  // namespace tranche::lsp
