// Rules, actions and statements: what may stand where, slots, locals, loops and templates.
#include <fmt/format.h>

#include <cmath>

#include "compiler/check.h"
#include "compiler/checker.h"
#include "compiler/names.h"

namespace tranche::compiler {

using ast::Expr;
using ast::Kind;
using ast::Stmt;
using ast::StmtKind;
using ast::Type;

std::string_view stmt_word(StmtKind k) {
  switch (k) {
    case StmtKind::Assign:
      return "an assignment";
    case StmtKind::Hook:
      return "`before`/`after`";
    case StmtKind::Replace:
      return "`replace`";
    case StmtKind::Gcode:
      return "`gcode`";
    case StmtKind::Comment:
      return "`comment`";
    case StmtKind::Let:
      return "`let`";
    case StmtKind::If:
      return "`if`";
    case StmtKind::For:
      return "`for`";
    case StmtKind::Move:
      return "`move`";
    case StmtKind::Default:
      return "`default`";
    case StmtKind::Offset:
      return "`offset`";
    case StmtKind::Reverse:
      return "`reverse`";
    case StmtKind::Retract:
      return "`retract`";
  }
  return "?";
}

std::optional<schema::Level> level_named(std::string_view n) {
  static constexpr std::string_view names[] = {"print", "layer", "island", "cell", "path", "piece"};
  for (size_t i = 0; i < std::size(names); ++i)
    if (names[i] == n) return static_cast<schema::Level>(i);
  return std::nullopt;
}

bool user_file(const ast::SourceMap& sources, const ast::Span& s) {
  return s.file < sources.size() && sources.file(s.file).user;
}

bool check(ast::Program& program, diag::Sink& sink) {
  Checker checker(program, sink);
  return checker.run();
}

bool Checker::run() {
  size_t errors_before = sink_.errors();
  params();
  int index = 0;
  for (ast::Rule* r : program_.cascade) {
    r->index = index++;
    r->slots.clear();
    r->conjuncts.clear();
    rule(*r);
  }
  dependencies();
  program_.checked = sink_.errors() == errors_before;
  return program_.checked;
}

void Checker::params() {
  params_.clear();
  for (ast::Param* p : program_.params) {
    // A name that would hide something else, or that `--set` could not tell from a property.
    std::string clash;
    if (schema::find_property(p->name)) clash = "is a property: set it in a rule, or with `--set`";
    else if (level_named(p->name) || p->name == "below" || p->name == "above" || p->name == "layers")
      clash = "names a level";
    for (const auto& e : schema::enums())
      if (clash.empty() && e.id != schema::EnumType::None && schema::find_enum_value(e.id, p->name))
        clash = fmt::format("is a `{}` value", e.name);
    if (!clash.empty()) {
      sink_.error("E0110", p->name_span, fmt::format("`{}` cannot be a param: it {}", p->name, clash),
                  "choose another name");
      continue;
    }
    auto known = params_.find(p->name);
    // `--set NAME=25`: a plain number takes the param's unit, as for a property.
    if (p->from_set && known != params_.end() && known->second.type.kind == Kind::Number &&
        !known->second.type.unit.plain()) {
      Expr* literal = p->value->kind == ast::ExprKind::Unary && p->value->op == ast::Op::Neg
                          ? p->value->args[0].get()
                          : p->value.get();
      if (literal->kind == ast::ExprKind::Number && literal->unit_text.empty()) {
        literal->unit_text = known->second.type.unit.name();
        literal->integer_literal = false;
      }
    }
    ExprContext ctx;
    ctx.where = ExprContext::Where::Value;
    Type t = expr(*p->value, ctx);
    if (t.is_error()) continue;
    if (!p->value->constant) {
      sink_
          .error("E0210", p->value->span, fmt::format("the value of param `{}` is not known before slicing", p->name),
                 "reads the print")
          .help("a param is a constant (`param pause_height = 10 mm`); read fields in the rules that use it");
      continue;
    }
    if (t.kind == Kind::Enum) {
      sink_.error("E0210", p->value->span, "a param is a number, an integer or a boolean", "an enum value")
          .help("compare in the rule instead: `param rear_seam = true` ... `seam = if rear_seam then rear else aligned`");
      continue;
    }
    p->type = t;
    p->constant = p->value->constant;
    if (known != params_.end()) {
      const Type& was = known->second.type;
      if (!(was == t)) {
        sink_
            .error("E0211", p->value->span,
                   fmt::format("param `{}` is {} here but {} where it was first defined", p->name, t.describe(),
                               was.describe()),
                   "another kind of value")
            .label(known->second.first->value->span, "first defined here");
        continue;
      }
      known->second.value = *p->constant;
    } else {
      params_[p->name] = ParamValue{t, *p->constant, p};
    }
  }
}

void Checker::rule(ast::Rule& r) {
  rule_ = &r;
  rule_sets_.clear();
  stage_reported_.clear();
  for (const auto& a : r.actions)
    if (a->kind == StmtKind::Assign)
      if (auto p = schema::find_property(a->name)) rule_sets_.insert(*p);

  if (r.filter) {
    ExprContext ctx;
    Type t = expr(*r.filter, ctx);
    if (!t.is_error() && t.kind != Kind::Bool) {
      auto& d = sink_.error("E0201", r.filter->span,
                            fmt::format("a filter must be true or false, found {}", t.describe()),
                            "not true or false");
      if (t.numeric()) d.help(fmt::format("compare it: `{} == ...`", sources_.text(r.filter->span)));
    }
  }

  std::map<uint32_t, const Stmt*> seen;
  for (auto& a : r.actions) {
    size_t slots_before = r.slots.size();
    switch (a->kind) {
      case StmtKind::Assign:
        modifier(r, *a);
        break;
      case StmtKind::Hook:
        hook(r, *a, false);
        break;
      case StmtKind::Replace:
        hook(r, *a, true);
        break;
      default: {
        auto& d = sink_.error("E0400", a->span,
                              fmt::format("{} cannot stand directly in a rule", stmt_word(a->kind)),
                              "not an action");
        if (a->kind == StmtKind::If)
          d.help("a rule's condition is its filter: `rule \"...\" when CONDITION { ... }`");
        else
          d.help("put it in an executor or a replacer: `before layer { ... }`, `replace path { ... }`");
        d.note(
            "a rule holds modifiers (`speed = 20 mm/s`), executors (`before path { ... }`) and replacers "
            "(`replace path { ... }`)");
      }
    }
    if (r.slots.size() == slots_before) continue;
    const ast::Slot& slot = r.slots.back();
    if (auto it = seen.find(slot.key()); it != seen.end()) {
      if (user_file(sources_, a->span))
        sink_
            .warning("W208", a->span, fmt::format("{} is set twice in this rule", slot.describe()),
                     "set again here")
            .label(it->second->span, "first set here")
            .note("the last one wins; the first has no effect");
    } else {
      seen[slot.key()] = a.get();
    }
  }

  if (r.filter)
    for (const auto& slot : r.slots) require(*r.filter, limit_for(slot, r), r);
  conjuncts(r);
  if (r.actions.empty() && !r.from_set && user_file(sources_, r.span))
    sink_.warning("W212", r.span, "this rule has no actions", "does nothing")
        .help("give it a modifier (`speed = 20 mm/s`), an executor or a replacer, or remove it");
}

void Checker::modifier(ast::Rule& r, Stmt& s) {
  auto p = schema::find_property(s.name);
  ExprContext ctx;
  ctx.where = ExprContext::Where::Value;
  if (!p) {
    std::vector<std::string> names;
    for (const auto& info : schema::properties()) names.emplace_back(info.name);
    auto& d = r.from_set
                  ? sink_.error("E0103", s.name_span, fmt::format("unknown property `{}` in `--set`", s.name),
                                "not a property")
                  : sink_.error("E0103", s.name_span, fmt::format("unknown property `{}`", s.name),
                                "not a property");
    if (auto theirs = foreign_property(s.name))
      d.help(fmt::format("`{}` is {} name for it: here it is `{}`", s.name,
                         theirs->whose.empty() ? "another slicer's" : theirs->whose, theirs->ours))
          .fix(s.name_span, std::string(theirs->ours));
    else if (auto best = suggest(s.name, names))
      d.did_you_mean(s.name_span, *best);
    if (level_named(s.name) || schema::find_field(s.name))
      d.note("fields describe the print and cannot be set");
    expr(*s.value, ctx);
    return;
  }
  const auto& info = schema::property(*p);
  s.prop = *p;
  if (info.type == schema::Type::Number) expected_unit_ = ast::Unit::from_schema(info.unit);
  expr(*s.value, ctx, info.enum_type);
  expected_unit_.reset();
  bool ok = assignable(*s.value, Type::of(info.type, info.unit, info.enum_type), s.name, s.name_span);
  if (ok && !r.from_set) range(*s.value, *p);
  if (ok && r.from_set && s.value->constant &&
      (*s.value->constant < info.min || *s.value->constant > info.max)) {
    auto& d = sink_.error(
        "E0500", s.value->span,
        fmt::format("`--set {}` is outside the physical range of `{}`", sources_.text(r.span), s.name),
        fmt::format("expected {} to {}", format_quantity(info.min, info.unit),
                    format_quantity(info.max, info.unit)));
    if (info.unit == schema::Unit::Ratio && *s.value->constant > 1 && *s.value->constant <= 100)
      d.help(fmt::format("for a percentage, write `--set {}={}%`", s.name, sources_.text(s.value->span)));
  }
  ast::Slot slot;
  slot.kind = ast::SlotKind::Property;
  slot.prop = *p;
  slot.stage = info.stage;
  slot.action = &s;
  r.slots.push_back(slot);
  require(*s.value, limit_for(slot, r), r);
}

bool Checker::assignable(Expr& value, const Type& want, std::string_view target,
                         const ast::Span& target_span) {
  const Type& got = value.type;
  if (got.is_error()) return false;
  auto fail = [&](const char* code, std::string message, std::string label) -> diag::Diagnostic& {
    auto& d = sink_.error(code, value.span, std::move(message), std::move(label));
    if (target_span.valid() && target_span.file == value.span.file) d.label(target_span, "set here");
    return d;
  };
  switch (want.kind) {
    case Kind::Number:
    case Kind::Int: {
      if (!got.numeric()) {
        fail("E0202", fmt::format("`{}` needs {}, found {}", target, want.describe(), got.describe()),
             "wrong kind of value");
        return false;
      }
      ast::Unit gu = got.kind == Kind::Number ? got.unit : ast::Unit{};
      bool zero = value.constant == 0.0;
      if (gu != want.unit && !(gu.plain() && zero)) {
        auto& d = fail("E0202",
                       fmt::format("`{}` needs {}, found {}", target, want.describe(),
                                   got.kind == Kind::Int ? std::string("a plain number") : got.describe()),
                       gu.plain() ? "this has no unit" : fmt::format("this is in `{}`", gu.name()));
        if (gu.plain() && value.kind == ast::ExprKind::Number && value.unit_text == "%") {
          // `width = 110%`: a fraction of what? Of the value the earlier rules give it.
          if (schema::find_property(target)) {
            std::string fixed = fmt::format("{} * {}", target, sources_.text(value.span));
            d.help(fmt::format("`%` is a fraction of something: `{} = {}` scales the value the earlier rules give "
                               "it; or write a value in `{}`",
                               target, fixed, want.unit.name()))
                .fix(value.span, fixed);
          }
        } else if (gu.plain() && value.kind == ast::ExprKind::Number) {
          std::string fixed = fmt::format("{} {}", sources_.text(value.span), want.unit.name());
          d.help(fmt::format("write `{}`", fixed)).fix(value.span, fixed);
        }
        else if (want.unit.plain())
          d.note(fmt::format("`{}` is a plain number (a ratio: `1` or `100%` is the full amount)", target));
        return false;
      }
      if (want.kind == Kind::Int && got.kind != Kind::Int) {
        fail("E0203", fmt::format("`{}` needs an integer, found {}", target, got.describe()),
             "not an integer")
            .help("round it: `round(...)`, `floor(...)` or `ceil(...)`")
            .fix(value.span, fmt::format("round({})", sources_.text(value.span)));
        return false;
      }
      return true;
    }
    case Kind::Bool:
      if (got.kind == Kind::Bool) return true;
      fail("E0201", fmt::format("`{}` needs `true` or `false`, found {}", target, got.describe()),
           "not true or false");
      return false;
    case Kind::Enum: {
      if (got == want) return true;
      const auto& info = schema::enum_info(want.enum_type);
      std::vector<std::string> values(info.values.begin(), info.values.end());
      fail("E0204", fmt::format("`{}` needs a `{}` value, found {}", target, info.name, got.describe()),
           "wrong kind of value")
          .note(fmt::format("`{}` values are {}", info.name, quoted_list(values, 12)));
      return false;
    }
    case Kind::Text:  // no property is a name
      fail("E0213", fmt::format("`{}` cannot be set from {}", target, got.describe()), "a name");
      return false;
    case Kind::Error:
      return false;
  }
  return false;
}

void Checker::hook(ast::Rule& r, Stmt& s, bool replace) {
  auto level = level_named(s.name);
  if (!level) {
    std::vector<std::string> names = {"print", "layer", "island", "cell", "path"};
    auto& d = sink_.error("E0101", s.name_span, fmt::format("unknown level `{}`", s.name), "not a level");
    if (auto best = suggest(s.name, names)) d.did_you_mean(s.name_span, *best);
    d.note(replace ? "`replace` takes `path` or `island`"
                   : "hooks are on `print`, `layer`, `island`, `cell` or `path`");
    return;
  }
  if (!replace && *level == schema::Level::Piece) {
    sink_.error("E0406", s.name_span, "there is no hook on `piece`", "not a hook")
        .help("loop over the pieces in a hook on the path: `before path { for pc in path.pieces { ... } }`");
    return;
  }
  if (replace && *level != schema::Level::Path && *level != schema::Level::Island) {
    sink_.error("E0406", s.name_span, fmt::format("`{}` cannot be replaced", s.name), "not replaceable")
        .note("`replace` takes `path` or `island`");
    return;
  }
  s.level = *level;
  ast::Slot slot;
  slot.kind = replace ? ast::SlotKind::Replace : ast::SlotKind::Hook;
  slot.level = *level;
  slot.when = s.when;
  slot.append = s.append;
  slot.stage = replace ? (*level == schema::Level::Island ? schema::Stage::Island : schema::Stage::Path)
                       : schema::Stage::Cooling;
  slot.action = &s;
  r.slots.push_back(slot);
  std::vector<Local> locals;
  bool emitted = false;
  s.frame_size = 0;
  statements(s.body, s, locals, 0, 1, emitted);
}

void Checker::conjuncts(ast::Rule& r) {
  if (!r.filter) return;
  std::vector<const Expr*> stack{r.filter.get()};
  std::vector<const Expr*> leaves;
  while (!stack.empty()) {
    const Expr* e = stack.back();
    stack.pop_back();
    if (e->kind == ast::ExprKind::Binary && e->op == ast::Op::And) {
      stack.push_back(e->args[1].get());
      stack.push_back(e->args[0].get());
    } else {
      leaves.push_back(e);
    }
  }
  for (const Expr* e : leaves) r.conjuncts.push_back(ast::Conjunct{e, e->stage, e->level});
}

}  // namespace tranche::compiler
