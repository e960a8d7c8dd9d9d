// `rulec fmt [--check] FILE...|-`: rewrites .rules files (and the ```rules blocks of markdown
// files) in the canonical layout of grammar/format.h.
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "apps/rulec_commands.h"
#include "base/input_file.h"
#include "base/output_file.h"
#include "compiler/diagnostics.h"
#include "grammar/format.h"

namespace tranche::apps {

namespace {

constexpr const char* kFmtUsage =
    "usage: rulec fmt [--check] FILE...\n"
    "       rulec fmt -          (reads standard input, writes the formatted text on standard output)\n";

// The canonical text of `text`, or nothing after printing its syntax errors.
std::optional<std::string> canonical(const std::string& path, std::string text) {
  if (path.ends_with(".md")) return grammar::format_markdown(text);
  ast::SourceMap sources;
  uint32_t id = sources.add(path, std::move(text));
  diag::Sink sink;
  auto out = grammar::format_file(sources, id, sink);
  sink.finish({});
  for (const auto& d : sink.all()) std::fprintf(stderr, "%s\n", compiler::render_text(sources, d, false).c_str());
  return out;
}

}  // namespace

int fmt_command(int argc, char** argv) {
  bool check = false;
  std::vector<std::string> files;
  for (int i = 2; i < argc; ++i) {
    std::string_view s = argv[i];
    if (s == "--check") {
      check = true;
    } else if (s == "-h" || s == "--help") {
      std::fputs(kFmtUsage, stdout);
      return 0;
    } else if (s.starts_with("-") && s != "-") {
      std::fprintf(stderr, "rulec: unknown option `%s`\n\n%s", argv[i], kFmtUsage);
      return 2;
    } else {
      files.emplace_back(s);
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "rulec: no input files\n\n%s", kFmtUsage);
    return 2;
  }
  int status = 0;
  for (const auto& file : files) {
    if (file == "-") {
      auto in = InputFile::adopt(0, "<stdin>", kRulesInput);
      auto text = in ? in->read_rest() : Result<std::string>(in.error());
      if (!text) {
        std::fprintf(stderr, "rulec: error: %s\n", text.error().to_string().c_str());
        return 1;
      }
      auto out = canonical("<stdin>", *text);
      if (!out) return 1;
      std::fwrite(out->data(), 1, out->size(), stdout);
      if (check && *out != *text) status = 1;
      continue;
    }
    auto text = read_input(file, kRulesInput);
    if (!text) {
      std::fprintf(stderr, "rulec: error: %s\n", text.error().to_string().c_str());
      status = 1;
      continue;
    }
    auto out = canonical(file, *text);
    if (!out) {
      std::fprintf(stderr, "rulec: %s not formatted: it has syntax errors\n", file.c_str());
      status = 1;
      continue;
    }
    if (*out == *text) continue;
    if (check) {
      std::fprintf(stderr, "rulec: %s is not formatted (run `rulec fmt %s`)\n", file.c_str(), file.c_str());
      status = 1;
      continue;
    }
    auto f = OutputFile::create(file, "the formatted file");
    Status written = f ? f->write(*out) : Status(f.error());
    if (written) written = f->commit();
    if (!written) {
      std::fprintf(stderr, "rulec: error: %s\n", written.error().to_string().c_str());
      status = 1;
      continue;
    }
    std::fprintf(stderr, "rulec: formatted %s\n", file.c_str());
  }
  return status;
}

}  // namespace tranche::apps
