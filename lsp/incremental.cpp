#include "lsp/incremental.h"

#include "grammar/parse.h"

namespace tranche::lsp {

namespace {
bool ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || (c & 0x80); }

bool starts_item(std::string_view text, size_t at) {
  for (std::string_view kw : {"rule", "on", "use", "param"})
    if (text.substr(at, kw.size()) == kw && (at + kw.size() >= text.size() || !ident_char(text[at + kw.size()])))
      return true;
  return false;
}
}  // namespace

std::vector<uint32_t> item_starts(std::string_view text) {
  std::vector<uint32_t> out{0};
  int depth = 0;
  bool line_start = true;
  for (size_t i = 0; i < text.size(); ++i) {
    char c = text[i];
    if (c == '\n' || c == '\r') {
      line_start = true;
      continue;
    }
    if (c == ' ' || c == '\t') continue;
    if (line_start && depth == 0 && i > 0 && starts_item(text, i)) {
      size_t bol = i;
      while (bol > 0 && text[bol - 1] != '\n' && text[bol - 1] != '\r') --bol;
      if (bol > out.back()) out.push_back(static_cast<uint32_t>(bol));
    }
    line_start = false;
    if (c == '#') {
      while (i + 1 < text.size() && text[i + 1] != '\n' && text[i + 1] != '\r') ++i;
    } else if (text.substr(i, 3) == "\"\"\"") {
      size_t end = text.find("\"\"\"", i + 3);
      i = end == std::string_view::npos ? text.size() : end + 2;
    } else if (c == '"') {
      while (i + 1 < text.size() && text[i + 1] != '"' && text[i + 1] != '\n' && text[i + 1] != '\r')
        i += text[i + 1] == '\\' ? 2 : 1;
      if (i + 1 < text.size() && text[i + 1] == '"') ++i;
    } else if (c == '{' || c == '(' || c == '[') {
      ++depth;
    } else if (c == '}' || c == ')' || c == ']') {
      depth = std::max(0, depth - 1);
    }
  }
  return out;
}

ast::File ItemCache::parse(const ast::SourceMap& sources, uint32_t file, diag::Sink& sink) {
  const std::string& text = sources.file(file).text;
  std::vector<uint32_t> starts = item_starts(text);
  ast::File out;
  out.id = file;
  reused_ = 0;
  for (size_t k = 0; k < starts.size(); ++k) {
    uint32_t begin = starts[k];
    uint32_t end = k + 1 < starts.size() ? starts[k + 1] : static_cast<uint32_t>(text.size());
    std::string part_text = text.substr(begin, end - begin);
    auto it = parts_.find(part_text);
    if (it == parts_.end()) {
      ast::SourceMap alone;
      uint32_t id = alone.add(sources.file(file).path, part_text);
      diag::Sink errors;
      auto parsed = std::make_shared<ast::File>(grammar::parse_file(alone, id, errors));
      // A syntax error: parse the whole file, for the same diagnostics as `rulec check`.
      if (errors.has_errors()) return grammar::parse_file(sources, file, sink);
      it = parts_.emplace(std::move(part_text), Part{std::move(parsed), generation_}).first;
    } else {
      ++reused_;
    }
    it->second.last_used = generation_;
    auto [line, col] = sources.line_col(file, begin);
    (void)col;
    ast::Relocation to{file, begin, line - 1};
    for (const auto& item : it->second.items->items) out.items.push_back(ast::clone(item, to));
  }
  return out;
}

void ItemCache::sweep() {
  std::erase_if(parts_, [&](auto& entry) { return entry.second.last_used + kKeep < generation_; });
  ++generation_;
}

}  // namespace tranche::lsp
