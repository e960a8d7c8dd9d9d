// AstBuilder, second half: files, rules, statements and template strings.
#include <fmt/format.h>

#include "grammar/build_ast.h"

namespace tranche::grammar {

using ast::Expr;
using ast::ExprPtr;
using ast::Stmt;
using ast::StmtKind;
using ast::StmtPtr;

ast::File AstBuilder::file(RulesParser::FileContext* ctx) {
  ast::File f;
  f.id = in_.file();
  for (auto* item : ctx->item()) {
    ast::Item out;
    if (auto* u = dynamic_cast<RulesParser::UseItemContext*>(item)) {
      out.use = use(u);
    } else if (auto* r = dynamic_cast<RulesParser::RuleItemContext*>(item)) {
      out.rule = rule(r);
    } else if (auto* o = dynamic_cast<RulesParser::OnItemContext*>(item)) {
      out.rule = on(o);
    } else if (auto* p = dynamic_cast<RulesParser::ParamItemContext*>(item)) {
      out.param = param(p);
    }
    if (out.use || out.rule || out.param) f.items.push_back(std::move(out));
  }
  return f;
}

std::unique_ptr<ast::Use> AstBuilder::use(RulesParser::UseItemContext* ctx) {
  auto u = std::make_unique<ast::Use>();
  u->span = in_.span(ctx);
  u->target = string_value(ctx->STRING()->getSymbol());
  u->target_span = in_.span(ctx->STRING()->getSymbol());
  return u;
}

ast::ParamPtr AstBuilder::param(RulesParser::ParamItemContext* ctx) {
  auto p = std::make_unique<ast::Param>();
  p->span = in_.span(ctx);
  p->name = ctx->name()->getText();
  p->name_span = in_.span(ctx->name());
  p->value = expr(ctx->expr());
  if (!p->value) return nullptr;
  return p;
}

ast::RulePtr AstBuilder::rule(RulesParser::RuleItemContext* ctx) {
  auto r = std::make_unique<ast::Rule>();
  antlr4::Token* last = ctx->RULE()->getSymbol();
  if (auto* s = ctx->STRING()) {
    r->name = string_value(s->getSymbol());
    r->has_name = true;
    last = s->getSymbol();
  }
  if (auto* f = ctx->expr()) {
    r->filter = expr(f);
    if (!r->filter) return nullptr;
    last = f->getStop();
  }
  r->span = join(in_.span(ctx->RULE()->getSymbol()), in_.span(last));
  if (!block(ctx->block(), r->actions)) return nullptr;
  return r;
}

namespace {
// Edit distance for the two event names; small enough to write out here.
int distance(std::string_view a, std::string_view b) {
  std::vector<int> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    int diag = row[0];
    row[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j) {
      int up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
      diag = up;
    }
  }
  return row[b.size()];
}
}  // namespace

// `on LEVEL.start|end [when F] [append] { ... }` is a rule with one `before|after LEVEL` action.
ast::RulePtr AstBuilder::on(RulesParser::OnItemContext* ctx) {
  auto r = std::make_unique<ast::Rule>();
  r->from_on = true;
  auto hook = std::make_unique<Stmt>();
  hook->kind = StmtKind::Hook;
  hook->name = name(ctx->name(0), &hook->name_span);
  ast::Span event_span;
  std::string event = name(ctx->name(1), &event_span);
  if (event == "start" || event == "end") {
    hook->when = event == "start" ? ast::When::Before : ast::When::After;
  } else {
    failed_ = true;
    std::string_view guess =
        event == "begin" || distance(event, "start") <= distance(event, "end") ? "start" : "end";
    sink_
        .error("E0107", event_span, fmt::format("unknown event `{}.{}`", hook->name, event),
               "an event is `start` or `end`")
        .help(fmt::format("did you mean `{}.{}`?", hook->name, guess))
        .fix(event_span, std::string(guess));
    return nullptr;
  }
  antlr4::Token* last = ctx->name(1)->getStop();
  if (auto* f = ctx->expr()) {
    r->filter = expr(f);
    if (!r->filter) return nullptr;
    last = f->getStop();
  }
  hook->append = ctx->APPEND() != nullptr;
  if (hook->append) last = ctx->APPEND()->getSymbol();
  r->span = join(in_.span(ctx->ON()->getSymbol()), in_.span(last));
  hook->span = r->span;
  if (!block(ctx->block(), hook->body)) return nullptr;
  r->actions.push_back(std::move(hook));
  return r;
}

bool AstBuilder::block(RulesParser::BlockContext* ctx, std::vector<StmtPtr>& out) {
  if (ctx == nullptr) return false;
  for (auto* s : ctx->stmt()) {
    StmtPtr st = stmt(s);
    if (!st) return false;
    out.push_back(std::move(st));
  }
  return true;
}

StmtPtr AstBuilder::stmt(RulesParser::StmtContext* ctx) {
  auto s = std::make_unique<Stmt>();
  s->span = in_.span(ctx);
  bool ok = true;
  if (auto* c1 = dynamic_cast<RulesParser::AssignStmtContext*>(ctx)) {
    s->kind = StmtKind::Assign;
    s->name = name(c1->name(), &s->name_span);
    ok = (s->value = expr(c1->expr())) != nullptr;
  } else if (auto* c2 = dynamic_cast<RulesParser::HookStmtContext*>(ctx)) {
    s->kind = StmtKind::Hook;
    s->when = c2->hook->getType() == RulesParser::BEFORE ? ast::When::Before : ast::When::After;
    s->name = name(c2->name(), &s->name_span);
    s->append = c2->APPEND() != nullptr;
    ok = block(c2->block(), s->body);
  } else if (auto* c3 = dynamic_cast<RulesParser::ReplaceStmtContext*>(ctx)) {
    s->kind = StmtKind::Replace;
    s->name = name(c3->name(), &s->name_span);
    ok = block(c3->block(), s->body);
  } else if (auto* c4 = dynamic_cast<RulesParser::GcodeStmtContext*>(ctx)) {
    s->kind = StmtKind::Gcode;
    ok = text(c4->text, s->text);
  } else if (auto* c5 = dynamic_cast<RulesParser::CommentStmtContext*>(ctx)) {
    s->kind = StmtKind::Comment;
    ok = text(c5->text, s->text);
  } else if (auto* c6 = dynamic_cast<RulesParser::LetStmtContext*>(ctx)) {
    s->kind = StmtKind::Let;
    s->name = name(c6->name(), &s->name_span);
    ok = (s->value = expr(c6->expr())) != nullptr;
  } else if (auto* c7 = dynamic_cast<RulesParser::IfStatementContext*>(ctx)) {
    return if_stmt(c7->ifStmt());
  } else if (auto* c8 = dynamic_cast<RulesParser::ForStmtContext*>(ctx)) {
    s->kind = StmtKind::For;
    s->name = name(c8->name(), &s->name_span);
    ok = (s->value = expr(c8->expr(0))) != nullptr;
    if (ok && c8->expr().size() > 1) ok = (s->value2 = expr(c8->expr(1))) != nullptr;
    ok = ok && block(c8->block(), s->body);
  } else if (auto* c9 = dynamic_cast<RulesParser::MoveStmtContext*>(ctx)) {
    return move(c9);
  } else if (dynamic_cast<RulesParser::DefaultStmtContext*>(ctx)) {
    s->kind = StmtKind::Default;
  } else if (auto* c10 = dynamic_cast<RulesParser::OffsetStmtContext*>(ctx)) {
    s->kind = StmtKind::Offset;
    ok = (s->value = expr(c10->expr())) != nullptr;
  } else if (dynamic_cast<RulesParser::ReverseStmtContext*>(ctx)) {
    s->kind = StmtKind::Reverse;
  } else if (dynamic_cast<RulesParser::RetractStmtContext*>(ctx)) {
    s->kind = StmtKind::Retract;
  } else {
    ok = false;
  }
  if (!ok) return nullptr;
  return s;
}

StmtPtr AstBuilder::if_stmt(RulesParser::IfStmtContext* ctx) {
  if (ctx == nullptr) return nullptr;
  auto s = std::make_unique<Stmt>();
  s->kind = StmtKind::If;
  s->span = in_.span(ctx);
  s->value = expr(ctx->expr());
  if (!s->value || !block(ctx->block(0), s->body)) return nullptr;
  if (ctx->block().size() > 1) {
    if (!block(ctx->block(1), s->else_body)) return nullptr;
  } else if (ctx->ifStmt() != nullptr) {
    StmtPtr nested = if_stmt(ctx->ifStmt());
    if (!nested) return nullptr;
    s->else_body.push_back(std::move(nested));
  }
  return s;
}

StmtPtr AstBuilder::move(RulesParser::MoveStmtContext* ctx) {
  auto s = std::make_unique<Stmt>();
  s->kind = StmtKind::Move;
  s->span = in_.span(ctx);
  s->x = expr(ctx->expr(0));
  s->y = expr(ctx->expr(1));
  if (!s->x || !s->y) return nullptr;
  s->travel = ctx->kind != nullptr && ctx->kind->getType() == RulesParser::TRAVEL;
  for (auto* o : ctx->moveOption()) {
    ast::MoveOption opt;
    opt.name = name(o->name(), &opt.name_span);
    opt.value = expr(o->expr());
    if (!opt.value) return nullptr;
    s->options.push_back(std::move(opt));
  }
  return s;
}

// The value of a plain string (`use`, rule names): quotes removed, `\"`, `\\`, `\n`, `\t`
// resolved; other backslashes are kept as written.
std::string AstBuilder::string_value(antlr4::Token* token) {
  std::string t = token->getText();
  size_t q = t.rfind("\"\"\"", 0) == 0 && t.size() >= 6 ? 3 : 1;
  std::string_view body = std::string_view(t).substr(q, t.size() - 2 * q);
  std::string out;
  for (size_t i = 0; i < body.size(); ++i) {
    if (body[i] == '\\' && i + 1 < body.size()) {
      char c = body[i + 1];
      if (c == '"' || c == '\\' || c == 'n' || c == 't') {
        out += c == 'n' ? '\n' : c == 't' ? '\t' : c;
        ++i;
        continue;
      }
    }
    out += body[i];
  }
  return out;
}

// A G-code or comment template: literal runs and `{expr}` / `{expr:.N}` parts. The expressions
// are parsed in place, so their diagnostics point inside the string.
bool AstBuilder::text(antlr4::Token* token, ast::Template& out) {
  const ast::SourceMap& sources = in_.sources();
  const std::string& src = sources.file(in_.file()).text;
  uint32_t b = in_.byte(token->getStartIndex());
  uint32_t e = in_.byte(token->getStopIndex() + 1);
  uint32_t q = token->getType() == RulesParser::TRIPLE_STRING ? 3 : 1;
  out.span = sources.span(in_.file(), b, e);
  uint32_t i = b + q, end = e - q;
  std::string literal;
  uint32_t literal_start = i;
  auto flush = [&](uint32_t at) {
    if (!literal.empty()) {
      ast::TemplatePart p;
      p.text = std::move(literal);
      p.span = sources.span(in_.file(), literal_start, at);
      out.parts.push_back(std::move(p));
    }
    literal.clear();
  };
  auto fail = [&](uint32_t from, uint32_t to, std::string message, std::string label, std::string help) {
    return template_error(from, to, std::move(message), std::move(label), std::move(help));
  };
  while (i < end) {
    char c = src[i];
    if (c == '\\' && i + 1 < end && std::string_view("\"\\nt").find(src[i + 1]) != std::string_view::npos) {
      char n = src[i + 1];
      literal += n == 'n' ? '\n' : n == 't' ? '\t' : n;
      i += 2;
    } else if ((c == '{' || c == '}') && i + 1 < end && src[i + 1] == c) {
      literal += c;
      i += 2;
    } else if (c == '}') {
      return fail(i, i + 1, "unmatched `}` in template", "no `{` opens this", "write `}}` for a literal `}`");
    } else if (c == '{') {
      uint32_t close = i + 1;
      while (close < end && src[close] != '}' && src[close] != '{') ++close;
      if (close >= end || src[close] != '}')
        return fail(i, i + 1, "unterminated `{` in template", "this `{` is never closed",
                    "close it with `}`, or write `{{` for a literal `{`");
      flush(i);
      if (!template_part(i, close, out)) return false;
      i = close + 1;
      literal_start = i;
    } else {
      literal += c;
      ++i;
    }
  }
  flush(end);
  return true;
}

// Reports a template error (E0007) from byte `from` to `to`; always false.
bool AstBuilder::template_error(uint32_t from, uint32_t to, std::string message, std::string label,
                                std::string help) {
  failed_ = true;
  auto& d =
      sink_.error("E0007", in_.sources().span(in_.file(), from, to), std::move(message), std::move(label));
  if (!help.empty()) d.help(std::move(help));
  return false;
}

// The part `{expr}` or `{expr:.N}` of a template between bytes `i` (the `{`) and `close` (its
// `}`), added to `out`; false after a diagnostic.
bool AstBuilder::template_part(uint32_t i, uint32_t close, ast::Template& out) {
  const ast::SourceMap& sources = in_.sources();
  const std::string& src = sources.file(in_.file()).text;
  // The format's `:` is outside brackets (`{any(i in 1..2: ...):.0}` has one inside).
  uint32_t colon = i + 1;
  for (int depth = 0; colon < close && (src[colon] != ':' || depth > 0); ++colon)
    depth += src[colon] == '(' ? 1 : src[colon] == ')' ? -1 : 0;
  std::string_view inner(src.data() + i + 1, colon - i - 1);
  std::string_view all(src.data() + i + 1, close - i - 1);
  if (size_t k = all.find_first_not_of(" \t");
      k != std::string_view::npos && (all[k] == '%' || all[k] == '#')) {
    failed_ = true;
    sink_
        .error("E0008", sources.span(in_.file(), i, close + 1),
               fmt::format("Jinja's `{{{}` ... `{}}}` is not part of the rule language", all[k], all[k]),
               "a Klipper macro statement")
        .help(
            "decide in the executor: `if layer.index == 0 { gcode \"...\" } else { gcode \"...\" }`; a "
            "template only prints values: `{layer.z:.2}`");
    return false;
  }
  if (inner.find_first_not_of(" \t\r\n") == std::string_view::npos)
    return template_error(i, close + 1, "empty `{}` in template", "nothing to print here",
                          "put a value inside, like `{layer.index}`, or write `{{}}` for literal braces");
  ast::TemplatePart p;
  p.span = sources.span(in_.file(), i, close + 1);
  if (colon < close) {
    std::string_view fmt(src.data() + colon + 1, close - colon - 1);
    bool good = fmt.size() >= 2 && fmt.size() <= 3 && fmt[0] == '.' &&
                fmt.find_first_not_of("0123456789", 1) == std::string_view::npos;
    int decimals = good ? std::stoi(std::string(fmt.substr(1))) : -1;
    if (!good || decimals > 12)
      return template_error(colon, close, fmt::format("unknown format `:{}` in template", fmt),
                            "expected `:.N`, N decimals (0 to 12)", "write `{layer.z:.2}` for two decimals");
    p.decimals = decimals;
  }
  p.expr = parse_expression(sources, in_.file(), i + 1, colon, sink_, options_);
  if (!p.expr) {
    failed_ = true;
    return false;
  }
  out.parts.push_back(std::move(p));
  return true;
}

}  // namespace tranche::grammar
