#include "compiler/load_rules.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <tuple>

#include "base/input_file.h"
#include "compiler/check.h"
#include "compiler/codegen.h"
#include "compiler/diagnostics.h"
#include "compiler/frontend.h"
#include "runtime/vm/bundle.h"
#include "runtime/vm/link.h"

namespace tranche::compiler {

namespace {

// A --rules file: a bundle (up to kBundleInput's bound) or rules text (up to kRulesInput's), read
// once, so that a FIFO or a pipe can be given too.
Result<std::string> read_rules_or_bundle(const std::string& path) {
  constexpr InputKind kRulesOrBundle{"the rules file", kBundleInput.max_bytes};
  auto f = InputFile::open(path, kRulesOrBundle);
  if (!f) return f.error();
  // The first bytes say which it is, and so which bound applies to the rest.
  std::string head(sizeof vm::kBundleMagic, '\0');
  size_t got = 0;
  while (got < head.size()) {
    auto n = f->read(head.data() + got, head.size() - got);
    if (!n) return n.error();
    if (*n == 0) break;
    got += *n;
  }
  head.resize(got);
  f->set_kind(vm::looks_like_bundle(head) ? kBundleInput : kRulesInput);
  if (!f->regular() || f->size() <= kRulesInput.max_bytes || vm::looks_like_bundle(head)) {
    auto rest = f->read_rest();
    if (!rest) return rest.error();
    return head + *rest;
  }
  return Error{path, fmt::format("the rules file is {}, more than the {} read at most (docs/cli.md, \"Files and "
                                 "safety\"); check that this is the right file",
                                 size_text(f->size()), size_text(kRulesInput.max_bytes))};
}

using Sources = std::vector<std::pair<std::string, std::string>>;  // path, text

// Compiles `.rules` files (and --set expressions) as one program; `profile` first when set.
Result<vm::Program> compile(const std::string* profile, const Sources& files,
                            const std::vector<std::pair<std::string, std::string>>& sets,
                            const std::string& stdlib_dir, Report& report) {
  FrontendOptions options;
  options.stdlib_dir = stdlib_dir;
  diag::Sink sink;
  ast::Program program;
  if (profile) load_source(program, kProfileName, *profile, options, sink);
  for (const auto& [path, text] : files) load_source(program, path, text, options, sink);
  for (const auto& [k, v] : sets) add_set(program, k, v, sink);
  if (check(program, sink) && !sink.has_errors()) lint(program, sink);
  sink.finish({});
  std::string first;
  std::string where;
  for (const auto& d : sink.all()) {
    if (d.severity == diag::Severity::Warning) {
      const auto& l = d.labels.empty() ? diag::Label{} : d.labels[0];
      std::string at = l.span.valid() ? fmt::format("{}:{}:{}", program.sources.file(l.span.file).path, l.span.line,
                                                    l.span.col)
                                      : std::string();
      report.warn("rules", at, fmt::format("warning[{}]: {} (rulec check explains)", d.code, d.message));
    } else if (first.empty()) {
      first = render_text(program.sources, d, false);
      if (!d.labels.empty() && d.labels[0].span.valid())
        where = program.sources.file(d.labels[0].span.file).path;
    }
  }
  if (sink.has_errors()) {
    std::string what = !where.empty() ? where : !files.empty() ? files.front().first : profile ? std::string("profile") : std::string("--set");
    std::string more = sink.errors() > 1 ? fmt::format("\n({} errors in all; `rulec check` lists them)", sink.errors())
                                         : std::string();
    return Error{what, fmt::format("the rules have errors; nothing was sliced\n{}{}", first, more)};
  }
  return generate(program);
}

}  // namespace

// --printer/--material NAME must exist: say which ones do.
Status check_profile(const RulesInput& in) {
  FrontendOptions options;
  options.stdlib_dir = in.stdlib_dir;
  namespace fs = std::filesystem;
  fs::path dir = stdlib_dir(options);
  if (dir.empty())
    return Error{"stdlib", "cannot find the stdlib folder (defaults.rules, printers/, materials/); pass --stdlib DIR "
                           "or set TRANCHE_STDLIB"};
  for (auto [flag, kind, name] : {std::tuple{"--printer", "printers", in.printer}, std::tuple{"--material", "materials", in.material}}) {
    if (name.empty() || name == "none") continue;
    std::error_code ec;
    bool path = profile_is_path(name);
    // A file, or a FIFO or device (read with the rules' size bound): anything but a folder.
    if (path ? fs::exists(name, ec) && !fs::is_directory(name, ec) : fs::is_regular_file(dir / kind / (name + ".rules"), ec))
      continue;
    std::vector<std::string> have;
    for (const auto& e : fs::directory_iterator(dir / kind, ec))
      if (e.path().extension() == ".rules") have.push_back(e.path().stem().string());
    std::sort(have.begin(), have.end());
    std::string list;
    for (const auto& h : have) list += (list.empty() ? "" : ", ") + h;
    return Error{flag, path ? fmt::format("cannot read {}", name)
                            : fmt::format("no {} `{}` in {}; there are: {} (or give a path to a .rules file, or none)",
                                          kind == std::string("printers") ? "printer" : "material", name,
                                          (dir / kind).string(), list)};
  }
  return ok_status();
}

Result<std::shared_ptr<const vm::RuleSet>> load_rules(const RulesInput& in, Report& report) {
  if (!in.profile && in.files.empty() && in.expressions.empty()) return std::shared_ptr<const vm::RuleSet>();
  if (in.profile)
    if (Status s = check_profile(in); !s) return s.error();
  std::vector<vm::Program> programs;
  std::vector<std::string> names;
  Sources pending;  // consecutive .rules files
  const std::string profile = in.profile ? profile_source(in.printer, in.material) : std::string();
  bool profile_done = !in.profile;
  auto flush = [&](bool with_sets) -> Status {
    if (pending.empty() && !with_sets && profile_done) return ok_status();
    auto p = compile(profile_done ? nullptr : &profile, pending,
                     with_sets ? in.expressions : std::vector<std::pair<std::string, std::string>>{}, in.stdlib_dir,
                     report);
    if (!p) return p.error();
    programs.push_back(std::move(*p));
    names.push_back(!pending.empty() ? pending.back().first : !profile_done ? "profile" : "--set");
    pending.clear();
    profile_done = true;
    return ok_status();
  };
  for (const auto& f : in.files) {
    auto bytes = read_rules_or_bundle(f);
    if (!bytes) return bytes.error();
    if (!vm::looks_like_bundle(*bytes)) {
      pending.emplace_back(f, std::move(*bytes));
      continue;
    }
    if (Status s = flush(false); !s) return s.error();
    auto p = vm::read_bundle(*bytes, f);
    if (!p) return p.error();
    programs.push_back(std::move(*p));
    names.push_back(f);
  }
  if (Status s = flush(!in.expressions.empty()); !s) return s.error();
  auto linked = vm::link(std::move(programs), names);
  if (!linked) return linked.error();
  auto rs = vm::RuleSet::create(std::move(*linked));
  if (!rs) return rs.error();
  return *rs;
}

}  // namespace tranche::compiler
