// The canonical layout of a `.rules` file (`rulec fmt`, the language server's formatting).
//
// It works on the tokens, so everything the user wrote is kept (parentheses, number spellings,
// strings, comments); only the white space between tokens changes:
// - two spaces of indentation per block, four more for a statement continued on the next line
//   (line breaks inside a statement are kept where the user put them);
// - one space around operators and after `,` and `:`, none inside brackets, after a unary `-` or around
//   `.` and `..`; `%` and `°` touch their number, other units are one space away (`20 mm/s`);
// - a block written on one line stays on one line (`{ a; b }`) while it fits in `width`
//   columns and holds no comment; otherwise each statement goes on a line of its own;
// - `{` ends the line of its header; `else` follows `}` unless it starts its own line;
// - comments stay where they are: at the end of their line, or on a line of their own at the
//   indentation of what follows; at most one blank line in a row, none after `{` or before `}`;
// - the file keeps its byte order mark and line ending style, and ends with one line ending.
// The result formats to itself. A file with syntax errors is not formatted.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "grammar/ast/diagnostic.h"
#include "grammar/ast/source.h"

namespace tranche::grammar {

struct FormatOptions {
  int width = 100;  // columns a one-line block may reach before it is broken
};

// The canonical text of file `file_id`, or nothing after reporting its syntax errors to `sink`.
std::optional<std::string> format_file(const ast::SourceMap& sources, uint32_t file_id, diag::Sink& sink,
                                       const FormatOptions& options = {});

// A markdown text with each ```rules block that parses in canonical layout (the others, such
// as examples of syntax errors, as they are).
std::string format_markdown(std::string_view text, const FormatOptions& options = {});

}  // namespace tranche::grammar
