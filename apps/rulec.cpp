// rulec: the rule compiler's command line (check, build, disasm, explain).
#include <cstdio>
#include <string_view>

int main(int argc, char** argv) {
  if (argc < 2 || std::string_view(argv[1]) == "--help" || std::string_view(argv[1]) == "-h") {
    std::puts("usage: rulec check|build|disasm|explain ...");
    return argc < 2 ? 2 : 0;
  }
  std::fprintf(stderr, "rulec: '%s' is not available in this build yet\n", argv[1]);
  return 2;
}
