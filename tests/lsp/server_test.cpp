// The language server in process: messages in, messages out, as a client sees them.
#include <doctest/doctest.h>

#include <sstream>

#include "lsp/protocol.h"
#include "lsp/server.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using lsp::json;

namespace {

const char* kUri = "file:///tmp/tranche-lsp-test/a.rules";

struct Session {
  lsp::Server server;
  int next_id = 0;
  std::vector<json> notifications;

  Session() : server(options()) {
    request("initialize", {{"capabilities", json::object()}});
    notify("initialized", json::object());
  }
  static compiler::FrontendOptions options() {
    compiler::FrontendOptions o;
    o.stdlib_dir = (test::source_dir() / "stdlib").string();
    return o;
  }
  json request(const std::string& method, const json& params) {
    auto out = server.handle({{"jsonrpc", "2.0"}, {"id", ++next_id}, {"method", method}, {"params", params}});
    json response;
    for (auto& m : out) (m.contains("id") ? response : notifications.emplace_back()) = m;
    return response;
  }
  void notify(const std::string& method, const json& params) {
    for (auto& m : server.handle({{"jsonrpc", "2.0"}, {"method", method}, {"params", params}}))
      notifications.push_back(m);
  }
  json open(const std::string& text) {
    notify("textDocument/didOpen",
           {{"textDocument", {{"uri", kUri}, {"languageId", "tranche-rules"}, {"version", 1}, {"text", text}}}});
    return last_diagnostics();
  }
  json last_diagnostics() {
    for (auto it = notifications.rbegin(); it != notifications.rend(); ++it)
      if ((*it)["method"] == "textDocument/publishDiagnostics") return (*it)["params"];
    return nullptr;
  }
  json at(const std::string& method, int line, int character) {
    return request(method, {{"textDocument", {{"uri", kUri}}}, {"position", {{"line", line}, {"character", character}}}})["result"];
  }
};

json pos(int line, int character) { return {{"line", line}, {"character", character}}; }

std::vector<std::string> labels(const json& completion) {
  std::vector<std::string> out;
  for (const auto& i : completion["items"]) out.push_back(i["label"]);
  return out;
}
bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

}  // namespace

TEST_CASE("lsp: framing and positions") {
  std::stringstream io;
  lsp::write_message(io, "{\"a\":1}");
  CHECK(io.str() == "Content-Length: 7\r\n\r\n{\"a\":1}");
  CHECK(lsp::read_message(io) == std::optional<std::string>("{\"a\":1}"));
  CHECK_FALSE(lsp::read_message(io).has_value());
  std::stringstream broken("Content-Length: 50\r\n\r\n{}");
  CHECK_FALSE(lsp::read_message(broken).has_value());
  // Columns are UTF-16 units: ö is one, 😀 two; offsets are bytes.
  std::string text = "ab\nö😀x\r\ny";
  lsp::LineIndex index(text);
  CHECK(index.offset({1, 0}) == 3);
  CHECK(index.offset({1, 1}) == 5);
  CHECK(index.offset({1, 3}) == 9);
  CHECK(index.position(9).character == 3);
  CHECK(index.offset({1, 99}) == 10);  // clamped to the line
  CHECK(index.offset({2, 0}) == 12);
  CHECK(lsp::uri_to_path("file:///a/b%20c.rules") == "/a/b c.rules");
  CHECK(lsp::path_to_uri("/a/b c.rules") == "file:///a/b%20c.rules");
}

TEST_CASE("lsp: lifecycle, errors instead of crashes") {
  lsp::Server server(Session::options());
  auto out = server.handle({{"jsonrpc", "2.0"}, {"id", 1}, {"method", "textDocument/hover"}, {"params", json::object()}});
  REQUIRE(out.size() == 1);
  CHECK(out[0]["error"]["code"] == -32002);  // not initialized
  Session s;
  CHECK(s.request("no/such/method", json::object())["error"]["code"] == -32601);
  CHECK(s.request("textDocument/hover", {{"textDocument", 3}})["error"]["code"] == -32603);
  CHECK(s.request("shutdown", nullptr)["result"].is_null());
  s.notify("exit", nullptr);
  CHECK(s.server.exited());
  std::stringstream in, out2;
  lsp::write_message(in, R"({"jsonrpc":"2.0","id":1,"method":"initialize","params":{}})");
  lsp::write_message(in, "not json");
  lsp::write_message(in, R"({"jsonrpc":"2.0","id":2,"method":"shutdown"})");
  lsp::write_message(in, R"({"jsonrpc":"2.0","method":"exit"})");
  lsp::Server served(Session::options());
  CHECK(served.run(in, out2) == 0);
  CHECK(out2.str().find("-32700") != std::string::npos);
}

TEST_CASE("lsp: diagnostics as rulec check gives them, with related locations, tags and links") {
  Session s;
  json d = s.open("rule \"slow\" when layer.indx < 2 { speed = 20 }\nrule \"x\" {\n  before layer { let unused = 1; gcode \"G4\" }\n}\n");
  REQUIRE(d["diagnostics"].size() == 3);
  json e = d["diagnostics"][0];
  CHECK(e["code"] == "E0102");
  CHECK(e["severity"] == 1);
  CHECK(e["range"] == json({{"start", pos(0, 17)}, {"end", pos(0, 27)}}));
  CHECK(e["message"] == "unknown field `layer.indx`\nhelp: did you mean `layer.index`?");
  CHECK(e["codeDescription"]["href"].get<std::string>().ends_with("docs/diagnostics.md#e0102"));
  CHECK(d["diagnostics"][1]["code"] == "E0202");
  CHECK(d["diagnostics"][1]["relatedInformation"][0]["message"] == "set here");
  CHECK(d["diagnostics"][2]["code"] == "W200");
  // Lints once the errors are fixed; an unused `let` is faded.
  s.notify("textDocument/didChange", {{"textDocument", {{"uri", kUri}, {"version", 2}}},
                                      {"contentChanges", json::array({{{"range", {{"start", pos(0, 17)}, {"end", pos(0, 27)}}}, {"text", "layer.index"}},
                                                                     {{"range", {{"start", pos(0, 43)}, {"end", pos(0, 45)}}}, {"text", "20 mm/s"}}})}});
  d = s.last_diagnostics();
  CHECK(d["version"] == 2);
  REQUIRE(d["diagnostics"].size() == 1);
  CHECK(d["diagnostics"][0]["code"] == "W200");
  CHECK(d["diagnostics"][0]["tags"] == json::array({1}));
  // An error in a used file shows on the `use`.
  d = s.open("use \"./no-such-file\"\n");
  REQUIRE(d["diagnostics"].size() == 1);
  CHECK(d["diagnostics"][0]["code"] == "E0010");
}

TEST_CASE("lsp: hover on fields, properties, params, uses and functions") {
  Session s;
  s.open("use \"features/bridges\"\nparam h = 5 mm\nrule when layer.z > h and island.area < 3 mm2 {\n  speed = min(speed, 20 mm/s)\n}\n");
  std::string field = s.at("textDocument/hover", 2, 12)["contents"]["value"];
  CHECK(field.find("`layer.z`") != std::string::npos);
  CHECK(field.find("nozzle height") != std::string::npos);
  std::string prop = s.at("textDocument/hover", 3, 3)["contents"]["value"];
  CHECK(prop.find("`speed`") != std::string::npos);
  CHECK(prop.find("physical range 0.1 mm/s – 1000 mm/s; default 60 mm/s") != std::string::npos);
  std::string param = s.at("textDocument/hover", 2, 20)["contents"]["value"];
  CHECK(param.find("param = `5 mm`") != std::string::npos);
  CHECK(param.find("a.rules:2 (in effect)") != std::string::npos);
  std::string use = s.at("textDocument/hover", 0, 8)["contents"]["value"];
  CHECK(use.find("stdlib/features/bridges.rules") != std::string::npos);
  CHECK(std::string(s.at("textDocument/hover", 3, 11)["contents"]["value"]).find("min(a, b, ...)") != std::string::npos);
  CHECK(s.at("textDocument/hover", 4, 0).is_null());
  // fill_angle: per island, and again per cell.
  s.open("rule when cell.area < 20 mm2 { fill_angle = 0 deg }\n");
  std::string angle = s.at("textDocument/hover", 0, 34)["contents"]["value"];
  CHECK(angle.find("decided at the *island* stage (and again per cell by a rule that reads `cell.*`)") !=
        std::string::npos);
  std::string width = s.at("textDocument/hover", 0, 15)["contents"]["value"];
  CHECK(width.find("`cell.area`") != std::string::npos);
}

TEST_CASE("lsp: completion by context") {
  Session s;
  s.open("param pause_at = 5 mm\nrule when layer.\n");
  CHECK(has(labels(s.at("textDocument/completion", 1, 16)), "z_bottom"));
  auto check = [&](const std::string& text, const std::string& want, const std::string& not_want = "") {
    s.open(text);
    int line = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
    size_t last = text.rfind('\n');
    int character = static_cast<int>(text.size() - (last == std::string::npos ? 0 : last + 1));
    auto got = labels(s.at("textDocument/completion", line, character));
    INFO(text << " -> " << want);
    CHECK(has(got, want));
    if (!not_want.empty()) CHECK_FALSE(has(got, not_want));
  };
  check("rule when path.kind == ", "outer_perimeter", "speed");
  check("rule when path.kind in (infill, ", "bridge");
  check("rule { seam = ", "rear");
  check("rule when below.", "area", "time");
  check("on layer.", "start");
  check("rule { before ", "path", "piece");
  check("rule { replace ", "island", "layer");
  check("rule { speed = 20 ", "mm/s");
  check("use \"printers/", "printers/generic-marlin");
  check("param pause_at = 5 mm\nrule { sp", "speed");
  check("param pause_at = 5 mm\nrule when layer.z > pa", "pause_at");
  check("rule { before path { for pc in path.pieces { comment \"{pc.", "overhang", "area");
  check("rule { replace path { for p in path.points { move to (p.", "x", "overhang");
  // The unit of the field compared first.
  s.open("rule when layer.z > 2 ");
  for (const auto& i : s.at("textDocument/completion", 0, 22)["items"])
    if (i["label"] == "mm") CHECK(i["sortText"] == "0mm");
  // The property's unit first.
  s.open("rule { speed = 20 ");
  for (const auto& i : s.at("textDocument/completion", 0, 18)["items"])
    if (i["label"] == "mm/s") CHECK(i["sortText"] == "0mm/s");
  // ... in a named one-line rule too, and after an earlier statement of the rule.
  for (std::string line : {"rule \"u\" { speed = 20 ", "rule \"u\" { fan = 50%; speed = 20 "}) {
    s.open(line);
    int first = 0;
    json got = s.at("textDocument/completion", 0, static_cast<int>(line.size()));
    INFO(got.dump());
    for (const auto& i : got["items"])
      if (i.value("sortText", "").starts_with("0")) {
        ++first;
        CHECK(i["label"] == "mm/s");
      }
    CHECK(first == 1);
  }
}

TEST_CASE("lsp: definition, symbols, formatting and quick fixes") {
  Session s;
  s.open("use \"features/bridges\"\nparam h = 5 mm\nrule \"a\"when layer.z>h{fan=0%}\nrule \"b\" { fan = 100% }\n");
  json def = s.at("textDocument/definition", 2, 22);
  REQUIRE(def.size() == 1);
  CHECK(def[0]["range"]["start"] == pos(1, 6));
  json use = s.at("textDocument/definition", 0, 8);
  CHECK(use[0]["uri"].get<std::string>().ends_with("stdlib/features/bridges.rules"));
  // Rule "a" never takes effect (W201): its definition lists the rule that overrides it.
  json shadow = s.at("textDocument/definition", 2, 2);
  REQUIRE(shadow.is_array());
  CHECK(shadow[0]["range"]["start"] == pos(3, 0));
  json symbols = s.request("textDocument/documentSymbol", {{"textDocument", {{"uri", kUri}}}})["result"];
  REQUIRE(symbols.size() == 4);
  CHECK(symbols[1]["name"] == "h");
  CHECK(symbols[2]["name"] == "a");
  CHECK(symbols[2]["children"][0]["name"] == "fan");
  json edits = s.request("textDocument/formatting", {{"textDocument", {{"uri", kUri}}}, {"options", json::object()}})["result"];
  REQUIRE(edits.size() == 1);
  CHECK(edits[0]["newText"].get<std::string>().find("rule \"a\" when layer.z > h { fan = 0% }") != std::string::npos);
  s.open("rule { speed = 20; perimeters = island.area / 10 mm2; fan = 50 }\nrule when path.kind == infil { flow = 1 }\n");
  json actions = s.request("textDocument/codeAction", {{"textDocument", {{"uri", kUri}}},
                                                       {"range", {{"start", pos(0, 0)}, {"end", pos(2, 0)}}},
                                                       {"context", {{"diagnostics", json::array()}}}})["result"];
  std::vector<std::string> fixes;
  for (const auto& a : actions) fixes.push_back(a["edit"]["changes"][kUri][0]["newText"]);
  CHECK(has(fixes, "20 mm/s"));
  CHECK(has(fixes, "round(island.area / 10 mm2)"));
  CHECK(has(fixes, "infill"));
}
