// rulec: the rule compiler's command line. `check` is here; build, disasm and explain come
// with code generation.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "compiler/ast/ast.h"
#include "compiler/check.h"
#include "compiler/diagnostics.h"
#include "compiler/frontend.h"

namespace {

constexpr const char* kUsage =
    "usage: rulec check [options] FILE...\n"
    "\n"
    "Checks .rules files: syntax, names, types and units, stages, lints.\n"
    "Exit status: 0 no errors (warnings allowed), 1 errors, 2 usage error.\n"
    "\n"
    "options:\n"
    "  --format text|json     diagnostics for people (stderr) or one JSON object per line (stdout)\n"
    "  --stdlib DIR           where `use \"printers/...\"` looks first\n"
    "  --set KEY=VALUE        check a command-line override too (an implicit last rule)\n"
    "  -W error, --deny-warnings\n"
    "                         treat warnings as errors\n"
    "  --allow CODE           do not report warning CODE (e.g. --allow W201)\n"
    "  --color auto|always|never\n"
    "  --dump-ast             print the checked AST (for developers)\n"
    "  --time                 print the time of each phase on stderr\n"
    "  -h, --help             this text\n"
    "\n"
    "Diagnostic codes are explained in docs/diagnostics.md.\n";

int usage_error(const std::string& message) {
  std::fprintf(stderr, "rulec: %s\n\n%s", message.c_str(), kUsage);
  return 2;
}

int check(int argc, char** argv) {
  using namespace tranche;
  compiler::FrontendOptions options;
  options.exe_path = argv[0];
  diag::Policy policy;
  std::vector<std::string> files;
  std::vector<std::pair<std::string, std::string>> sets;
  std::string format = "text", color = "auto";
  bool dump = false, timing = false;
  for (int i = 2; i < argc; ++i) {
    std::string_view a = argv[i];
    auto value = [&](std::string_view flag) -> const char* {
      if (i + 1 >= argc) return nullptr;
      (void)flag;
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (a == "--format") {
      const char* v = value(a);
      if (!v || (std::string_view(v) != "text" && std::string_view(v) != "json"))
        return usage_error("--format takes `text` or `json`");
      format = v;
    } else if (a == "--stdlib") {
      const char* v = value(a);
      if (!v) return usage_error("--stdlib needs a directory");
      options.stdlib_dir = v;
    } else if (a == "--set") {
      const char* v = value(a);
      std::string_view kv = v ? v : "";
      size_t eq = kv.find('=');
      if (!v || eq == std::string_view::npos || eq == 0)
        return usage_error("--set takes KEY=VALUE, e.g. --set speed=40");
      sets.emplace_back(std::string(kv.substr(0, eq)), std::string(kv.substr(eq + 1)));
    } else if (a == "-W") {
      const char* v = value(a);
      if (!v || std::string_view(v) != "error") return usage_error("-W takes `error`");
      policy.deny_warnings = true;
    } else if (a == "-Werror" || a == "--deny-warnings") {
      policy.deny_warnings = true;
    } else if (a == "--allow") {
      const char* v = value(a);
      if (!v || v[0] != 'W') return usage_error("--allow takes a warning code, e.g. --allow W201");
      policy.allowed.insert(v);
    } else if (a == "--color") {
      const char* v = value(a);
      std::string_view c = v ? v : "";
      if (c != "auto" && c != "always" && c != "never")
        return usage_error("--color takes auto, always or never");
      color = c;
    } else if (a == "--dump-ast") {
      dump = true;
    } else if (a == "--time") {
      timing = true;
    } else if (a.starts_with("-") && a != "-") {
      return usage_error(std::string("unknown option `").append(a).append("`"));
    } else {
      files.emplace_back(a);
    }
  }
  if (files.empty()) return usage_error("no input files");

  // The phases of compiler::compile(), timed one by one for --time.
  diag::Sink sink;
  ast::Program program;
  using Clock = std::chrono::steady_clock;
  std::vector<std::pair<const char*, double>> times;
  auto t0 = Clock::now();
  auto lap = [&](const char* phase) {
    auto t = Clock::now();
    times.emplace_back(phase, std::chrono::duration<double, std::milli>(t - t0).count());
    t0 = t;
  };
  for (const auto& f : files) compiler::load_file(program, f, options, sink);
  for (const auto& [k, v] : sets) compiler::add_set(program, k, v, sink);
  lap("read and parse");
  bool ok = compiler::check(program, sink) && !sink.has_errors();
  lap("check");
  if (ok) compiler::lint(program, sink);
  lap("lint");
  sink.finish(policy);

  bool use_color =
      color == "always" || (color == "auto" && isatty(2) && std::getenv("NO_COLOR") == nullptr &&
                            std::string_view(std::getenv("TERM") ? std::getenv("TERM") : "dumb") != "dumb");
  for (const auto& d : sink.all()) {
    if (format == "json") {
      std::printf("%s\n", compiler::render_json(program.sources, d).c_str());
    } else {
      std::fprintf(stderr, "%s\n", compiler::render_text(program.sources, d, use_color).c_str());
    }
  }
  lap("report");
  if (dump && program.checked) std::fputs(ast::dump(program).c_str(), stdout);
  if (timing)
    for (const auto& [phase, ms] : times) std::fprintf(stderr, "rulec: %-15s %8.1f ms\n", phase, ms);
  if (format == "text") {
    std::fprintf(stderr, "rulec: %zu rule%s checked: %s\n", program.cascade.size(),
                 program.cascade.size() == 1 ? "" : "s",
                 compiler::summary(sink.errors(), sink.warnings()).c_str());
  }
  return sink.has_errors() ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage_error("no command");
  std::string_view cmd = argv[1];
  if (cmd == "--help" || cmd == "-h" || cmd == "help") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (cmd == "check") return check(argc, argv);
  if (cmd == "build" || cmd == "disasm" || cmd == "explain") {
    std::fprintf(stderr, "rulec: `%s` is not available in this build yet\n", argv[1]);
    return 2;
  }
  return usage_error(std::string("unknown command `").append(cmd).append("`"));
}
