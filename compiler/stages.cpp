// Stages: what each slot may read, and the order of same-stage properties.
#include <fmt/format.h>

#include <functional>
#include <set>

#include "compiler/checker.h"

namespace tranche::compiler {

using ast::Expr;
using ast::RefKind;
using schema::Level;
using schema::Stage;

std::string decided_at(Stage s) {
  switch (s) {
    case Stage::Print:
      return "decided once, before anything is sliced";
    case Stage::LayerPlan:
      return "decided while layer heights are planned, before the layer is sliced";
    case Stage::Layer:
      return "decided per layer, once every layer is sliced";
    case Stage::Island:
      return "decided per island, before any path exists";
    case Stage::Cell:
      return "decided per fill cell, before its paths exist";
    case Stage::PathPlan:
      return "decided per path, before its geometry is built";
    case Stage::Path:
      return "decided per path, once its geometry is built";
    case Stage::Piece:
      return "decided per straight move, before the layer's print time is estimated";
    case Stage::Cooling:
      return "decided once the layer's print time is estimated";
  }
  return "?";
}

std::string known_at(Stage s) {
  switch (s) {
    case Stage::Print:
      return "known before slicing";
    case Stage::LayerPlan:
      return "known while planning layer heights";
    case Stage::Layer:
      return "known once the layer is sliced";
    case Stage::Island:
      return "known per island";
    case Stage::Cell:
      return "known per fill cell";
    case Stage::PathPlan:
      return "known when a path is planned";
    case Stage::Path:
      return "known once a path's geometry is built";
    case Stage::Piece:
      return "known per piece";
    case Stage::Cooling:
      return "known once the layer's print time is estimated";
  }
  return "?";
}

std::string format_quantity(double value, schema::Unit unit) {
  if (unit == schema::Unit::Ratio) return fmt::format("{:g}%", value * 100);
  if (unit == schema::Unit::None) return fmt::format("{:g}", value);
  return fmt::format("{:g} {}", value, schema::unit_name(unit));
}

namespace {

std::string runs_once_per(Level l) {
  return l == Level::Print ? "runs once for the whole print"
                           : fmt::format("runs once per {}", schema::level_name(l));
}

// A field known earlier that says nearly the same thing.
std::optional<std::string> substitute(schema::FieldId f, Stage limit) {
  if (f == schema::FieldId::LayerZ && limit >= Stage::LayerPlan)
    return "`layer.z_bottom` is known while planning layer heights: use it instead (the layer's top is "
           "`layer.z_bottom` plus its height)";
  if (f == schema::FieldId::PathKind && limit == Stage::Cell)
    return "`cell.solid` says whether a fill cell is solid (top, bottom, bridge or internal solid): "
           "`rule when cell.solid { fill_angle = 0 deg }` decides it per cell";
  return std::nullopt;
}

}  // namespace

Limit Checker::limit_for(const ast::Slot& slot, const ast::Rule& r) const {
  (void)r;
  Limit l;
  l.site = slot.action ? (slot.action->name_span.valid() ? slot.action->name_span : slot.action->span)
                       : ast::Span{};
  switch (slot.kind) {
    case ast::SlotKind::Property: {
      const auto& p = schema::property(slot.prop);
      l.stage = p.stage;
      l.prop = slot.prop;
      l.what = fmt::format("`{}` is {}", p.name, decided_at(p.stage));
      if (schema::finest_stage(p.id) != p.stage) {  // fill_angle: again per cell
        l.fields_until = schema::finest_stage(p.id);
        const auto lv = schema::level_name(schema::stage_level(*l.fields_until));
        l.what = fmt::format("`{}` is {} (or per {} by a rule that reads `{}.*`)", p.name, decided_at(p.stage), lv, lv);
      }
      break;
    }
    case ast::SlotKind::Hook:
      l.level = slot.level;
      l.what = fmt::format("`{} {}` {}", slot.when == ast::When::Before ? "before" : "after",
                           schema::level_name(slot.level), runs_once_per(slot.level));
      break;
    case ast::SlotKind::Replace:
      l.level = slot.level;
      l.stage = slot.level == Level::Island ? Stage::Island : Stage::Path;
      l.what = fmt::format("`replace {}` is {}", schema::level_name(slot.level), decided_at(*l.stage));
      break;
  }
  return l;
}

void Checker::require(const Expr& e, const Limit& limit, const ast::Rule& r) {
  for (const auto& a : e.args) require(*a, limit, r);
  if (e.ref == RefKind::None || e.ref == RefKind::Local || e.ref == RefKind::ElementField ||
      e.ref == RefKind::EnumValue || e.ref == RefKind::Bound)
    return;
  std::string shown(sources_.text(e.span));
  auto report = [&](const char* code, std::string message, std::string label) -> diag::Diagnostic* {
    if (!stage_reported_.insert(e.span.offset).second) return nullptr;
    auto& d = sink_.error(code, e.span, std::move(message), std::move(label));
    if (limit.site.valid() && limit.site.file == e.span.file && limit.site.offset != e.span.offset)
      d.label(limit.site, "the slot is set here");
    // A filter shared by several actions may suit some of them: say so.
    if (r.filter && e.span.offset >= r.filter->span.offset && e.span.end() <= r.filter->span.end() &&
        r.slots.size() > 1)
      d.help("the filter applies to every action of the rule: move this action to a rule of its own");
    return &d;
  };
  if (e.ref == RefKind::Field || e.ref == RefKind::OtherLayer) {
    const auto& f = schema::field(e.field);
    Stage known = e.ref == RefKind::OtherLayer ? std::max(Stage::Layer, f.stage) : f.stage;
    Level level = e.ref == RefKind::OtherLayer ? Level::Layer : f.level;
    const std::optional<Stage> until = limit.fields_until ? limit.fields_until : limit.stage;
    if (until && known > *until) {
      std::string when = e.ref == RefKind::OtherLayer ? "other layers are known once every layer is sliced"
                                                      : known_at(known);
      if (auto* d =
              report("E0300", fmt::format("{}, so `{}` ({}) cannot be read here", limit.what, shown, when),
                     "not known yet")) {
        if (auto s = substitute(e.field, *until)) d->help(*s);
        if (d->helps.empty())
          d->help(fmt::format("read what is {} (the fields of `{}` and the levels above it), or set a property "
                              "decided later",
                              known_at(*until), schema::level_name(schema::stage_level(*until))));
      }
    } else if (limit.level && level > *limit.level) {
      std::string of = e.ref == RefKind::OtherLayer ? "another layer"
                                                    : fmt::format("a {} field", schema::level_name(level));
      if (auto* d =
              report("E0302", fmt::format("{}, so `{}` ({}) cannot be read here", limit.what, shown, of),
                     fmt::format("one value per {}", schema::level_name(level)))) {
        if (level == Level::Piece && *limit.level == Level::Path)
          d->help("loop over the pieces to read them: `for pc in path.pieces { ... pc.length ... }`");
        else if (level == Level::Piece)
          d->help(
              "loop over the pieces in a hook on the path: `before path { for pc in path.pieces { ... } }`");
        else
          d->help(fmt::format("use a hook on the {0}: `before {0} {{ ... }}`", schema::level_name(level)));
      }
    }
    return;
  }
  // A property read: its decided value (Property) or the value earlier rules give it (Inherited).
  const auto& q = schema::property(e.prop);
  if (limit.stage) {
    if (q.stage > *limit.stage) {
      report("E0301",
             fmt::format("{}, so `{}` ({}) cannot be read here", limit.what, q.name, decided_at(q.stage)),
             "decided later");
      return;
    }
    if (q.stage == *limit.stage && e.ref == RefKind::Property && limit.prop && *limit.prop != e.prop)
      deps_.push_back(Dependency{*limit.prop, e.prop, e.span, &r});
  }
  // Hooks on the print read layer properties as decided for the first layer: the start G-code
  // heats to the first layer's temperatures.
  bool first_layer = limit.level == Level::Print && !limit.stage && q.stage <= Stage::Layer;
  if (limit.level && schema::stage_level(q.stage) > *limit.level && !first_layer) {
    report("E0302",
           fmt::format("{}, so `{}` ({}) cannot be read here", limit.what, q.name, decided_at(q.stage)),
           fmt::format("one value per {}", schema::level_name(schema::stage_level(q.stage))));
  }
}

// Same-stage properties may read each other in one direction only; the order found here is
// the order codegen decides them in.
void Checker::dependencies() {
  const int n = schema::kPropCount;
  std::vector<std::vector<const Dependency*>> out(static_cast<size_t>(n));
  for (const auto& d : deps_) out[static_cast<size_t>(d.from)].push_back(&d);
  std::vector<int> state(static_cast<size_t>(n), 0);  // 0 new, 1 on the stack, 2 done
  std::vector<const Dependency*> path;
  std::vector<schema::PropId> order;
  std::set<std::pair<int, int>> reported;
  std::function<void(int)> visit = [&](int p) {
    state[static_cast<size_t>(p)] = 1;
    for (const Dependency* d : out[static_cast<size_t>(p)]) {
      int q = static_cast<int>(d->to);
      if (state[static_cast<size_t>(q)] == 1) {
        if (!reported.insert({p, q}).second) continue;
        // A cycle: the edges from q back to q on the current path, plus this one.
        std::vector<const Dependency*> cycle;
        for (const Dependency* e : path)
          if (!cycle.empty() || static_cast<int>(e->from) == q) cycle.push_back(e);
        cycle.push_back(d);
        std::string names;
        for (const Dependency* e : cycle) names += fmt::format("`{}` → ", schema::property(e->from).name);
        names += fmt::format("`{}`", schema::property(d->to).name);
        auto& diag = sink_.error("E0305", d->at, fmt::format("properties read each other: {}", names),
                                 fmt::format("`{}` reads `{}` here", schema::property(d->from).name,
                                             schema::property(d->to).name));
        for (const Dependency* e : cycle)
          if (e != d)
            diag.label(e->at, fmt::format("`{}` reads `{}` here", schema::property(e->from).name,
                                          schema::property(e->to).name));
        diag.note(fmt::format("both are {}: one of them must be decided first",
                              decided_at(schema::property(d->from).stage)));
        diag.help(
            "read the property in one direction only; inside its own modifier a property's name means "
            "its value from the earlier rules");
        continue;
      }
      if (state[static_cast<size_t>(q)] == 0) {
        path.push_back(d);
        visit(q);
        path.pop_back();
      }
    }
    state[static_cast<size_t>(p)] = 2;
    order.push_back(static_cast<schema::PropId>(p));
  };
  // Visit by stage so that the order is stage-major; dependencies come out first.
  std::vector<int> by_stage(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) by_stage[static_cast<size_t>(i)] = i;
  std::stable_sort(by_stage.begin(), by_stage.end(), [](int a, int b) {
    return schema::property(static_cast<schema::PropId>(a)).stage <
           schema::property(static_cast<schema::PropId>(b)).stage;
  });
  for (int p : by_stage)
    if (state[static_cast<size_t>(p)] == 0) visit(p);
  program_.property_order = std::move(order);
}

}  // namespace tranche::compiler
