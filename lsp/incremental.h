// Incremental parsing for the language server: a file is cut into its top-level items (each
// starts on a line that begins, outside any bracket, with `rule`, `on`, `use` or `param`), each
// part is parsed on its own once, and later parses copy the items of the parts whose text did
// not change (ast::clone), relocated to where the part now is. So one edit of a 2000-rule file
// parses one rule. A file with a syntax error anywhere is parsed whole, as `rulec check` does,
// so that it reports the same errors.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "grammar/ast/ast.h"
#include "grammar/ast/diagnostic.h"

namespace tranche::lsp {

// Byte offsets where the top-level items of `text` start (the first part starts at 0).
std::vector<uint32_t> item_starts(std::string_view text);

class ItemCache {
 public:
  // A drop-in for grammar::parse_file (compiler::FrontendOptions::parser).
  ast::File parse(const ast::SourceMap& sources, uint32_t file, diag::Sink& sink);
  // Forgets the parts no parse used in the last few calls (call once per analysis, so that the
  // parts of other open documents survive a few analyses of this one).
  void sweep();
  size_t size() const { return parts_.size(); }
  size_t reused() const { return reused_; }  // parts copied in the last parse

 private:
  struct Part {
    std::shared_ptr<const ast::File> items;  // parsed alone: spans from offset 0, line 1
    uint64_t last_used = 0;
  };
  static constexpr uint64_t kKeep = 8;  // analyses a part survives unused
  std::unordered_map<std::string, Part> parts_;
  uint64_t generation_ = 0;
  size_t reused_ = 0;
};

}  // namespace tranche::lsp
