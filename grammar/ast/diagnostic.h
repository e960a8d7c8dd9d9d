// A diagnostic of the rule compiler: a stable code (E0xxx errors, W2xx lints), a lowercase
// message without trailing period, labelled spans (the first is the primary one, shown with
// `^`), notes and helps. Rendering (text, JSON) is compiler/diagnostics.h; the codes are
// documented in docs/diagnostics.md.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "grammar/ast/source.h"

namespace tranche::diag {

enum class Severity : unsigned char { Error, Warning };

struct Label {
  ast::Span span;
  std::string text;  // may be empty
  bool primary = false;
};

// A suggested edit: the text of `span` becomes `replacement` (an editor offers it as a quick fix).
struct Fix {
  ast::Span span;
  std::string replacement;
};

struct Diagnostic {
  Severity severity = Severity::Error;
  std::string code;  // "E0102", "W201"
  std::string message;
  std::vector<Label> labels;  // labels[0] is the primary one; line 0 there means the whole file
  std::vector<std::string> notes;
  std::vector<std::string> helps;
  std::vector<Fix> fixes;  // edits that apply the first help, when it is one

  Diagnostic& label(const ast::Span& span, std::string text);  // a secondary label
  Diagnostic& note(std::string text);
  Diagnostic& help(std::string text);
  Diagnostic& fix(const ast::Span& span, std::string replacement);
  // help("did you mean `REPLACEMENT`?") and the fix that writes it over `span`.
  Diagnostic& did_you_mean(const ast::Span& span, std::string replacement);
  // The primary span (line 0 for whole-file diagnostics).
  ast::Span span() const;
};

// What to do with warnings: `--allow W201` drops a code, `-W error` makes warnings errors.
struct Policy {
  std::set<std::string> allowed;
  bool deny_warnings = false;
};

// Collects diagnostics in report order. Not thread-safe: one per compilation.
class Sink {
 public:
  Diagnostic& error(std::string code, const ast::Span& span, std::string message, std::string label = {});
  Diagnostic& warning(std::string code, const ast::Span& span, std::string message, std::string label = {});
  void add(Diagnostic d) { all_.push_back(std::move(d)); }

  const std::vector<Diagnostic>& all() const { return all_; }
  size_t errors() const;
  size_t warnings() const;
  bool has_errors() const { return errors() != 0; }

  // Applies `policy` (drops allowed codes, promotes warnings) and sorts by file and position,
  // keeping report order among equal positions.
  void finish(const Policy& policy);

 private:
  std::vector<Diagnostic> all_;
};

}  // namespace tranche::diag
