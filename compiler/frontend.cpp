#include "compiler/frontend.h"

#include <fmt/format.h>

#include <cstdlib>
#include <map>

#include "compiler/check.h"
#include "compiler/names.h"
#include "runtime/vm/verify.h"
#include "base/input_file.h"
#include "base/result.h"

namespace tranche::compiler {

namespace fs = std::filesystem;

namespace {

constexpr size_t kMaxUseDepth = 16;
static_assert(kMaxFileBytes == kRulesInput.max_bytes);  // files being read at once: profiles nest a few deep

Result<std::string> read(const fs::path& path, const FrontendOptions& options) {
  if (options.read_file) {
    if (auto text = options.read_file(path)) return std::move(*text);
    return Error{path.string(), "no such file"};
  }
  // The one input reader: at most kMaxFileBytes, from a file, a FIFO or a device alike.
  return read_input(path.string(), kRulesInput);
}

bool ident_byte(char c) {
  const auto u = static_cast<unsigned char>(c);
  return u >= 0x80 || u == '_' || (u >= '0' && u <= '9') || ((u | 0x20) >= 'a' && (u | 0x20) <= 'z');
}

}  // namespace

size_t count_rule_items(std::string_view text) {
  size_t n = 0, depth = 0;
  for (size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '#') {  // a comment, to the end of the line
      while (i < text.size() && text[i] != '\n' && text[i] != '\r') ++i;
    } else if (text.substr(i, 3) == "\"\"\"") {
      const size_t end = text.find("\"\"\"", i + 3);
      i = end == std::string_view::npos ? text.size() : end + 3;
    } else if (c == '"') {  // a string, to its quote or the end of its line
      for (++i; i < text.size() && text[i] != '"' && text[i] != '\n' && text[i] != '\r'; ++i)
        if (text[i] == '\\') ++i;
      ++i;
    } else if (c == '{' || c == '}') {
      depth = c == '{' ? depth + 1 : depth - (depth > 0);
      ++i;
    } else if (ident_byte(c)) {
      const size_t start = i;
      while (i < text.size() && ident_byte(text[i])) ++i;
      const std::string_view word = text.substr(start, i - start);
      if (depth == 0 && (word == "rule" || word == "on")) ++n;
    } else {
      ++i;
    }
  }
  return n;
}

namespace {

fs::path canonical_key(const fs::path& p) {
  std::error_code ec;
  fs::path c = fs::weakly_canonical(p, ec);
  return ec ? p.lexically_normal() : c;
}

class Loader {
 public:
  Loader(ast::Program& program, const FrontendOptions& options, diag::Sink& sink)
      : program_(program), options_(options), sink_(sink) {
    // Files read for earlier inputs count as read: each file is read once per program.
    for (uint32_t i = 0; i < program.sources.size(); ++i)
      if (program.sources.file(i).path != "--set")
        loaded_.emplace(canonical_key(program.sources.file(i).path).string(), i);
  }

  bool loaded(const fs::path& key) const { return loaded_.count(key.string()) != 0; }

  void expand(uint32_t file, const fs::path& key) {
    loaded_[key.string()] = file;
    if (too_many_rules(file)) {
      ast::File empty;
      empty.id = file;
      program_.files.push_back(std::move(empty));
      return;
    }
    stack_.push_back(file);
    ast::File parsed = options_.parser ? options_.parser(program_.sources, file, sink_)
                                       : grammar::parse_file(program_.sources, file, sink_, options_.parse);
    std::map<std::string, ast::Span> used_here;
    for (auto& item : parsed.items) {
      if (item.rule) {
        program_.cascade.push_back(item.rule.get());
        continue;
      }
      if (item.param) {
        program_.params.push_back(item.param.get());
        continue;
      }
      ast::Use& use = *item.use;
      auto target = resolve(use, file);
      if (!target) continue;
      auto [path, from_stdlib] = *target;
      fs::path k = canonical_key(path);
      if (auto it = used_here.find(k.string()); it != used_here.end()) {
        if (program_.sources.file(file).user)
          sink_
              .warning("W207", use.span, fmt::format("`{}` is used twice in this file", use.target),
                       "used again")
              .label(it->second, "first used here")
              .note("a file is read once, at its first `use`; the second `use` does nothing");
        continue;
      }
      used_here[k.string()] = use.span;
      if (auto it = loaded_.find(k.string()); it != loaded_.end()) {
        use.file = static_cast<int>(it->second);
        auto on_stack = std::find(stack_.begin(), stack_.end(), it->second);
        if (on_stack != stack_.end()) {
          std::string chain;
          for (auto f = on_stack; f != stack_.end(); ++f) chain += program_.sources.file(*f).path + " → ";
          chain += program_.sources.file(it->second).path;
          sink_
              .error("E0011", use.target_span, fmt::format("`use` cycle: {}", chain),
                     "uses a file that is being read")
              .help("remove one of the `use`s: each file can be used by the ones after it only");
        }
        continue;
      }
      if (stack_.size() >= kMaxUseDepth) {
        sink_.error("E0012", use.target_span,
                    fmt::format("`use` chain is deeper than {} files", kMaxUseDepth), "too deep");
        continue;
      }
      auto text = read(path, options_);
      if (!text.ok()) {
        sink_
            .error("E0010", use.target_span,
                   fmt::format("cannot read `{}`: {}", use.target, text.error().message), "not found")
            .note(fmt::format("looked for {}", path.string()));
        continue;
      }
      bool user = program_.sources.file(file).user && !from_stdlib;
      uint32_t id = program_.sources.add(path.lexically_normal().string(), std::move(text.value()), user);
      use.file = static_cast<int>(id);
      expand(id, k);
    }
    program_.files.push_back(std::move(parsed));
    stack_.pop_back();
  }

 private:
  // More rules than the VM numbers (vm::kMaxRules), counted from the text before it is parsed: a
  // file of 100 000 rules is refused in milliseconds, not after a minute of compiling.
  bool too_many_rules(uint32_t file) {
    const size_t here = count_rule_items(program_.sources.file(file).text);
    const size_t total = program_.cascade.size() + here;
    if (total <= vm::kMaxRules) return false;
    sink_
        .error("E0013", program_.sources.span(file, 0, 0),
               fmt::format("too many rules: this file has {}{}, and at most {} can be compiled", here,
                           total > here ? fmt::format(" ({} with the files before it)", total) : std::string(),
                           vm::kMaxRules),
               "too many rules")
        .help("split the rules into several runs, or merge rules that set the same properties");
    return true;
  }

  // The file a `use` names, and whether it came from the stdlib directory.
  std::optional<std::pair<fs::path, bool>> resolve(const ast::Use& use, uint32_t from) {
    const std::string& t = use.target;
    if (t.empty()) {
      sink_.error("E0010", use.target_span, "`use` needs a file name", "empty")
          .help("write `use \"printers/generic-marlin\"` or `use \"./my-profile\"`");
      return std::nullopt;
    }
    fs::path p;
    bool from_stdlib = false;
    if (t.starts_with("./") || t.starts_with("../")) {
      p = fs::path(program_.sources.file(from).path).parent_path() / t;
    } else if (fs::path(t).is_absolute()) {
      p = t;
    } else {
      fs::path dir = stdlib_dir(options_);
      if (dir.empty()) {
        auto& d = sink_.error("E0010", use.target_span,
                              fmt::format("cannot find `{}`: no stdlib directory", t), "a stdlib name");
        for (const auto& c : stdlib_candidates(options_)) d.note(fmt::format("looked for {}", c.string()));
        d.help("pass `--stdlib DIR`, set TRANCHE_STDLIB, or write `./` for a file next to this one");
        return std::nullopt;
      }
      p = dir / t;
      from_stdlib = true;
    }
    if (!p.has_extension()) p += ".rules";
    return std::make_pair(p, from_stdlib);
  }

  ast::Program& program_;
  const FrontendOptions& options_;
  diag::Sink& sink_;
  std::map<std::string, uint32_t> loaded_;
  std::vector<uint32_t> stack_;
};

}  // namespace

std::vector<fs::path> stdlib_candidates(const FrontendOptions& options) {
  std::vector<fs::path> out;
  if (!options.stdlib_dir.empty()) out.emplace_back(options.stdlib_dir);
  if (const char* env = std::getenv("TRANCHE_STDLIB"); env && *env) out.emplace_back(env);
#ifdef TRANCHE_STDLIB_DIR
  out.emplace_back(TRANCHE_STDLIB_DIR);
#endif
  if (!options.exe_path.empty()) {
    std::error_code ec;
    fs::path exe = fs::weakly_canonical(options.exe_path, ec);
    if (!ec) out.push_back(exe.parent_path() / ".." / "share" / "tranche" / "stdlib");
  }
  return out;
}

fs::path stdlib_dir(const FrontendOptions& options) {
  for (const auto& c : stdlib_candidates(options)) {
    std::error_code ec;
    if (fs::is_directory(c, ec)) return c;
  }
  return {};
}

bool load_source(ast::Program& program, const std::string& path, std::string text,
                 const FrontendOptions& options, diag::Sink& sink) {
  size_t before = sink.errors();
  Loader loader(program, options, sink);
  fs::path key = canonical_key(path);
  if (loader.loaded(key)) return true;  // given twice: read once
  uint32_t id = program.sources.add(path, std::move(text), true);
  loader.expand(id, key);
  return sink.errors() == before;
}

bool load_file(ast::Program& program, const std::string& path, const FrontendOptions& options,
               diag::Sink& sink) {
  auto text = read(path, options);
  if (!text.ok()) {
    uint32_t id = program.sources.add(path, "", true);
    sink.error("E0010", ast::Span{id, 0, 0, 0, 0},
               fmt::format("cannot read `{}`: {}", path, text.error().message));
    return false;
  }
  return load_source(program, path, std::move(text.value()), options, sink);
}

bool add_set(ast::Program& program, std::string_view key, std::string_view value, diag::Sink& sink) {
  std::string text = std::string(key) + "=" + std::string(value);
  uint32_t id = program.sources.add("--set", text, true);
  uint32_t key_end = static_cast<uint32_t>(key.size());
  ast::Span key_span = program.sources.span(id, 0, key_end);
  auto prop = schema::find_property(key);
  bool param = false;
  for (const ast::Param* p : program.params) param = param || p->name == key;
  if (!prop && !param) {
    std::vector<std::string> names;
    for (const auto& p : schema::properties()) names.emplace_back(p.name);
    for (const ast::Param* p : program.params) names.push_back(p->name);
    bool any_params = !program.params.empty();
    auto& d = sink.error("E0103", key_span,
                         fmt::format("unknown property{} `{}` in `--set`", any_params ? " or param" : "", key),
                         any_params ? "not a property or a param of these rules" : "not a property");
    if (auto theirs = foreign_property(key))
      d.help(fmt::format("`{}` is {} name for it: write `--set {}={}`", key,
                         theirs->whose.empty() ? "another slicer's" : theirs->whose, theirs->ours, value));
    else if (auto best = suggest(key, names))
      d.help(fmt::format("did you mean `--set {}={}`?", *best, value));
    return false;
  }
  if (value.find_first_not_of(" \t") == std::string_view::npos) {
    sink.error("E0004", program.sources.span(id, key_end, key_end + 1),
               fmt::format("`--set {}=` has no value", key), "expected a value after `=`")
        .help(fmt::format("write `--set {}=VALUE`", key));
    return false;
  }
  ast::ExprPtr v =
      grammar::parse_expression(program.sources, id, key_end + 1, static_cast<uint32_t>(text.size()), sink);
  if (!v) return false;
  if (!prop) {  // a param: an implicit last definition (a plain number takes its unit, see check)
    auto def = std::make_unique<ast::Param>();
    def->from_set = true;
    def->span = program.sources.span(id, 0, static_cast<uint32_t>(text.size()));
    def->name = std::string(key);
    def->name_span = key_span;
    def->value = std::move(v);
    program.params.push_back(def.get());
    program.set_params.push_back(std::move(def));
    return true;
  }
  const auto& info = schema::property(*prop);
  ast::Expr* literal = v->kind == ast::ExprKind::Unary && v->op == ast::Op::Neg ? v->args[0].get() : v.get();
  if (literal->kind == ast::ExprKind::Number && literal->unit_text.empty() &&
      info.type == schema::Type::Number && info.unit != schema::Unit::None &&
      info.unit != schema::Unit::Ratio) {
    literal->unit_text = std::string(schema::unit_name(info.unit));
    literal->integer_literal = false;
  }
  auto rule = std::make_unique<ast::Rule>();
  rule->from_set = true;
  rule->name = fmt::format("--set {}", key);
  rule->span = program.sources.span(id, 0, static_cast<uint32_t>(text.size()));
  auto assign = std::make_unique<ast::Stmt>();
  assign->kind = ast::StmtKind::Assign;
  assign->span = rule->span;
  assign->name = std::string(key);
  assign->name_span = key_span;
  assign->value = std::move(v);
  rule->actions.push_back(std::move(assign));
  program.cascade.push_back(rule.get());
  program.set_rules.push_back(std::move(rule));
  return true;
}

ast::Program compile(const std::vector<std::string>& paths,
                     const std::vector<std::pair<std::string, std::string>>& sets,
                     const FrontendOptions& options, diag::Sink& sink) {
  ast::Program program;
  for (const auto& p : paths) load_file(program, p, options, sink);
  for (const auto& [k, v] : sets) add_set(program, k, v, sink);
  bool ok = check(program, sink) && !sink.has_errors();
  if (ok && options.lints) lint(program, sink);
  return program;
}

bool profile_is_path(const std::string& name) {
  return name.find('/') != std::string::npos || name.ends_with(".rules");
}

std::string profile_source(const std::string& printer, const std::string& material) {
  auto target = [](const std::string& kind, const std::string& name) {
    if (!profile_is_path(name)) return kind + "/" + name;
    std::error_code ec;
    return std::filesystem::absolute(name, ec).string();
  };
  std::string s = "use \"defaults\"\n";
  if (!printer.empty() && printer != "none") s += "use \"" + target("printers", printer) + "\"\n";
  if (!material.empty() && material != "none") s += "use \"" + target("materials", material) + "\"\n";
  return s;
}

}  // namespace tranche::compiler
