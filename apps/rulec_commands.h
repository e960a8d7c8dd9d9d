// rulec's commands that live in files of their own (rulec.cpp dispatches to them).
#pragma once

namespace tranche::apps {

// `rulec fmt [--check] FILE...|-`; returns the exit status.
int fmt_command(int argc, char** argv);
// `rulec lsp [--stdlib DIR]`: the language server on standard input and output.
int lsp_command(int argc, char** argv);

}  // namespace tranche::apps
