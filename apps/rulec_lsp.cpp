// `rulec lsp [--stdlib DIR]`: the language server (lsp/server.h) on standard input and output.
#include <cstdio>
#include <iostream>
#include <string_view>

#include "apps/rulec_commands.h"
#include "lsp/server.h"

namespace tranche::apps {

int lsp_command(int argc, char** argv) {
  compiler::FrontendOptions options;
  options.exe_path = argv[0];
  for (int i = 2; i < argc; ++i) {
    std::string_view s = argv[i];
    if (s == "--stdlib" && i + 1 < argc) {
      options.stdlib_dir = argv[++i];
    } else if (s == "--stdio") {
      // What some clients add (vscode-languageclient's stdio transport); stdio is the only one.
    } else {
      std::fprintf(stderr, "rulec: lsp takes --stdlib DIR only, found `%s`\n", argv[i]);
      return 2;
    }
  }
  std::ios::sync_with_stdio(false);
  lsp::Server server(options);
  return server.run(std::cin, std::cout);
}

}  // namespace tranche::apps
