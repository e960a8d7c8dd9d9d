// Statements in hook and replacer bodies: what may stand there, `if`, `for` loops (ranges and
// collections), `move`, templates, `offset`/`reverse`, and the body's locals.
#include <fmt/format.h>

#include <cmath>
#include <set>

#include "compiler/checker.h"
#include "compiler/names.h"

namespace tranche::compiler {

using ast::Expr;
using ast::Kind;
using ast::Stmt;
using ast::StmtKind;
using ast::Type;

namespace {

constexpr int64_t kMaxRangeSteps = 10000;
constexpr double kMaxLoopSteps = 1e6;  // iterations of nested constant ranges, all together

}  // namespace

void Checker::statements(std::vector<ast::StmtPtr>& body, Stmt& action, std::vector<Local>& locals,
                         int nesting, double loop_steps, bool& emitted) {
  size_t mark = locals.size();
  for (auto& s : body) statement(*s, action, locals, nesting, loop_steps, emitted);
  unused_locals(locals, mark);
  locals.resize(mark);
}

// What the statements of `action` (a hook or replacer body) may read.
Limit Checker::body_limit(const Stmt& action) const {
  ast::Slot body_slot;
  body_slot.kind = ast::SlotKind::Hook;
  body_slot.level = action.level;
  body_slot.when = action.when;
  body_slot.action = &action;
  Limit limit = limit_for(body_slot, *rule_);
  if (action.kind == StmtKind::Replace)
    limit.what = fmt::format("`replace {}` runs once per {}", action.name, action.name);
  return limit;
}

void Checker::statement(Stmt& s, Stmt& action, std::vector<Local>& locals, int nesting, double loop_steps,
                        bool& emitted) {
  bool replace = action.kind == StmtKind::Replace;
  ExprContext ctx;
  ctx.where = ExprContext::Where::Body;
  ctx.locals = &locals;
  const Limit limit = body_limit(action);
  const char* where = replace ? "replace" : action.when == ast::When::Before ? "before" : "after";
  switch (s.kind) {
    case StmtKind::Assign:
      sink_
          .error("E0400", s.span, "properties are set directly in a rule",
                 fmt::format("not allowed inside `{}`", where))
          .help("for a single move, write `move to (x, y) with speed = ...`");
      expr(*s.value, ctx);
      return;
    case StmtKind::Hook:
    case StmtKind::Replace:
      sink_
          .error("E0400", s.span, fmt::format("{} cannot be nested", stmt_word(s.kind)),
                 fmt::format("inside `{} {}`", where, action.name))
          .help("put it directly in a rule");
      return;
    case StmtKind::Gcode:
    case StmtKind::Comment:
      text(s.text, ctx);
      for (const auto& p : s.text.parts)
        if (p.expr) require(*p.expr, limit, *rule_);
      emitted = true;
      return;
    case StmtKind::Let: {
      Type t = expr(*s.value, ctx);
      require(*s.value, limit, *rule_);
      Local l;
      l.name = s.name;
      l.span = s.name_span;
      l.type = t;
      if (declare(locals, std::move(l), action)) s.local = locals.back().slot;
      return;
    }
    case StmtKind::If:
      if_statement(s, action, locals, nesting, loop_steps, emitted, ctx, limit);
      return;
    case StmtKind::For:
      loop(s, action, locals, nesting, loop_steps, emitted);
      return;
    case StmtKind::Move:
      move(s, ctx);
      if (s.x) require(*s.x, limit, *rule_);
      if (s.y) require(*s.y, limit, *rule_);
      for (const auto& o : s.options) require(*o.value, limit, *rule_);
      emitted = true;
      return;
    case StmtKind::Default:
      if (!replace)
        sink_
            .error("E0401", s.span, "`default` is only allowed in a replacer",
                   fmt::format("inside `{}`", where))
            .help("`default` stands for the element's own G-code: use it in `replace path { ... }`");
      emitted = true;
      return;
    case StmtKind::Retract:
      if (!replace)
        sink_
            .error("E0401", s.span, "`retract` is only allowed in a replacer",
                   fmt::format("inside `{}`", where))
            .help(
                "the slicer retracts before the travels that need it; a replacer that moves on its own "
                "says where with `retract`");
      emitted = true;
      return;
    case StmtKind::Offset:
    case StmtKind::Reverse:
      alteration(s, action, nesting, emitted, ctx, where);
      return;
  }
}

// `if C { ... } else { ... }`: C true or false, each branch checked; `emitted` when either emits.
void Checker::if_statement(Stmt& s, Stmt& action, std::vector<Local>& locals, int nesting, double loop_steps,
                           bool& emitted, ExprContext& ctx, const Limit& limit) {
  Type t = expr(*s.value, ctx);
  require(*s.value, limit, *rule_);
  if (!t.is_error() && t.kind != Kind::Bool) {
    sink_.error("E0201", s.value->span,
                fmt::format("the condition of `if` must be true or false, found {}", t.describe()),
                "not true or false");
  } else if (s.value->constant && !s.value->from_param && user_file(sources_, s.span)) {
    sink_
        .warning("W203", s.value->span,
                 fmt::format("this condition is always {}", *s.value->constant != 0 ? "true" : "false"),
                 "a constant")
        .help(*s.value->constant != 0 ? "remove the `if`" : "remove the `if` and its block");
  }
  bool a = emitted, b = emitted;
  statements(s.body, action, locals, nesting + 1, loop_steps, a);
  statements(s.else_body, action, locals, nesting + 1, loop_steps, b);
  emitted = a || b;
}

// `offset` and `reverse`: only in a replacer, at its top, before anything it prints; an offset
// is a length read when the element is decided.
void Checker::alteration(Stmt& s, Stmt& action, int nesting, bool emitted, ExprContext& ctx,
                         const char* where) {
  const bool replace = action.kind == StmtKind::Replace;
  const char* word = s.kind == StmtKind::Offset ? "offset" : "reverse";
  if (!replace) {
    sink_
        .error("E0401", s.span, fmt::format("`{}` is only allowed in a replacer", word),
               fmt::format("inside `{}`", where))
        .help(fmt::format("write it in `replace {} {{ ... }}`",
                          s.kind == StmtKind::Offset ? "island" : "path"));
  } else if (s.kind == StmtKind::Reverse && action.level != schema::Level::Path) {
    sink_.error("E0402", s.span, "`reverse` only applies to paths", "inside `replace island`")
        .help("reverse a path in `replace path { reverse; default }`");
  } else if (nesting > 0) {
    sink_
        .error("E0404", s.span, fmt::format("`{}` must stand at the top of the replacer", word),
               "inside `if` or `for`")
        .help(
            "put the condition in the rule's filter: the element is altered once, before it is printed");
  } else if (emitted) {
    sink_
        .error("E0403", s.span, fmt::format("`{}` must come before anything the replacer prints", word),
               "after G-code was emitted")
        .help(fmt::format(
            "move `{}` to the start of the block: the element is altered before any of it prints", word));
  }
  if (s.kind == StmtKind::Offset) {
    expr(*s.value, ctx);
    assignable(*s.value, Type::number(ast::Unit{1, 0, 0, 0}), "offset", {});
    // The alteration happens when the element is decided, not when it is printed.
    ast::Slot alter;
    alter.kind = ast::SlotKind::Replace;
    alter.level = action.level;
    alter.action = &action;
    Limit when = limit_for(alter, *rule_);
    require(*s.value, when, *rule_);
  }
}

// `for i in LO..HI`: integer bounds known before slicing, at most kMaxRangeSteps steps and
// kMaxLoopSteps with the loops around it. Returns its number of steps (at least 1).
double Checker::range_loop(Stmt& s, Local& var, ExprContext& ctx, double loop_steps) {
  double steps = 1;
  Type lo = expr(*s.value, ctx);
  Type hi = expr(*s.value2, ctx);
  s.loop = ast::LoopKind::Range;
  var.type = Type::integer();
  var.element = ast::Element::Int;
  bool ok = !lo.is_error() && !hi.is_error();
  for (const Expr* bound : {s.value.get(), s.value2.get()}) {
    if (ok && (bound->type.kind != Kind::Int || !bound->constant)) {
      sink_
          .error("E0405", bound->span, "the bounds of a `for` range must be integers known before slicing",
                 bound->type.kind != Kind::Int ? "not an integer" : "not a constant")
          .help(
              "loops run a fixed number of times: `for i in 1..3 { ... }`; to loop over the print, use "
              "`path.points`, `path.pieces` or `layer.islands`");
      ok = false;
    }
  }
  if (ok) {
    s.range_lo = static_cast<int64_t>(*s.value->constant);
    s.range_hi = static_cast<int64_t>(*s.value2->constant);
    double n = static_cast<double>(s.range_hi) - static_cast<double>(s.range_lo) + 1;
    ast::Span range = join(s.value->span, s.value2->span);
    if (n > static_cast<double>(kMaxRangeSteps)) {
      sink_.error("E0405", range,
                  fmt::format("this range has {:.0f} steps; at most {} are allowed", n, kMaxRangeSteps),
                  "too many steps");
    } else if (n <= 0) {
      if (user_file(sources_, range))
        sink_
            .warning("W210", range,
                     fmt::format("the range `{}` is empty: the loop never runs", sources_.text(range)),
                     "no steps")
            .help("ranges count up and include both ends: `1..3` is 1, 2, 3");
    } else if (loop_steps * n > kMaxLoopSteps) {
      sink_.error("E0405", range,
                  fmt::format("nested loops would run {:.0f} times; at most {:.0f} are allowed",
                              loop_steps * n, kMaxLoopSteps),
                  "the innermost range");
    }
    steps = std::max(n, 1.0);
  }
  return steps;
}

// `for p in path.points` (`path.pieces`, `layer.islands`): a collection the action's level can read.
void Checker::collection_loop(Stmt& s, Stmt& action, Local& var) {
  Expr& c = *s.value;
  std::string name = c.kind == ast::ExprKind::Member ? c.text + "." + c.member : std::string();
  std::optional<schema::Level> needs;
  if (name == "path.points") {
    s.loop = ast::LoopKind::Points;
    var.element = ast::Element::Point;
    needs = schema::Level::Path;
  } else if (name == "path.pieces") {
    s.loop = ast::LoopKind::Pieces;
    var.element = ast::Element::Piece;
    needs = schema::Level::Path;
  } else if (name == "layer.islands") {
    s.loop = ast::LoopKind::Islands;
    var.element = ast::Element::Island;
    needs = schema::Level::Layer;
  } else {
    sink_
        .error("E0405", c.span, fmt::format("cannot loop over `{}`", sources_.text(c.span)),
               "not a collection")
        .note("`for` loops over `path.points`, `path.pieces`, `layer.islands` or a constant range `A..B`");
    var.type = Type::error();
    var.used = true;  // one error is enough
  }
  if (needs && action.level < *needs) {
    sink_
        .error("E0304", c.span,
               fmt::format("`{}` cannot be read in `{} {}`", name,
                           action.kind == StmtKind::Replace ? "replace" : "before", action.name),
               fmt::format("needs a hook on `{}` or deeper", schema::level_name(*needs)))
        .help(fmt::format("loop in a hook on the {}: `before {} {{ for ... }}`", schema::level_name(*needs),
                          schema::level_name(*needs)));
  }
  c.type = Type::error();  // a collection, not a value; `loop` says which
}

void Checker::loop(Stmt& s, Stmt& action, std::vector<Local>& locals, int nesting, double loop_steps,
                   bool& emitted) {
  ExprContext ctx;
  ctx.where = ExprContext::Where::Body;
  ctx.locals = &locals;
  Local var;
  var.name = s.name;
  var.span = s.name_span;
  var.loop = true;
  double steps = 1;
  if (s.value2)
    steps = range_loop(s, var, ctx, loop_steps);
  else
    collection_loop(s, action, var);
  size_t mark = locals.size();
  if (declare(locals, std::move(var), action)) s.local = locals.back().slot;
  statements(s.body, action, locals, nesting + 1, loop_steps * steps, emitted);
  unused_locals(locals, mark);
  locals.resize(mark);
}

void Checker::move(Stmt& s, ExprContext& ctx) {
  for (Expr* coord : {s.x.get(), s.y.get()}) {
    expr(*coord, ctx);
    assignable(*coord, Type::number(ast::Unit{1, 0, 0, 0}), "move to", {});
  }
  std::set<std::string> given;
  for (auto& o : s.options) {
    auto p = schema::find_property(o.name);
    bool allowed =
        p && (*p == schema::PropId::Speed || *p == schema::PropId::Flow || *p == schema::PropId::Width);
    if (!allowed) {
      auto& d = sink_.error("E0407", o.name_span, fmt::format("`move ... with` cannot set `{}`", o.name),
                            "not a move setting");
      if (auto best = suggest(o.name, {"speed", "flow", "width"}))
        d.did_you_mean(o.name_span, *best);
      d.note("a move takes `speed`, `flow` and `width`");
      expr(*o.value, ctx);
      continue;
    }
    if (!given.insert(o.name).second)
      sink_.error("E0407", o.name_span, fmt::format("`{}` is given twice", o.name), "given again");
    o.prop = *p;
    const auto& info = schema::property(*p);
    expected_unit_ = ast::Unit::from_schema(info.unit);
    expr(*o.value, ctx);
    expected_unit_.reset();
    if (assignable(*o.value, Type::of(info.type, info.unit, info.enum_type), o.name, o.name_span))
      range(*o.value, *p);
  }
}

void Checker::text(ast::Template& t, ExprContext& ctx) {
  placeholders(t);
  for (auto& p : t.parts) {
    if (!p.expr) continue;
    Type type = expr(*p.expr, ctx);
    if (type.is_error()) continue;
    if (type.kind == Kind::Text) {
      sink_
          .error("E0213", p.span, "a name cannot be printed in a template", "a name")
          .help("a name is only compared with quoted text: `when object.name == \"lid\" { ... }`");
      continue;
    }
    if (p.decimals >= 0 && !type.numeric())
      sink_
          .error("E0207", p.span,
                 fmt::format("`:.{}` formats numbers, but this is {}", p.decimals, type.describe()),
                 "not a number")
          .help("remove the format: enum values print as their name, booleans as 1 or 0");
  }
}

bool Checker::declare(std::vector<Local>& locals, Local local, Stmt& action) {
  auto clash = [&](std::string why) {
    sink_.error("E0108", local.span, fmt::format("`{}` {}", local.name, why), "choose another name");
  };
  for (const auto& l : locals) {
    if (l.name == local.name) {
      sink_
          .error("E0108", local.span, fmt::format("`{}` is already defined", local.name),
                 "defined again here")
          .label(l.span, "first defined here")
          .help("choose another name");
      return false;
    }
  }
  if (schema::find_property(local.name)) {
    clash("is a property");
    return false;
  }
  if (params_.count(local.name)) {
    clash("is a param");
    return false;
  }
  if (level_named(local.name) || local.name == "below" || local.name == "above" || local.name == "layers") {
    clash("names a level");
    return false;
  }
  for (const auto& e : schema::enums()) {
    if (e.id != schema::EnumType::None && schema::find_enum_value(e.id, local.name)) {
      clash(fmt::format("is a `{}` value", e.name));
      return false;
    }
  }
  local.slot = action.frame_size++;
  locals.push_back(std::move(local));
  return true;
}

void Checker::unused_locals(std::vector<Local>& locals, size_t from) {
  for (size_t i = from; i < locals.size(); ++i) {
    const Local& l = locals[i];
    if (l.used || l.name.starts_with('_') || !user_file(sources_, l.span)) continue;
    if (l.loop)
      sink_.warning("W209", l.span, fmt::format("loop variable `{}` is never used", l.name), "unused")
          .help(fmt::format("to repeat without reading it, name it `_`: `for _ in ...`"))
          .fix(l.span, "_");
    else
      sink_.warning("W200", l.span, fmt::format("`let {}` is never used", l.name), "unused")
          .help("remove it, or start its name with `_`");
  }
}

}  // namespace tranche::compiler
