// `rulec lsp`: a Language Server Protocol server for `.rules` files. It keeps the open
// documents, checks each one as `rulec check` would after every change (the document's `use`s
// are read from disk), publishes the diagnostics, and answers hover, completion, definition,
// document symbols, code actions and formatting (lsp/features.h). One thread; requests are
// answered in order.
#pragma once

#include <iosfwd>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "compiler/frontend.h"
#include "lsp/document.h"
#include "lsp/incremental.h"

namespace tranche::lsp {

class Server {
 public:
  explicit Server(compiler::FrontendOptions options);

  // Handles one message; returns what to send back (a response, notifications).
  std::vector<json> handle(const json& message);
  // Serves `in` until `exit` or the end of the input; returns the exit status (0 after a
  // `shutdown`, else 1, as the protocol asks).
  int run(std::istream& in, std::ostream& out);

  bool exited() const { return exited_; }
  // Milliseconds the last analysis took (for `$/tranche/stats` and the benchmark).
  double last_analysis_ms() const { return last_ms_; }

 private:
  json request(const std::string& method, const json& params, bool& handled);
  void notification(const std::string& method, const json& params, std::vector<json>& out);
  void analyze(Document& doc, std::vector<json>& out);
  Document* find(const json& params);

  compiler::FrontendOptions options_;
  std::unique_ptr<ItemCache> cache_;  // incremental parsing, shared by every document
  // Analyses replaced by newer ones: freed once the replies are written, not before (freeing a
  // large program takes as long as a fifth of checking it).
  std::vector<Analysis> retired_;
  std::map<std::string, std::unique_ptr<Document>> docs_;
  bool initialized_ = false, shutdown_ = false, exited_ = false;
  double last_ms_ = 0;
  double last_cpu_ms_ = 0;  // processor time of that analysis (every thread), ms
};

}  // namespace tranche::lsp
