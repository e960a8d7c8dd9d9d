// Internal to grammar/: the characters ANTLR reads, decoded here (strict UTF-8) so that every
// token position maps back to a byte offset, line and column of the source file.
#pragma once

#include <antlr4-runtime.h>

#include <cstdint>
#include <string>
#include <vector>

#include "grammar/ast/source.h"

namespace tranche::grammar {

class Input : public antlr4::ANTLRInputStream {
 public:
  // Decodes bytes [begin, end) of file `file`. On invalid UTF-8, ok() is false and
  // bad_offset() is the first bad byte.
  Input(const ast::SourceMap& sources, uint32_t file, uint32_t begin, uint32_t end);

  bool ok() const { return ok_; }
  uint32_t bad_offset() const { return bad_offset_; }
  const ast::SourceMap& sources() const { return sources_; }
  uint32_t file() const { return file_; }

  // Character `cp` of the input, or 0 past the end.
  size_t char_at(size_t cp) const { return cp < _data.size() ? static_cast<size_t>(_data[cp]) : 0; }
  // Byte offset in the file of character `cp` of the input (cp == size(): the end).
  uint32_t byte(size_t cp) const;
  // The span of characters [start, stop] (inclusive, as ANTLR reports them).
  ast::Span span(size_t start, size_t stop) const;
  ast::Span span(const antlr4::Token* token) const;
  ast::Span span(antlr4::ParserRuleContext* ctx) const;
  // An empty span just after the last character.
  ast::Span end_span() const;

 private:
  const ast::SourceMap& sources_;
  uint32_t file_;
  bool ok_ = true;
  uint32_t bad_offset_ = 0;
  std::vector<uint32_t> byte_of_;  // per character, plus one for the end
};

}  // namespace tranche::grammar
