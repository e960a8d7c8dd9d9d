// Copies of syntax trees, for the language server's incremental parsing: items of an unchanged
// part of a file are copied from its previous parse instead of being parsed again.
#include "grammar/ast/ast.h"

namespace tranche::ast {

Span Relocation::operator()(const Span& s) const {
  if (!s.valid()) return s;
  return Span{file, s.line + line, s.col, s.offset + offset, s.length};
}

namespace {

ExprPtr copy(const Expr* e, const Relocation& to) {
  if (!e) return nullptr;
  auto out = std::make_unique<Expr>();
  out->kind = e->kind;
  out->span = to(e->span);
  out->op = e->op;
  out->number = e->number;
  out->integer_literal = e->integer_literal;
  out->unit_text = e->unit_text;
  out->unit_span = to(e->unit_span);
  out->boolean = e->boolean;
  out->text = e->text;
  out->str = e->str;
  out->text_span = to(e->text_span);
  out->member = e->member;
  out->member_span = to(e->member_span);
  out->depth = e->depth;
  for (const auto& a : e->args) out->args.push_back(copy(a.get(), to));
  return out;
}

StmtPtr copy(const Stmt& s, const Relocation& to) {
  auto out = std::make_unique<Stmt>();
  out->kind = s.kind;
  out->span = to(s.span);
  out->name = s.name;
  out->name_span = to(s.name_span);
  out->value = copy(s.value.get(), to);
  out->value2 = copy(s.value2.get(), to);
  out->x = copy(s.x.get(), to);
  out->y = copy(s.y.get(), to);
  out->when = s.when;
  out->append = s.append;
  out->travel = s.travel;
  for (const auto& o : s.options) {
    MoveOption m;
    m.name = o.name;
    m.name_span = to(o.name_span);
    m.value = copy(o.value.get(), to);
    out->options.push_back(std::move(m));
  }
  out->text.span = to(s.text.span);
  for (const auto& p : s.text.parts) {
    TemplatePart part;
    part.text = p.text;
    part.expr = copy(p.expr.get(), to);
    part.decimals = p.decimals;
    part.span = to(p.span);
    out->text.parts.push_back(std::move(part));
  }
  for (const auto& b : s.body) out->body.push_back(copy(*b, to));
  for (const auto& b : s.else_body) out->else_body.push_back(copy(*b, to));
  return out;
}

}  // namespace

Item clone(const Item& item, const Relocation& to) {
  Item out;
  if (item.use) {
    out.use = std::make_unique<Use>();
    out.use->span = to(item.use->span);
    out.use->target = item.use->target;
    out.use->target_span = to(item.use->target_span);
  }
  if (item.param) {
    out.param = std::make_unique<Param>();
    out.param->span = to(item.param->span);
    out.param->name = item.param->name;
    out.param->name_span = to(item.param->name_span);
    out.param->value = copy(item.param->value.get(), to);
    out.param->from_set = item.param->from_set;
  }
  if (item.rule) {
    const Rule& r = *item.rule;
    out.rule = std::make_unique<Rule>();
    out.rule->span = to(r.span);
    out.rule->name = r.name;
    out.rule->has_name = r.has_name;
    out.rule->from_on = r.from_on;
    out.rule->from_set = r.from_set;
    out.rule->filter = copy(r.filter.get(), to);
    for (const auto& a : r.actions) out.rule->actions.push_back(copy(*a, to));
  }
  return out;
}

}  // namespace tranche::ast
