// tranche: the slicer's command line. Parses the arguments (apps/slice_args.h) and runs the
// slice (apps/slice_command.h); prints warnings, errors and the files written.
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include "apps/slice_args.h"
#include "apps/slice_command.h"
#include "base/memory.h"

namespace {

int usage_error(const std::string& msg) {
  std::fprintf(stderr, "tranche: %s\n\n%s", msg.c_str(), tranche::app::slice_usage().c_str());
  return 2;
}

int run(int argc, char** argv) {
  if (argc < 2) return usage_error("missing command");
  std::string_view cmd = argv[1];
  if (cmd == "-h" || cmd == "--help" || cmd == "help") {
    std::fputs(tranche::app::slice_usage().c_str(), stdout);
    return 0;
  }
  if (cmd != "slice") return usage_error("unknown command '" + std::string(cmd) + "'");
  auto args = tranche::app::parse_slice_args(std::vector<std::string>(argv + 2, argv + argc), !isatty(STDERR_FILENO));
  if (!args) return usage_error(args.error().message);
  if (args->help) {
    std::fputs(tranche::app::slice_usage().c_str(), stdout);
    return 0;
  }

  if (args->max_memory_mb)
    if (tranche::Status s = tranche::set_memory_limit(args->max_memory_mb); !s) return usage_error(s.error().to_string());

  tranche::Report report;
  auto result = tranche::app::slice(args->slice, args->plate, report);
  for (const auto& w : report.warnings())
    std::fprintf(stderr, "warning: %s%s%s\n", w.where.c_str(), w.where.empty() ? "" : ": ", w.message.c_str());
  if (!result) {
    std::fprintf(stderr, "error: %s\n", result.error().to_string().c_str());
    return 1;
  }
  std::fputs(result->explanation.c_str(), stdout);
  for (const auto& f : result->written) std::printf("wrote %s\n", f.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  tranche::load_unwinder();  // before memory runs short: out of memory must end in our message, not an abort
  std::signal(SIGPIPE, SIG_IGN);  // a reader that goes away is a write error with a message, not a kill
  // Anything that escapes the library's own error handling still ends in a message and exit 1,
  // never an abort; the outputs' temporary files are removed by their destructors.
  try {
    return run(argc, argv);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "error: %s\n", tranche::out_of_memory("", "slicing").message.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: internal error: %s; please report it\n", e.what());
  }
  return 1;
}
