// The rulec executable's fmt and lsp commands, run as a user or an editor runs them.
#include <doctest/doctest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <string>

#include "tests/apps/run_command.h"
#include "tests/support/fixtures.h"

namespace fs = std::filesystem;
using namespace tranche::test;

namespace {


// Runs `rulec ARGS` through the shell, with `input` on its standard input.
Run rulec(const std::string& args, const std::string& input = "") {
  TempDir dir("rulec-in");
  fs::path in = dir.path() / "stdin";
  std::ofstream(in, std::ios::binary) << input;
  return run_app("rulec", args, "< '" + in.string() + "' 2>&1");
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::string frame(const std::string& body) {
  std::string out = "Content-Length: ";
  out.append(std::to_string(body.size())).append("\r\n\r\n").append(body);
  return out;
}

}  // namespace

TEST_CASE("rulec fmt: --check changes nothing and fails on an unformatted file; fmt rewrites it") {
  TempDir dir("rulec-fmt");
  fs::path f = dir.path() / "a.rules";
  write(f, "rule \"x\"when layer.index<2{speed=20 mm/s}\n");
  Run check = rulec("fmt --check '" + f.string() + "'");
  CHECK(check.status == 1);
  CHECK(check.out.find("is not formatted") != std::string::npos);
  CHECK(read_file(f) == "rule \"x\"when layer.index<2{speed=20 mm/s}\n");
  Run fmt = rulec("fmt '" + f.string() + "'");
  CHECK(fmt.status == 0);
  CHECK(read_file(f) == "rule \"x\" when layer.index < 2 { speed = 20 mm/s }\n");
  CHECK(rulec("fmt --check '" + f.string() + "'").status == 0);
  // No temporary file is left beside it.
  size_t files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++files;
  CHECK(files == 1);
}

TEST_CASE("rulec fmt: a file with syntax errors is reported and left alone; - formats standard input") {
  TempDir dir("rulec-fmt-bad");
  fs::path f = dir.path() / "bad.rules";
  write(f, "rule \"x\" { speed = }\n");
  Run r = rulec("fmt '" + f.string() + "'");
  CHECK(r.status == 1);
  CHECK(r.out.find("error[E0004]") != std::string::npos);
  CHECK(r.out.find("= docs: docs/diagnostics.md#e0004") != std::string::npos);
  CHECK(read_file(f) == "rule \"x\" { speed = }\n");
  Run in = rulec("fmt -", "rule{fan=0%}\n");
  CHECK(in.status == 0);
  CHECK(in.out == "rule { fan = 0% }\n");
  CHECK(rulec("fmt --nope x.rules").status == 2);
  CHECK(rulec("fmt").status == 2);
}

TEST_CASE("rulec lsp: initialize, shutdown and exit over standard input and output") {
  std::string input = frame(R"({"jsonrpc":"2.0","id":1,"method":"initialize","params":{"capabilities":{}}})") +
                      frame(R"({"jsonrpc":"2.0","method":"initialized","params":{}})") +
                      frame(R"({"jsonrpc":"2.0","id":2,"method":"shutdown"})") +
                      frame(R"({"jsonrpc":"2.0","method":"exit"})");
  Run r = rulec("lsp", input);
  CHECK(r.status == 0);
  CHECK(r.out.find("\"documentFormattingProvider\":true") != std::string::npos);
  CHECK(r.out.find("Content-Length: ") == 0);
  // Without `shutdown` first, `exit` ends the server with status 1, as the protocol asks.
  CHECK(rulec("lsp", frame(R"({"jsonrpc":"2.0","method":"exit"})")).status == 1);
  CHECK(rulec("lsp --port 3").status == 2);
}
