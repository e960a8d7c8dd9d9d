#include "grammar/ast/diagnostic.h"

#include <algorithm>

namespace tranche::diag {

Diagnostic& Diagnostic::label(const ast::Span& span, std::string text) {
  labels.push_back(Label{span, std::move(text), false});
  return *this;
}

Diagnostic& Diagnostic::note(std::string text) {
  notes.push_back(std::move(text));
  return *this;
}

Diagnostic& Diagnostic::help(std::string text) {
  helps.push_back(std::move(text));
  return *this;
}

Diagnostic& Diagnostic::fix(const ast::Span& span, std::string replacement) {
  fixes.push_back(Fix{span, std::move(replacement)});
  return *this;
}

Diagnostic& Diagnostic::did_you_mean(const ast::Span& span, std::string replacement) {
  help("did you mean `" + replacement + "`?");
  return fix(span, std::move(replacement));
}

ast::Span Diagnostic::span() const {
  for (const auto& l : labels)
    if (l.primary) return l.span;
  return {};
}

namespace {
Diagnostic make(Severity sev, std::string code, const ast::Span& span, std::string message,
                std::string label) {
  Diagnostic d;
  d.severity = sev;
  d.code = std::move(code);
  d.message = std::move(message);
  d.labels.push_back(Label{span, std::move(label), true});  // line 0: the whole file
  return d;
}
}  // namespace

Diagnostic& Sink::error(std::string code, const ast::Span& span, std::string message, std::string label) {
  all_.push_back(make(Severity::Error, std::move(code), span, std::move(message), std::move(label)));
  return all_.back();
}

Diagnostic& Sink::warning(std::string code, const ast::Span& span, std::string message, std::string label) {
  all_.push_back(make(Severity::Warning, std::move(code), span, std::move(message), std::move(label)));
  return all_.back();
}

size_t Sink::errors() const {
  return static_cast<size_t>(std::count_if(
      all_.begin(), all_.end(), [](const Diagnostic& d) { return d.severity == Severity::Error; }));
}

size_t Sink::warnings() const { return all_.size() - errors(); }

void Sink::finish(const Policy& policy) {
  std::erase_if(all_, [&](const Diagnostic& d) {
    return d.severity == Severity::Warning && policy.allowed.count(d.code) != 0;
  });
  if (policy.deny_warnings)
    for (auto& d : all_) d.severity = Severity::Error;
  std::stable_sort(all_.begin(), all_.end(), [](const Diagnostic& a, const Diagnostic& b) {
    ast::Span sa = a.span(), sb = b.span();
    if (sa.file != sb.file) return sa.file < sb.file;
    return sa.offset < sb.offset;
  });
}

}  // namespace tranche::diag
