#include "lsp/server.h"

#include <chrono>
#include <ctime>
#include <iostream>

#include "lsp/features.h"

namespace tranche::lsp {

namespace {

// JSON-RPC error codes.
constexpr int kParseError = -32700;
constexpr int kInvalidRequest = -32600;
constexpr int kMethodNotFound = -32601;
constexpr int kInternalError = -32603;
constexpr int kServerNotInitialized = -32002;

json error_response(const json& id, int code, const std::string& message) {
  return {{"jsonrpc", "2.0"}, {"id", id}, {"error", {{"code", code}, {"message", message}}}};
}

json capabilities() {
  return {
      {"positionEncoding", "utf-16"},
      {"textDocumentSync", {{"openClose", true}, {"change", 2}}},  // incremental
      {"hoverProvider", true},
      {"completionProvider", {{"triggerCharacters", json::array({".", "\"", "/", " ", "(", ","})}}},
      {"definitionProvider", true},
      {"documentSymbolProvider", true},
      {"documentFormattingProvider", true},
      {"codeActionProvider", {{"codeActionKinds", json::array({"quickfix"})}}},
  };
}

}  // namespace

Server::Server(compiler::FrontendOptions options)
    : options_(std::move(options)), cache_(std::make_unique<ItemCache>()) {
  ItemCache* cache = cache_.get();
  options_.parser = [cache](const ast::SourceMap& sources, uint32_t id, diag::Sink& sink) {
    return cache->parse(sources, id, sink);
  };
}

Document* Server::find(const json& params) {
  std::string uri = params.at("textDocument").at("uri").get<std::string>();
  auto it = docs_.find(uri);
  return it == docs_.end() ? nullptr : it->second.get();
}

void Server::analyze(Document& doc, std::vector<json>& out) {
  auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  retired_.push_back(std::move(doc.analysis));
  doc.analysis = lsp::analyze(doc.path, doc.text, options_);
  cache_->sweep();
  last_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  last_cpu_ms_ = 1000.0 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  out.push_back({{"jsonrpc", "2.0"}, {"method", "textDocument/publishDiagnostics"}, {"params", publish_diagnostics(doc)}});
}

void Server::notification(const std::string& method, const json& params, std::vector<json>& out) {
  if (method == "exit") {
    exited_ = true;
  } else if (method == "textDocument/didOpen") {
    const json& td = params.at("textDocument");
    auto doc = std::make_unique<Document>();
    doc->uri = td.at("uri").get<std::string>();
    doc->path = uri_to_path(doc->uri);
    doc->text = td.value("text", std::string());
    doc->version = td.value("version", int64_t{0});
    doc->reindex();
    Document& d = *doc;
    docs_[d.uri] = std::move(doc);
    analyze(d, out);
  } else if (method == "textDocument/didChange") {
    Document* doc = find(params);
    if (!doc) return;
    for (const auto& change : params.value("contentChanges", json::array())) doc->apply(change);
    doc->version = params.at("textDocument").value("version", doc->version + 1);
    analyze(*doc, out);
  } else if (method == "textDocument/didClose") {
    if (Document* doc = find(params)) {
      out.push_back({{"jsonrpc", "2.0"},
                     {"method", "textDocument/publishDiagnostics"},
                     {"params", {{"uri", doc->uri}, {"diagnostics", json::array()}}}});
      docs_.erase(doc->uri);
    }
  } else if (method == "textDocument/didSave") {
    // A save changes files other documents `use`: check them all again.
    for (auto& [uri, doc] : docs_) analyze(*doc, out);
  }
}

json Server::request(const std::string& method, const json& params, bool& handled) {
  handled = true;
  if (method == "initialize") {
    initialized_ = true;
    return {{"capabilities", capabilities()}, {"serverInfo", {{"name", "rulec lsp"}, {"version", "0.1.0"}}}};
  }
  if (method == "shutdown") {
    shutdown_ = true;
    return nullptr;
  }
  if (method == "$/tranche/stats") return {{"lastAnalysisMs", last_ms_}, {"lastAnalysisCpuMs", last_cpu_ms_}, {"documents", docs_.size()}};
  Document* doc = params.contains("textDocument") ? find(params) : nullptr;
  if (method == "textDocument/hover") return doc ? hover(*doc, params.at("position")) : json(nullptr);
  if (method == "textDocument/completion")
    return doc ? completion(*doc, params.at("position"), options_) : json(nullptr);
  if (method == "textDocument/definition") return doc ? definition(*doc, params.at("position")) : json(nullptr);
  if (method == "textDocument/documentSymbol") return doc ? document_symbols(*doc) : json(nullptr);
  if (method == "textDocument/codeAction") return doc ? code_actions(*doc, params) : json(nullptr);
  if (method == "textDocument/formatting") return doc ? formatting(*doc) : json(nullptr);
  handled = false;
  return nullptr;
}

std::vector<json> Server::handle(const json& message) {
  retired_.clear();  // callers that do not go through run()
  std::vector<json> out;
  if (!message.is_object()) {
    out.push_back(error_response(nullptr, kInvalidRequest, "a message is a JSON object"));
    return out;
  }
  std::string method = message.value("method", std::string());
  json params = message.value("params", json::object());
  bool is_request = message.contains("id");
  if (method.empty()) return out;  // a response to a request of ours: we send none
  json id = is_request ? message["id"] : json(nullptr);
  try {
    if (!is_request) {
      if (initialized_ || method == "exit") notification(method, params, out);
      return out;
    }
    if (!initialized_ && method != "initialize") {
      out.push_back(error_response(id, kServerNotInitialized, "the server is not initialized"));
      return out;
    }
    if (shutdown_ && method != "shutdown") {
      out.push_back(error_response(id, kInvalidRequest, "the server is shutting down"));
      return out;
    }
    bool handled = false;
    json result = request(method, params, handled);
    if (!handled)
      out.push_back(error_response(id, kMethodNotFound, "unknown method " + method));
    else
      out.push_back({{"jsonrpc", "2.0"}, {"id", id}, {"result", result}});
  } catch (const std::exception& e) {
    // Malformed params (a missing field, a wrong type): an error for this request, not a crash.
    if (is_request) out.push_back(error_response(id, kInternalError, std::string("bad request: ") + e.what()));
  }
  return out;
}

int Server::run(std::istream& in, std::ostream& out) {
  while (!exited_) {
    std::optional<std::string> body = read_message(in);
    if (!body) break;
    json message = json::parse(*body, nullptr, /*allow_exceptions=*/false);
    std::vector<json> replies;
    if (message.is_discarded())
      replies.push_back(error_response(nullptr, kParseError, "the message is not valid JSON"));
    else
      replies = handle(message);
    for (const auto& r : replies) write_message(out, r.dump(-1, ' ', false, json::error_handler_t::replace));
    retired_.clear();
  }
  return shutdown_ ? 0 : 1;
}

}  // namespace tranche::lsp
