// Runs an executable of the build through the shell, as a user does, for tests/apps.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

#include "tests/support/fixtures.h"

namespace tranche::test {

struct Run {
  int status;       // exit status, -1 when it did not exit
  std::string out;  // standard output (and whatever the command line sends there)
};

// Runs `'BUILD/apps/NAME' ARGS` through the shell; `redirect` is appended as is (e.g. "2>&1").
inline Run run_app(const std::string& name, const std::string& args, const std::string& redirect) {
  std::string cmd = "'";
  cmd.append((binary_dir() / "apps" / name).string()).append("' ").append(args).append(" ").append(redirect);
  Run r{-1, ""};
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  int raw = pclose(p);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

}  // namespace tranche::test
