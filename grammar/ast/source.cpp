#include "grammar/ast/source.h"

#include <algorithm>

namespace tranche::ast {

Span join(const Span& a, const Span& b) {
  if (!a.valid()) return b;
  if (!b.valid() || a.file != b.file) return a;
  const Span& first = a.offset <= b.offset ? a : b;
  Span s = first;
  s.length = std::max(a.end(), b.end()) - first.offset;
  return s;
}

uint32_t char_count(std::string_view s) {
  uint32_t n = 0;
  for (unsigned char c : s) n += (c & 0xC0) != 0x80;
  return n;
}

uint32_t SourceMap::add(std::string path, std::string text, bool user) {
  auto f = std::make_unique<SourceFile>();
  f->path = std::move(path);
  f->text = std::move(text);
  f->user = user;
  f->line_starts.push_back(0);
  const std::string& t = f->text;
  for (size_t i = 0; i < t.size(); ++i) {
    if (t[i] == '\n' || (t[i] == '\r' && (i + 1 >= t.size() || t[i + 1] != '\n')))
      f->line_starts.push_back(static_cast<uint32_t>(i + 1));
  }
  files_.push_back(std::move(f));
  return static_cast<uint32_t>(files_.size() - 1);
}

std::pair<uint32_t, uint32_t> SourceMap::line_col(uint32_t id, uint32_t offset) const {
  const SourceFile& f = file(id);
  offset = std::min<uint32_t>(offset, static_cast<uint32_t>(f.text.size()));
  auto it = std::upper_bound(f.line_starts.begin(), f.line_starts.end(), offset);
  uint32_t line = static_cast<uint32_t>(it - f.line_starts.begin());
  uint32_t start = f.line_starts[line - 1];
  return {line, 1 + char_count(std::string_view(f.text).substr(start, offset - start))};
}

Span SourceMap::span(uint32_t id, uint32_t begin, uint32_t end) const {
  const SourceFile& f = file(id);
  uint32_t size = static_cast<uint32_t>(f.text.size());
  begin = std::min(begin, size);
  end = std::clamp(end, begin, size);
  auto [line, col] = line_col(id, begin);
  return Span{id, line, col, begin, end - begin};
}

std::string_view SourceMap::line_text(uint32_t id, uint32_t line) const {
  const SourceFile& f = file(id);
  if (line == 0 || line > f.line_starts.size()) return {};
  uint32_t start = f.line_starts[line - 1];
  uint32_t end = line < f.line_starts.size() ? f.line_starts[line] : static_cast<uint32_t>(f.text.size());
  std::string_view s = std::string_view(f.text).substr(start, end - start);
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::string_view SourceMap::text(const Span& span) const {
  if (span.file >= files_.size()) return {};
  const std::string& t = file(span.file).text;
  if (span.offset >= t.size()) return {};
  return std::string_view(t).substr(span.offset, span.length);
}

}  // namespace tranche::ast
