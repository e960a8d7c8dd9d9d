#include "lsp/analysis.h"

#include "compiler/check.h"

namespace tranche::lsp {

Analysis analyze(const std::string& path, std::string text, const compiler::FrontendOptions& options) {
  Analysis a;
  a.program = std::make_unique<ast::Program>();
  diag::Sink sink;
  compiler::load_source(*a.program, path, std::move(text), options, sink);
  if (compiler::check(*a.program, sink) && !sink.has_errors() && options.lints) compiler::lint(*a.program, sink);
  sink.finish({});
  a.diagnostics = sink.all();
  for (const auto& f : a.program->files)
    if (f.id == a.file) a.parsed = &f;
  return a;
}

namespace {

bool contains(const ast::Span& s, uint32_t offset) {
  return s.valid() && s.file == 0 && s.offset <= offset && offset <= s.end();
}

void in_expr(const ast::Expr* e, uint32_t offset, Found& f) {
  if (!e || !contains(e->span, offset)) return;
  f.expr = e;
  for (const auto& a : e->args) in_expr(a.get(), offset, f);
}

void in_stmts(const std::vector<ast::StmtPtr>& body, uint32_t offset, Found& f) {
  for (const auto& s : body) {
    // `on` rules give their hook the header's span: look inside whatever the span says.
    if (contains(s->span, offset)) f.stmt = s.get();
    for (const ast::Expr* e : {s->value.get(), s->value2.get(), s->x.get(), s->y.get()}) in_expr(e, offset, f);
    for (const auto& o : s->options) in_expr(o.value.get(), offset, f);
    for (const auto& p : s->text.parts) in_expr(p.expr.get(), offset, f);
    in_stmts(s->body, offset, f);
    in_stmts(s->else_body, offset, f);
  }
}

}  // namespace

Found find_at(const Analysis& a, uint32_t offset) {
  Found f;
  if (!a.parsed) return f;
  for (const auto& item : a.parsed->items) {
    if (item.use && contains(item.use->span, offset)) f.use = item.use.get();
    if (item.param && contains(item.param->span, offset)) {
      f.param = item.param.get();
      in_expr(item.param->value.get(), offset, f);
    }
    if (item.rule) {
      const ast::Rule& r = *item.rule;
      Found inside;
      in_expr(r.filter.get(), offset, inside);
      in_stmts(r.actions, offset, inside);
      if (!inside.expr && !inside.stmt && !contains(r.span, offset)) continue;
      f.expr = inside.expr;
      f.stmt = inside.stmt;
      f.rule = &r;
    }
  }
  return f;
}

std::vector<const ast::Param*> param_definitions(const ast::Program& program, const std::string& name) {
  std::vector<const ast::Param*> out;
  for (const ast::Param* p : program.params)
    if (p->name == name) out.push_back(p);
  return out;
}

}  // namespace tranche::lsp
