// stdlib/features: every number a user may want to tune is a `param`, so that `--set NAME=VALUE`
// changes it without copying the file.
#include <doctest/doctest.h>

#include <filesystem>
#include <functional>

#include "compiler/check.h"
#include "compiler/frontend.h"
#include "tests/support/fixtures.h"

namespace fs = std::filesystem;
using namespace tranche;

namespace {

// Numbers written in the rules of file 0 that are not structural: anything but an integer without
// a unit (a layer index, `mod 4`) and 0 or 1 (`/ 1 mm`).
std::vector<std::string> tuning_literals(const ast::Program& program) {
  std::vector<std::string> out;
  std::function<void(const ast::Expr*)> expr = [&](const ast::Expr* e) {
    if (!e) return;
    if (e->kind == ast::ExprKind::Number && !e->integer_literal && e->number != 0 && e->number != 1)
      out.push_back(std::to_string(e->span.line) + ": " + std::string(program.sources.text(e->span)));
    for (const auto& a : e->args) expr(a.get());
  };
  std::function<void(const std::vector<ast::StmtPtr>&)> stmts = [&](const std::vector<ast::StmtPtr>& body) {
    for (const auto& s : body) {
      for (const ast::Expr* e : {s->value.get(), s->value2.get(), s->x.get(), s->y.get()}) expr(e);
      for (const auto& o : s->options) expr(o.value.get());
      for (const auto& p : s->text.parts) expr(p.expr.get());
      stmts(s->body);
      stmts(s->else_body);
    }
  };
  for (const ast::Rule* r : program.cascade) {
    if (r->span.file != 0) continue;
    expr(r->filter.get());
    stmts(r->actions);
  }
  return out;
}

}  // namespace

TEST_CASE("stdlib/features: every tuning number is a param, and each param can be set with --set") {
  fs::path dir = test::source_dir() / "stdlib" / "features";
  size_t files = 0, params = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() != ".rules") continue;
    ++files;
    compiler::FrontendOptions options;
    options.stdlib_dir = (test::source_dir() / "stdlib").string();
    ast::Program program;
    diag::Sink sink;
    compiler::load_file(program, e.path().string(), options, sink);
    REQUIRE(compiler::check(program, sink));
    INFO(e.path().filename().string());
    CHECK(tuning_literals(program) == std::vector<std::string>{});
    // --set NAME=VALUE with the value as written, then with a plain number (the param's unit).
    std::vector<std::pair<std::string, std::string>> sets;
    for (const ast::Param* p : program.params) {
      ++params;
      sets.emplace_back(p->name, std::string(program.sources.text(p->value->span)));
      if (p->type.kind == ast::Kind::Number && p->constant)
        sets.emplace_back(p->name, std::to_string(*p->constant));
    }
    for (const auto& [k, v] : sets) {
      ast::Program again;
      diag::Sink s2;
      compiler::load_file(again, e.path().string(), options, s2);
      INFO("--set " << k << "=" << v);
      CHECK(compiler::add_set(again, k, v, s2));
      CHECK(compiler::check(again, s2));
    }
  }
  CHECK(files >= 12);
  CHECK(params >= 30);
}
