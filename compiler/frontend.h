// The front end as a whole: read `.rules` files, expand `use`, add `--set` overrides, check,
// lint. `rulec check` and `tranche slice --rules` call compile(); tests and the fuzzer call the
// pieces with in-memory sources.
//
// `use "NAME"`: NAME starting with `./` or `../` is relative to the using file; an absolute path
// is taken as is; anything else is looked up in the stdlib directory, which is the first
// existing one of: FrontendOptions::stdlib_dir (`--stdlib`), $TRANCHE_STDLIB, the checkout's
// stdlib/ (compiled in), <directory of the executable>/../share/tranche/stdlib. `.rules` is
// added when NAME has no extension. Each file is read once, at its first `use`; a cycle is an
// error naming the chain.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "grammar/ast/ast.h"
#include "grammar/ast/diagnostic.h"
#include "grammar/parse.h"

namespace tranche::compiler {

struct FrontendOptions {
  std::string stdlib_dir;  // `--stdlib`; empty: the other places, in order
  std::string exe_path;    // argv[0], for <exe dir>/../share/tranche/stdlib
  grammar::ParseOptions parse;
  bool lints = true;
  // Reads a file's bytes; nothing if it cannot be read. Tests and the fuzzer replace it; the
  // default reads through base/input_file.h (kRulesInput: at most kMaxFileBytes, from a regular
  // file or a stream alike).
  std::function<std::optional<std::string>(const std::filesystem::path&)> read_file;
  // Parses file `id` of the program; grammar::parse_file when unset. The language server passes
  // one that copies the items of the unchanged parts of a file from its previous parse.
  std::function<ast::File(const ast::SourceMap&, uint32_t id, diag::Sink&)> parser;
};

inline constexpr size_t kMaxFileBytes = 16u << 20;  // kRulesInput.max_bytes

// The candidate stdlib directories, in order of preference, and the one in use (empty if none exists).
std::vector<std::filesystem::path> stdlib_candidates(const FrontendOptions& options);
std::filesystem::path stdlib_dir(const FrontendOptions& options);

// Reads and parses `path` (a user file) and every file it uses, appending their rules to
// program.cascade in order. Returns false if it reported an error.
bool load_file(ast::Program& program, const std::string& path, const FrontendOptions& options,
               diag::Sink& sink);
// Same for a user file already in memory (`path` is used in messages and to resolve `./` uses).
bool load_source(ast::Program& program, const std::string& path, std::string text,
                 const FrontendOptions& options, diag::Sink& sink);

// `--set key=value`: appends the implicit last rule `rule "--set key" { key = value }`. A plain
// number takes the property's unit (`--set speed=40` is 40 mm/s). Diagnostics name `--set`.
// The rule is checked by check(), which reports a value outside the property's physical range
// as an error (E0500) rather than a warning. Returns false if it reported an error.
bool add_set(ast::Program& program, std::string_view key, std::string_view value, diag::Sink& sink);

// The profile `tranche slice` puts below the user's rules, as a source of `use` lines:
// `use "defaults"`, then the printer and the material (stdlib names such as `generic-marlin`,
// or paths to .rules files; empty or "none" for neither). Load it first with load_source.
std::string profile_source(const std::string& printer, const std::string& material);
// Whether a --printer/--material value is a path to a file rather than a stdlib name.
bool profile_is_path(const std::string& name);
inline constexpr const char* kProfileName = "--printer/--material profile";

// The number of `rule` and `on` items in a rules text (the keywords outside braces, strings and
// comments): a cheap count, made before parsing, that refuses more rules than the VM numbers
// (E0013).
size_t count_rule_items(std::string_view text);

// Everything `rulec check` does: load each file, add the `--set`s, check, lint.
ast::Program compile(const std::vector<std::string>& paths,
                     const std::vector<std::pair<std::string, std::string>>& sets,
                     const FrontendOptions& options, diag::Sink& sink);

}  // namespace tranche::compiler
