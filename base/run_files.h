// The files of one run of a tool (`tranche slice`, `rulec build`): every input read through
// base/input_file.h is noted here, and every output (base/output_file.h) is checked against them
// before a byte is written, so that `tranche slice self.stl -o self.stl` or `rulec build my.rules
// -o my.rules` is refused with a message naming both files instead of destroying the input.
// Files are compared by device and inode (a symlink or another spelling of the path is the same
// file); only regular files and FIFOs count (a terminal or /dev/null read and written is harmless).
// Two outputs of one run that are the same file are refused too.
//
// A RunFiles object makes a run: while it lives, inputs are noted and outputs checked. Without
// one (library callers, tests) nothing is noted and nothing is refused. Thread-safe.
#pragma once

#include <sys/stat.h>

#include <string>
#include <string_view>

#include "base/result.h"

namespace tranche {

class RunFiles {
 public:
  RunFiles();
  ~RunFiles();
  RunFiles(const RunFiles&) = delete;
  RunFiles& operator=(const RunFiles&) = delete;

  // `st` is the opened file's fstat; `what` names it ("the model", "the rules file").
  static void note_input(const std::string& path, const struct stat& st, std::string_view what);
  // Notes `path` as an input if it exists (files named on the command line, before they are read).
  static void note_input_path(const std::string& path, std::string_view what);

  // An error if `path` (through symlinks) is an input, or an output already claimed, of the run;
  // else the output is claimed. `what` names the output ("the G-code"); claiming the same file for
  // the same output again is allowed (a tool checks its outputs first, OutputFile again).
  static Status claim_output(const std::string& path, std::string_view what);
  // Same check without claiming: for refusing a run before any work.
  static Status check_output(const std::string& path, std::string_view what);

 private:
  struct State;
  State* state_;
  RunFiles* outer_;
};

}  // namespace tranche
