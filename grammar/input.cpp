#include "grammar/input.h"

namespace tranche::grammar {

namespace {
// Length of the UTF-8 sequence starting at s[i] and its code point, or 0 if invalid
// (overlong forms, surrogates and values past U+10FFFF are invalid).
int decode(const std::string& s, size_t i, size_t end, uint32_t* cp) {
  unsigned char c = static_cast<unsigned char>(s[i]);
  if (c < 0x80) {
    *cp = c;
    return 1;
  }
  int n = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC0 ? 2 : 0;
  if (n == 0 || c > 0xF4 || i + static_cast<size_t>(n) > end) return 0;
  uint32_t v = c & (0x7F >> n);
  for (int k = 1; k < n; ++k) {
    unsigned char d = static_cast<unsigned char>(s[i + static_cast<size_t>(k)]);
    if ((d & 0xC0) != 0x80) return 0;
    v = (v << 6) | (d & 0x3F);
  }
  static const uint32_t kMin[] = {0, 0, 0x80, 0x800, 0x10000};
  if (v < kMin[n] || v > 0x10FFFF || (v >= 0xD800 && v <= 0xDFFF)) return 0;
  *cp = v;
  return n;
}
}  // namespace

Input::Input(const ast::SourceMap& sources, uint32_t file, uint32_t begin, uint32_t end)
    : sources_(sources), file_(file) {
  const std::string& text = sources.file(file).text;
  end = std::min<uint32_t>(end, static_cast<uint32_t>(text.size()));
  _data.clear();
  _data.reserve(end > begin ? end - begin : 0);
  byte_of_.reserve(end > begin ? end - begin + 1 : 1);
  for (size_t i = begin; i < end;) {
    uint32_t cp = 0;
    int n = decode(text, i, end, &cp);
    if (n == 0) {
      ok_ = false;
      bad_offset_ = static_cast<uint32_t>(i);
      _data.clear();
      byte_of_.clear();
      begin = end;
      break;
    }
    _data.push_back(static_cast<UTF32String::value_type>(cp));
    byte_of_.push_back(static_cast<uint32_t>(i));
    i += static_cast<size_t>(n);
  }
  byte_of_.push_back(ok_ ? end : begin);
  p = 0;
}

uint32_t Input::byte(size_t cp) const { return byte_of_[std::min(cp, byte_of_.size() - 1)]; }

ast::Span Input::span(size_t start, size_t stop) const {
  uint32_t b = byte(start);
  uint32_t e = stop + 1 > start ? byte(stop + 1) : b;
  return sources_.span(file_, b, e);
}

ast::Span Input::span(const antlr4::Token* token) const {
  if (token == nullptr) return end_span();
  if (token->getType() == antlr4::Token::EOF) return end_span();
  return span(token->getStartIndex(), token->getStopIndex());
}

ast::Span Input::span(antlr4::ParserRuleContext* ctx) const {
  if (ctx == nullptr || ctx->getStart() == nullptr) return end_span();
  const antlr4::Token* start = ctx->getStart();
  const antlr4::Token* stop = ctx->getStop();
  if (start->getType() == antlr4::Token::EOF) return end_span();
  if (stop == nullptr || stop->getType() == antlr4::Token::EOF ||
      stop->getStopIndex() < start->getStartIndex())
    return span(start);
  return span(start->getStartIndex(), stop->getStopIndex());
}

ast::Span Input::end_span() const {
  uint32_t e = byte_of_.back();
  return sources_.span(file_, e, e);
}

}  // namespace tranche::grammar
