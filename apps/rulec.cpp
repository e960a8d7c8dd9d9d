// rulec: the rule compiler's command line: check, build, disasm, explain.
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include "apps/rulec_commands.h"
#include "base/input_file.h"
#include "base/memory.h"
#include "base/output_file.h"
#include "base/run_files.h"
#include "grammar/ast/ast.h"
#include "compiler/check.h"
#include "compiler/codegen.h"
#include "compiler/diagnostics.h"
#include "compiler/explain.h"
#include "compiler/frontend.h"
#include "runtime/vm/bundle.h"
#include "runtime/vm/verify.h"
#include "runtime/vm/vm.h"

namespace {

constexpr const char* kUsage =
    "usage: rulec check [options] FILE...\n"
    "       rulec build [options] FILE... -o OUT.bundle [--no-debug]\n"
    "       rulec disasm FILE.bundle|FILE.rules...\n"
    "       rulec explain [options] FILE... --at \"layer.index=3, path.kind=outer_perimeter\"\n"
    "       rulec fmt [--check] FILE...|-\n"
    "       rulec lsp [--stdlib DIR]\n"
    "\n"
    "check    checks .rules files: syntax, names, types and units, stages, lints\n"
    "build    checks, then compiles the files (in cascade order) into one bundle for\n"
    "         `tranche slice --rules OUT.bundle`\n"
    "disasm   prints a bundle's (or compiled rules') tables and bytecode\n"
    "explain  for one context, says which rule decides each slot, the chain of values that led\n"
    "         to it, and why later rules do not match\n"
    "fmt      rewrites .rules files (and the ```rules blocks of .md files) in the canonical layout;\n"
    "         `-` formats standard input to standard output\n"
    "lsp      a Language Server Protocol server on standard input and output, for editors\n"
    "         (editors/README.md)\n"
    "\n"
    "Exit status: 0 no errors (warnings allowed), 1 errors, 2 usage error.\n"
    "\n"
    "options:\n"
    "  --format text|json|sarif\n"
    "                         diagnostics for people (stderr), one JSON object per line (stdout),\n"
    "                         or one SARIF 2.1.0 log (stdout)\n"
    "  --stdlib DIR           where `use \"printers/...\"` looks first\n"
    "  --set KEY=VALUE        a command-line override too (an implicit last rule)\n"
    "  -W error, --deny-warnings\n"
    "                         treat warnings as errors\n"
    "  --allow CODE           do not report warning CODE (e.g. --allow W201)\n"
    "  --color auto|always|never\n"
    "  -o, --output FILE      (build) the bundle to write\n"
    "  --no-debug             (build) leave out the debug section (file:line:col of the code)\n"
    "  --at FIELD=VALUE,...   (explain) the context: fields (`island.area=3mm2`), other layers'\n"
    "                         (`below.area=30mm2`, `above.z=0.6`, `layers[3].z=0.8`), and properties\n"
    "                         as the lower layers of the cascade give them (`speed=60`)\n"
    "  --slot NAME            (explain) show only this slot (`speed`, `before path`); repeatable\n"
    "  --printer NAME, --material NAME\n"
    "                         put the profile tranche slice uses below the files (stdlib/defaults.rules,\n"
    "                         the printer, the material); explain does so by default\n"
    "                         (generic-marlin, pla); `none` leaves one out\n"
    "  --profile, --no-profile\n"
    "                         with or without that profile (explain: with; the others: without)\n"
    "  --dump-ast             (check) print the checked AST\n"
    "  --time                 print the time of each phase on stderr\n"
    "  --check                (fmt) change nothing; exit with 1 if a file is not formatted\n"
    "  -h, --help             this text\n"
    "\n"
    "Diagnostic codes are explained in docs/diagnostics.md; the bundle format in docs/bundles.md.\n";

int usage_error(const std::string& message) {
  std::fprintf(stderr, "rulec: %s\n\n%s", message.c_str(), kUsage);
  return 2;
}

struct Args {
  std::string command;
  tranche::compiler::FrontendOptions options;
  tranche::diag::Policy policy;
  std::vector<std::string> files;
  std::vector<std::pair<std::string, std::string>> sets;
  std::string format = "text", color = "auto", output, at;
  std::string printer = "generic-marlin", material = "pla";
  std::vector<std::string> slots;
  bool dump = false, timing = false, debug = true, has_at = false, profile = false;
};

// Parses the options shared by every command; returns an exit code for usage errors.
int parse(int argc, char** argv, Args& a) {
  a.command = argv[1];
  a.options.exe_path = argv[0];
  for (int i = 2; i < argc; ++i) {
    std::string_view s = argv[i];
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    if (s == "-h" || s == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (s == "--format") {
      const char* v = value();
      if (!v || (std::string_view(v) != "text" && std::string_view(v) != "json" && std::string_view(v) != "sarif"))
        return usage_error("--format takes `text`, `json` or `sarif`");
      a.format = v;
    } else if (s == "--stdlib") {
      const char* v = value();
      if (!v) return usage_error("--stdlib needs a directory");
      a.options.stdlib_dir = v;
    } else if (s == "--set") {
      const char* v = value();
      std::string_view kv = v ? v : "";
      size_t eq = kv.find('=');
      if (!v || eq == std::string_view::npos || eq == 0) return usage_error("--set takes KEY=VALUE, e.g. --set speed=40");
      a.sets.emplace_back(std::string(kv.substr(0, eq)), std::string(kv.substr(eq + 1)));
    } else if (s == "-W") {
      const char* v = value();
      if (!v || std::string_view(v) != "error") return usage_error("-W takes `error`");
      a.policy.deny_warnings = true;
    } else if (s == "-Werror" || s == "--deny-warnings") {
      a.policy.deny_warnings = true;
    } else if (s == "--allow") {
      const char* v = value();
      if (!v || v[0] != 'W') return usage_error("--allow takes a warning code, e.g. --allow W201");
      a.policy.allowed.insert(v);
    } else if (s == "--color") {
      const char* v = value();
      std::string_view c = v ? v : "";
      if (c != "auto" && c != "always" && c != "never") return usage_error("--color takes auto, always or never");
      a.color = c;
    } else if (s == "-o" || s == "--output") {
      const char* v = value();
      if (!v) return usage_error("-o needs a file name");
      a.output = v;
    } else if (s == "--no-debug") {
      a.debug = false;
    } else if (s == "--at") {
      const char* v = value();
      if (!v) return usage_error("--at needs a context, e.g. --at \"layer.index=3, path.kind=infill\"");
      a.at = v;
      a.has_at = true;
    } else if (s == "--printer" || s == "--material") {
      const char* v = value();
      if (!v || !*v) return usage_error(std::string(s) + " needs a name or a file");
      (s == "--printer" ? a.printer : a.material) = v;
      a.profile = true;
    } else if (s == "--slot") {
      const char* v = value();
      if (!v || !*v) return usage_error("--slot needs a property, a hook or a replacement, e.g. --slot speed");
      a.slots.emplace_back(v);
    } else if (s == "--profile") {
      a.profile = true;
    } else if (s == "--no-profile") {
      a.profile = false;
    } else if (s == "--dump-ast") {
      a.dump = true;
    } else if (s == "--time") {
      a.timing = true;
    } else if (s.starts_with("-") && s != "-") {
      return usage_error(std::string("unknown option `").append(s).append("`"));
    } else {
      a.files.emplace_back(s);
    }
  }
  if (a.files.empty()) return usage_error("no input files");
  return -1;
}

// Loads, checks and lints; prints the diagnostics. Returns whether there were no errors.
struct Front {
  tranche::diag::Sink sink;
  tranche::ast::Program program;
  std::vector<std::pair<const char*, double>> times;
};

bool front(const Args& a, Front& f) {
  using namespace tranche;
  using Clock = std::chrono::steady_clock;
  auto t0 = Clock::now();
  auto lap = [&](const char* phase) {
    auto t = Clock::now();
    f.times.emplace_back(phase, std::chrono::duration<double, std::milli>(t - t0).count());
    t0 = t;
  };
  // The profile first, as `tranche slice` loads it (explain does by default; the others on request).
  if (a.profile)
    compiler::load_source(f.program, compiler::kProfileName, compiler::profile_source(a.printer, a.material),
                          a.options, f.sink);
  for (const auto& file : a.files) compiler::load_file(f.program, file, a.options, f.sink);
  for (const auto& [k, v] : a.sets) compiler::add_set(f.program, k, v, f.sink);
  lap("read and parse");
  bool ok = compiler::check(f.program, f.sink) && !f.sink.has_errors();
  lap("check");
  if (ok) compiler::lint(f.program, f.sink);
  lap("lint");
  f.sink.finish(a.policy);
  bool use_color = a.color == "always" ||
                   (a.color == "auto" && isatty(2) && std::getenv("NO_COLOR") == nullptr &&
                    std::string_view(std::getenv("TERM") ? std::getenv("TERM") : "dumb") != "dumb");
  if (a.format == "sarif") std::fputs(compiler::render_sarif(f.program.sources, f.sink.all()).c_str(), stdout);
  for (const auto& d : f.sink.all()) {
    if (a.format == "sarif") break;
    if (a.format == "json")
      std::printf("%s\n", compiler::render_json(f.program.sources, d).c_str());
    else
      std::fprintf(stderr, "%s\n", compiler::render_text(f.program.sources, d, use_color).c_str());
  }
  lap("report");
  return !f.sink.has_errors();
}

void print_times(const Args& a, const Front& f) {
  if (a.timing)
    for (const auto& [phase, ms] : f.times) std::fprintf(stderr, "rulec: %-15s %8.1f ms\n", phase, ms);
}

int check(const Args& a) {
  using namespace tranche;
  Front f;
  bool ok = front(a, f);
  if (a.dump && f.program.checked) std::fputs(ast::dump(f.program).c_str(), stdout);
  print_times(a, f);
  if (a.format == "text")
    std::fprintf(stderr, "rulec: %zu rule%s checked: %s\n", f.program.cascade.size(),
                 f.program.cascade.size() == 1 ? "" : "s", compiler::summary(f.sink.errors(), f.sink.warnings()).c_str());
  return ok ? 0 : 1;
}

int build(const Args& a) {
  using namespace tranche;
  if (a.output.empty()) return usage_error("build needs an output: -o FILE.bundle");
  // The rules files (and every file they use) are inputs that the bundle may not replace.
  RunFiles run;
  for (const auto& file : a.files) RunFiles::note_input_path(file, "a rules file");
  if (a.profile && compiler::profile_is_path(a.printer)) RunFiles::note_input_path(a.printer, "the printer profile");
  if (a.profile && compiler::profile_is_path(a.material)) RunFiles::note_input_path(a.material, "the material profile");
  if (Status s = RunFiles::claim_output(a.output, "the bundle"); !s) {
    std::fprintf(stderr, "rulec: error: %s\n", s.error().to_string().c_str());
    return 1;
  }
  Front f;
  if (!front(a, f)) {
    std::fprintf(stderr, "rulec: %s; no bundle written\n", compiler::summary(f.sink.errors(), f.sink.warnings()).c_str());
    return 1;
  }
  compiler::CodegenOptions o;
  o.debug = a.debug;
  auto p = compiler::generate(f.program, o);
  if (!p) {
    std::fprintf(stderr, "rulec: error: %s\n", p.error().to_string().c_str());
    return 1;
  }
  std::string bytes = vm::write_bundle(*p, a.debug);
  // Written next to the target, then renamed: never a half-written bundle.
  auto file = OutputFile::create(a.output, "the bundle");
  Status written = file ? file->write(bytes) : Status(file.error());
  if (written) written = file->commit();
  if (!written) {
    std::fprintf(stderr, "rulec: error: %s\n", written.error().to_string().c_str());
    return 1;
  }
  print_times(a, f);
  std::fprintf(stderr, "rulec: %zu rule%s, %zu instructions, %zu bytes -> %s%s\n", p->rules.size(),
               p->rules.size() == 1 ? "" : "s", p->code.size(), bytes.size(), a.output.c_str(),
               f.sink.warnings() ? (" (" + compiler::summary(0, f.sink.warnings()) + ")").c_str() : "");
  return 0;
}

int disasm(const Args& a) {
  using namespace tranche;
  int status = 0;
  for (const auto& file : a.files) {
    auto bytes = read_input(file, InputKind{"the rules file or bundle", kBundleInput.max_bytes});
    if (!bytes) {
      std::fprintf(stderr, "rulec: error: %s\n", bytes.error().to_string().c_str());
      status = 1;
      continue;
    }
    if (!vm::looks_like_bundle(*bytes)) {
      Args one = a;
      one.files = {file};
      Front f;
      if (!front(one, f)) {
        status = 1;
        continue;
      }
      auto p = compiler::generate(f.program);
      if (!p) {
        std::fprintf(stderr, "rulec: error: %s\n", p.error().to_string().c_str());
        status = 1;
        continue;
      }
      std::printf("; %s (compiled)\n%s", file.c_str(), vm::disassemble(*p).c_str());
      continue;
    }
    auto p = vm::read_bundle(*bytes, file);
    if (!p) {
      std::fprintf(stderr, "rulec: error: %s\n", p.error().to_string().c_str());
      status = 1;
      continue;
    }
    std::printf("; %s\n%s", file.c_str(), vm::disassemble(*p).c_str());
  }
  return status;
}

int explain(const Args& a) {
  using namespace tranche;
  if (!a.has_at) return usage_error("explain needs a context: --at \"layer.index=3, path.kind=infill\"");
  Front f;
  if (!front(a, f)) return 1;
  auto p = compiler::generate(f.program);
  if (!p) {
    std::fprintf(stderr, "rulec: error: %s\n", p.error().to_string().c_str());
    return 1;
  }
  auto rs = vm::RuleSet::create(std::move(*p));
  if (!rs) {
    std::fprintf(stderr, "rulec: error: %s\n", rs.error().to_string().c_str());
    return 1;
  }
  auto text = compiler::explain(f.program, **rs, a.at, a.slots);
  if (!text) {
    std::fprintf(stderr, "rulec: error: %s\n", text.error().to_string().c_str());
    return 1;
  }
  std::fputs(text->c_str(), stdout);
  return 0;
}

}  // namespace

static int run(int argc, char** argv) {
  if (argc < 2) return usage_error("no command");
  std::string_view cmd = argv[1];
  if (cmd == "--help" || cmd == "-h" || cmd == "help") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (cmd == "fmt") return tranche::apps::fmt_command(argc, argv);
  if (cmd == "lsp") return tranche::apps::lsp_command(argc, argv);
  if (cmd != "check" && cmd != "build" && cmd != "disasm" && cmd != "explain")
    return usage_error(std::string("unknown command `").append(cmd).append("`"));
  Args a;
  a.profile = cmd == "explain";  // explain shows what tranche slice does: with the profile
  if (int rc = parse(argc, argv, a); rc >= 0) return rc;
  if (cmd == "check") return check(a);
  if (cmd == "build") return build(a);
  if (cmd == "disasm") return disasm(a);
  return explain(a);
}

int main(int argc, char** argv) {
  tranche::load_unwinder();  // before memory runs short: out of memory must end in our message, not an abort
  std::signal(SIGPIPE, SIG_IGN);  // a reader that goes away is a write error with a message
  try {
    return run(argc, argv);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "rulec: error: %s\n", tranche::out_of_memory("", "compiling", "simplify the rules").message.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rulec: internal error: %s; please report it\n", e.what());
  }
  return 1;
}
