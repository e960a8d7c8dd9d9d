// Lints (W2xx) on a checked program. Each is reported only for rules in user files, and only
// when proven: a filter the prover cannot bound is never reported.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <span>

#include "compiler/check.h"
#include "compiler/checker.h"
#include "compiler/prover.h"

namespace tranche::compiler {

using ast::Expr;
using ast::ExprKind;
using ast::Rule;

namespace {

bool user_rule(const ast::SourceMap& sources, const Rule& r) {
  return !r.from_set && r.span.file < sources.size() && sources.file(r.span.file).user;
}

template <class Fn>
void walk(const Expr& e, const Fn& fn) {
  fn(e);
  for (const auto& a : e.args) walk(*a, fn);
}

template <class Fn>
void walk_stmts(const std::vector<ast::StmtPtr>& body, const Fn& fn) {
  for (const auto& s : body) {
    for (const Expr* e : {s->value.get(), s->value2.get(), s->x.get(), s->y.get()})
      if (e) walk(*e, fn);
    for (const auto& o : s->options) walk(*o.value, fn);
    for (const auto& p : s->text.parts)
      if (p.expr) walk(*p.expr, fn);
    walk_stmts(s->body, fn);
    walk_stmts(s->else_body, fn);
  }
}

// W205: `==` on a measured length, area, time... is true only by luck.
void float_equality(const ast::SourceMap& sources, const Rule& r, diag::Sink& sink) {
  auto check = [&](const Expr& e) {
    bool eq = e.kind == ExprKind::Binary && (e.op == ast::Op::Eq || e.op == ast::Op::Ne);
    if (!eq && e.kind != ExprKind::InSet) return;
    for (const auto& side : e.args) {
      const Expr& f = *side;
      bool measured = (f.ref == ast::RefKind::Field || f.ref == ast::RefKind::OtherLayer ||
                       (f.ref == ast::RefKind::ElementField && f.element != ast::Element::Point)) &&
                      f.type.kind == ast::Kind::Number;
      bool point = f.ref == ast::RefKind::ElementField && f.element == ast::Element::Point &&
                   f.point_field != ast::PointField::Index;
      if (!measured && !point) continue;
      std::string name(sources.text(f.span));
      auto& d = sink.warning("W205", e.span,
                             fmt::format("comparing `{}` with `{}` is fragile", name,
                                         eq && e.op == ast::Op::Ne ? "!="
                                         : eq                      ? "=="
                                                                   : "in (...)"),
                             "exact equality of a measured value");
      d.note(
          fmt::format("`{}` comes from geometry and floating-point arithmetic: 0.2 may be 0.19999999", name));
      const Expr& other = side.get() == e.args[0].get() && e.args.size() > 1 ? *e.args[1] : *e.args[0];
      if (eq && other.constant && f.type.unit == ast::Unit{1, 0, 0, 0}) {
        double c = *other.constant;
        d.help(fmt::format("compare with a range: `{} in {:g} mm..{:g} mm`", name, c - 0.01, c + 0.01));
      } else {
        d.help(fmt::format("compare with a range: `{} in LOW..HIGH`", name));
      }
      return;
    }
  };
  if (r.filter) walk(*r.filter, check);
  walk_stmts(r.actions, check);
}

// The constant values an expression can take: itself, or both branches of an `if`.
void constant_leaves(const Expr& e, std::vector<const Expr*>& out) {
  if (e.kind == ExprKind::If && !e.args[0]->constant) {
    constant_leaves(*e.args[1], out);
    constant_leaves(*e.args[2], out);
  } else if (e.constant) {
    out.push_back(&e);
  }
}

// W206: a constant direction outside the property's range (other properties: E0212, an error).
void range(const Expr& value, schema::PropId prop, diag::Sink& sink) {
  const auto& p = schema::property(prop);
  if (!p.wraps()) return;
  std::vector<const Expr*> leaves;
  constant_leaves(value, leaves);
  for (const Expr* e : leaves) {
    double v = *e->constant;
    if (v >= p.min && v <= p.max) continue;
    auto& d = sink.warning(
        "W206", e->span,
        fmt::format("`{}` = {} is outside its physical range", p.name, format_quantity(v, p.unit)),
        fmt::format("expected {} to {}", format_quantity(p.min, p.unit), format_quantity(p.max, p.unit)));
    if (p.unit == schema::Unit::Ratio && v > 1 && v <= 100 && e->kind == ExprKind::Number &&
        e->unit_text.empty())
      d.help(fmt::format("for a percentage, write `{:g}%`", v)).fix(e->span, fmt::format("{:g}%", v));
  }
}

// `below.F` or `above.F`, read directly or scaled by constants (`above.area * 2`): 0 when the
// neighbour is the empty layer.
const Expr* neighbour(const Expr& e) {
  if (e.ref == ast::RefKind::OtherLayer && e.kind == ExprKind::Member && e.other != ast::OtherLayer::Indexed) return &e;
  if (e.kind == ExprKind::Binary && (e.op == ast::Op::Mul || e.op == ast::Op::Div) && !e.constant) {
    if (e.args[1]->constant) return neighbour(*e.args[0]);
    if (e.op == ast::Op::Mul && e.args[0]->constant) return neighbour(*e.args[1]);
  }
  return nullptr;
}

bool reads_other_layers(const Expr& e) {
  bool found = false;
  walk(e, [&](const Expr& x) { found = found || x.ref == ast::RefKind::OtherLayer; });
  return found;
}

// W214: on the first layer `below` is an empty layer (every field 0), and so is `above` on the
// last: a comparison of one of its fields with a positive value of this layer is true there,
// and the rule applies where the user probably did not think of. Filters that place the rule
// (`layer.index`, `layer.z`...) or that test the neighbour against 0 (`below.area > 0`) are left alone.
void edge_layers(const ast::SourceMap& sources, const Rule& r, diag::Sink& sink) {
  if (!r.filter) return;
  for (const auto& c : r.conjuncts) {
    bool guard = false;
    walk(*c.expr, [&](const Expr& x) {
      guard = guard || (x.ref == ast::RefKind::Field &&
                        (x.field == schema::FieldId::LayerIndex || x.field == schema::FieldId::LayerZ ||
                         x.field == schema::FieldId::LayerZBottom || x.field == schema::FieldId::PrintLayers));
    });
    const Expr& e = *c.expr;
    if (e.kind == ExprKind::Binary && e.args.size() == 2 && (neighbour(*e.args[0]) || neighbour(*e.args[1])) &&
        ((e.args[0]->constant && *e.args[0]->constant == 0) || (e.args[1]->constant && *e.args[1]->constant == 0)))
      guard = true;
    if (guard) return;
  }
  for (const auto& c : r.conjuncts) {
    const Expr& e = *c.expr;
    if (e.kind != ExprKind::Binary || e.args.size() != 2) continue;
    bool lt = e.op == ast::Op::Lt || e.op == ast::Op::Le, gt = e.op == ast::Op::Gt || e.op == ast::Op::Ge;
    if (!lt && !gt) continue;
    const Expr* side = neighbour(*e.args[0]);
    const Expr& other = side ? *e.args[1] : *e.args[0];
    bool left = side != nullptr;
    if (!side) side = neighbour(*e.args[1]);
    if (!side || reads_other_layers(other)) continue;
    if (other.constant && *other.constant <= 0) continue;
    // With the neighbour's field at 0 and the other side positive: `0 < X` holds, `0 > X` does not.
    if (left ? !lt : !gt) continue;
    bool below = side->other == ast::OtherLayer::Below;
    std::string shown(sources.text(e.span));
    auto& d = sink.warning("W214", e.span,
                           fmt::format("on the {} layer, `{}` is an empty layer: `{}` is true there",
                                       below ? "first" : "last", below ? "below" : "above", shown),
                           fmt::format("true on the {} layer", below ? "first" : "last"));
    d.note(fmt::format("a layer outside the print reads as an empty layer (every field 0), so the rule applies on "
                       "the {} layer",
                       below ? "first" : "last"));
    std::string guard = below ? "layer.index > 0 and " : "above.area > 0 and ";
    d.help(fmt::format("if the {} layer is not meant, say so: `{}{}`", below ? "first" : "last", guard,
                       sources.text(r.filter->span)));
    d.fix(sources.span(r.filter->span.file, r.filter->span.offset, r.filter->span.offset), guard);
    return;
  }
}

void ranges(const Rule& r, diag::Sink& sink) {
  for (const auto& slot : r.slots)
    if (slot.kind == ast::SlotKind::Property && slot.action && slot.action->value)
      range(*slot.action->value, slot.prop, sink);
  std::function<void(const std::vector<ast::StmtPtr>&)> moves = [&](const std::vector<ast::StmtPtr>& body) {
    for (const auto& s : body) {
      if (s->kind == ast::StmtKind::Move)
        for (const auto& o : s->options)
          if (o.value->type.kind != ast::Kind::Error) range(*o.value, o.prop, sink);
      moves(s->body);
      moves(s->else_body);
    }
  };
  for (const auto& a : r.actions) moves(a->body);
}

// Does this later action take the slot whole, or does it read or add to what earlier rules gave?
bool takes_slot(const ast::Slot& slot) {
  if (slot.kind == ast::SlotKind::Hook && slot.append) return false;
  if (slot.kind != ast::SlotKind::Property || !slot.action || !slot.action->value) return true;
  bool inherits = false;
  walk(*slot.action->value, [&](const Expr& e) { inherits = inherits || e.ref == ast::RefKind::Inherited; });
  return !inherits;
}

struct RuleFacts {
  std::optional<prover::Boxes> boxes;  // the filter as boxes; nothing = unknown
};

// The rules that can take a slot from an earlier rule (known filter, whole slot), latest first.
struct Takers {
  std::vector<size_t> rules;                  // descending cascade index
  std::vector<const prover::Boxes*> filters;  // parallel
};

// What the cascade-wide lints share: each rule's filter as boxes and, per slot key, the rules
// that set it in cascade order and those that can take it.
struct CascadeFacts {
  const ast::SourceMap& sources;
  const std::vector<Rule*>& rules;
  prover::Space space;
  std::vector<RuleFacts> facts;
  std::map<uint32_t, std::vector<size_t>> by_slot;
  std::map<uint32_t, Takers> takers;

  explicit CascadeFacts(const ast::Program& program) : sources(program.sources), rules(program.cascade) {
    facts.resize(rules.size());
    for (size_t i = 0; i < rules.size(); ++i) {
      const Rule& r = *rules[i];
      if (!r.filter)
        facts[i].boxes = prover::Boxes{prover::Box{}};
      else if (!r.filter->type.is_error())
        facts[i].boxes = prover::to_boxes(*r.filter, space, sources, r.index);
    }
    for (size_t i = 0; i < rules.size(); ++i)
      for (const auto& s : rules[i]->slots) by_slot[s.key()].push_back(i);
    for (size_t i = rules.size(); i-- > 0;) {
      std::set<uint32_t> seen;
      for (const auto& s : rules[i]->slots) {
        if (!seen.insert(s.key()).second || !facts[i].boxes || rules[i]->from_set || !takes_slot(s)) continue;
        takers[s.key()].rules.push_back(i);
        takers[s.key()].filters.push_back(&*facts[i].boxes);
      }
    }
  }
};

// W211: two rules of one file with the same name.
void duplicate_name(std::map<std::pair<uint32_t, std::string>, const Rule*>& names, const Rule& r,
                    diag::Sink& sink) {
  if (!r.has_name) return;
  auto [it, fresh] = names.emplace(std::make_pair(r.span.file, r.name), &r);
  if (!fresh)
    sink.warning("W211", r.span, fmt::format("two rules are named \"{}\"", r.name),
                 "second rule with this name")
        .label(it->second->span, "first one")
        .help("give each rule its own name: `rulec explain` and messages refer to rules by name");
}

// W203 (a constant filter), W202 (never true), W204 (always true) on rule i's filter. False when
// the filter is constant or never true: the rule's slots are not worth analysing further.
bool filter_lints(CascadeFacts& c, size_t i, diag::Sink& sink) {
  const Rule& r = *c.rules[i];
  if (!r.filter || r.filter->type.is_error()) return true;
  if (r.filter->constant && r.filter->from_param) return false;  // a param switches it on or off: on purpose
  if (r.filter->constant) {
    bool always = *r.filter->constant != 0;
    sink.warning("W203", r.filter->span, fmt::format("this filter is always {}", always ? "true" : "false"),
                 "a constant")
        .help(always ? "remove `when ...`: a rule without a filter always applies"
                     : "remove the rule: it never applies");
    return false;
  }
  if (c.facts[i].boxes && c.facts[i].boxes->empty()) {
    sink.warning("W202", r.filter->span, "this filter can never be true", "no print element matches it")
        .note("its conditions contradict each other, so the rule never applies");
    return false;
  }
  auto negation = prover::to_boxes(*r.filter, c.space, c.sources, r.index, true);
  if (negation && negation->empty()) {
    auto& d = sink.warning("W204", r.filter->span, "this filter is always true", "matches every element");
    d.help("remove `when ...` if that is intended; otherwise check the comparison");
    for (const auto& s : r.slots) {
      auto& list = c.by_slot[s.key()];
      size_t shadowed = 0;
      for (size_t j : list)
        if (j < i) ++shadowed;
      if (shadowed) {
        d.note(fmt::format("it takes {} from every earlier rule that sets it", s.describe()));
        break;
      }
    }
  }
  return true;
}

// A slot of a rule that later rules always take, and which rules take it.
struct Lost {
  const ast::Slot* slot;
  std::vector<size_t> by;
};

// W213: some of rule r's slots never take effect (each in `lost`).
void lost_slots(const CascadeFacts& c, const Rule& r, std::vector<Lost>& lost, diag::Sink& sink) {
  for (Lost& l : lost) {
    std::sort(l.by.begin(), l.by.end());
    l.by.erase(std::unique(l.by.begin(), l.by.end()), l.by.end());
    const auto& at = l.slot->action ? l.slot->action->span : r.span;
    auto& d = sink.warning(
        "W213", at, fmt::format("{} in rule {} never takes effect", l.slot->describe(), r.display(c.sources)),
        "always overridden by later rules");
    for (size_t k = 0; k < l.by.size() && k < 4; ++k) {
      const Rule& s = *c.rules[l.by[k]];
      d.label(s.span, fmt::format("{} sets it too", s.display(c.sources)));
    }
    if (l.by.size() > 4) d.note(fmt::format("and {} more rules", l.by.size() - 4));
    d.note(
        fmt::format("wherever this rule matches, later rules also set {}: the last match wins; the "
                    "rule's other settings still apply",
                    l.slot->describe()));
    d.help("remove this setting, or move the rule after the ones that override it");
  }
}

// W201: every slot of rule r is taken by the later rules `shadowers` wherever r matches.
void shadowed_rule(const CascadeFacts& c, const Rule& r, std::vector<size_t> shadowers, diag::Sink& sink) {
  std::sort(shadowers.begin(), shadowers.end());
  shadowers.erase(std::unique(shadowers.begin(), shadowers.end()), shadowers.end());
  std::string slots;
  for (size_t k = 0; k < r.slots.size(); ++k) slots += (k ? ", " : "") + r.slots[k].describe();
  auto& d = sink.warning("W201", r.span, fmt::format("rule {} never takes effect", r.display(c.sources)),
                         "always overridden by later rules");
  for (size_t k = 0; k < shadowers.size() && k < 4; ++k) {
    const Rule& s = *c.rules[shadowers[k]];
    d.label(s.span, fmt::format("{} overrides it", s.display(c.sources)));
  }
  if (shadowers.size() > 4) d.note(fmt::format("and {} more rules", shadowers.size() - 4));
  d.note(fmt::format("wherever it matches, later rules also match and set {}: the last match wins", slots));
  d.help("remove it, or move it after the rules that override it");
}

// W201: every slot taken by later rules wherever rule i matches. W213: some of them.
void shadowing(CascadeFacts& c, size_t i, diag::Sink& sink) {
  const Rule& r = *c.rules[i];
  if (r.slots.empty() || !c.facts[i].boxes || c.facts[i].boxes->empty()) return;
  std::vector<size_t> shadowers;
  std::vector<Lost> lost;
  bool shadowed = true;
  std::set<uint32_t> seen_slots;
  for (const auto& slot : r.slots) {
    if (!seen_slots.insert(slot.key()).second) continue;  // set twice in the rule: W208
    // Latest first: a rule that still finds part of the region uncovered is the one that wins
    // there, so the rules named are exactly those that take the slot from this one.
    const Takers& t = c.takers[slot.key()];
    size_t later = static_cast<size_t>(
        std::partition_point(t.rules.begin(), t.rules.end(), [&](size_t j) { return j > i; }) -
        t.rules.begin());
    std::vector<size_t> used;
    auto proof = later == 0
                     ? std::optional<bool>(false)
                     : prover::covered(*c.facts[i].boxes, std::span(t.filters.data(), later), c.space, &used);
    if (!proof || !*proof) {
      shadowed = false;
      continue;
    }
    Lost l{&slot, {}};
    for (size_t u : used) shadowers.push_back(t.rules[u]), l.by.push_back(t.rules[u]);
    lost.push_back(std::move(l));
  }
  if (!shadowed)
    lost_slots(c, r, lost, sink);
  else
    shadowed_rule(c, r, std::move(shadowers), sink);
}

}  // namespace

void lint(const ast::Program& program, diag::Sink& sink) {
  CascadeFacts cascade(program);
  std::map<std::pair<uint32_t, std::string>, const Rule*> names;  // per file (W211)
  for (size_t i = 0; i < cascade.rules.size(); ++i) {
    const Rule& r = *cascade.rules[i];
    if (!user_rule(program.sources, r)) continue;
    duplicate_name(names, r, sink);
    float_equality(program.sources, r, sink);
    ranges(r, sink);
    edge_layers(program.sources, r, sink);
    if (!filter_lints(cascade, i, sink)) continue;
    shadowing(cascade, i, sink);
  }
}

}  // namespace tranche::compiler
