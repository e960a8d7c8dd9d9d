#include "lsp/protocol.h"

#include <algorithm>
#include <istream>
#include <ostream>

namespace tranche::lsp {

namespace {
constexpr size_t kMaxMessageBytes = 64u << 20;  // a document of 16 MiB, escaped, with room to spare

// Length of the UTF-8 sequence starting with byte c (1 for stray continuation bytes).
size_t utf8_length(unsigned char c) { return c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC0 ? 2 : 1; }
}  // namespace

std::optional<std::string> read_message(std::istream& in) {
  size_t length = 0;
  bool has_length = false;
  std::string line;
  for (;;) {
    if (!std::getline(in, line)) return std::nullopt;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) {
      if (has_length) break;
      continue;  // stray blank lines between messages
    }
    constexpr std::string_view kKey = "content-length:";
    std::string lower = line.substr(0, kKey.size());
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    if (lower == kKey) {
      try {
        length = std::stoul(line.substr(kKey.size()));
      } catch (...) {
        return std::nullopt;
      }
      has_length = true;
    }
  }
  if (length > kMaxMessageBytes) return std::nullopt;
  std::string body(length, '\0');
  in.read(body.data(), static_cast<std::streamsize>(length));
  if (static_cast<size_t>(in.gcount()) != length) return std::nullopt;
  return body;
}

void write_message(std::ostream& out, std::string_view body) {
  out << "Content-Length: " << body.size() << "\r\n\r\n" << body;
  out.flush();
}

LineIndex::LineIndex(std::string_view text) : text_(text) {
  starts_.push_back(0);
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n' || (text[i] == '\r' && (i + 1 >= text.size() || text[i + 1] != '\n')))
      starts_.push_back(static_cast<uint32_t>(i + 1));
}

Position LineIndex::position(uint32_t offset) const {
  offset = std::min<uint32_t>(offset, static_cast<uint32_t>(text_.size()));
  auto it = std::upper_bound(starts_.begin(), starts_.end(), offset);
  uint32_t line = static_cast<uint32_t>(it - starts_.begin()) - 1;
  uint32_t units = 0;
  for (size_t i = starts_[line]; i < offset;) {
    size_t n = utf8_length(static_cast<unsigned char>(text_[i]));
    units += n == 4 ? 2 : 1;  // outside the BMP: a surrogate pair
    i += n;
  }
  return {line, units};
}

uint32_t LineIndex::offset(Position p) const {
  if (p.line >= starts_.size()) return static_cast<uint32_t>(text_.size());
  uint32_t end = p.line + 1 < starts_.size() ? starts_[p.line + 1] : static_cast<uint32_t>(text_.size());
  while (end > starts_[p.line] && (text_[end - 1] == '\n' || text_[end - 1] == '\r')) --end;
  uint32_t i = starts_[p.line], units = 0;
  while (i < end && units < p.character) {
    size_t n = utf8_length(static_cast<unsigned char>(text_[i]));
    units += n == 4 ? 2 : 1;
    i = std::min<uint32_t>(end, i + static_cast<uint32_t>(n));
  }
  return i;
}

std::string uri_to_path(std::string_view uri) {
  if (uri.starts_with("file://")) uri.remove_prefix(7);
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out += static_cast<char>(std::stoi(std::string(uri.substr(i + 1, 2)), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

std::string path_to_uri(std::string_view path) {
  static const char* hex = "0123456789ABCDEF";
  std::string out = "file://";
  for (unsigned char c : path) {
    if (std::isalnum(c) || c == '/' || c == '-' || c == '_' || c == '.' || c == '~') {
      out += static_cast<char>(c);
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

}  // namespace tranche::lsp
