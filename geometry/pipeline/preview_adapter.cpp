#include "geometry/pipeline/preview_adapter.h"

#include <fmt/format.h>

#include <map>
#include <unordered_map>

#include "runtime/vm/trace_text.h"

namespace tranche::pipeline {
namespace {

using plan::IslandPlan;
using plan::Op;
using plan::PathPlan;
using preview::ChainStep;
using preview::SourceKind;
using schema::PropId;

// The slots every path shows; others only when something other than a default decided them.
bool always_shown(PropId p) {
  return p == PropId::Speed || p == PropId::Flow || p == PropId::Width || p == PropId::Fan ||
         p == PropId::FillAngle;
}

// Turns trace steps into preview chains, naming rules.
class Chains {
 public:
  explicit Chains(const vm::RuleSet* rules) : rules_(rules) {}

  void add(const plan::TraceLog* log) {
    if (!log) return;
    for (const ctx::TraceStep& s : log->steps) chains_[s.prop].push_back(step(s));
  }
  void add_step(PropId prop, ChainStep s) { chains_[prop].push_back(std::move(s)); }
  bool has(PropId prop) const { return chains_.count(prop) > 0; }
  double last(PropId prop) const { return chains_.at(prop).back().value; }

  std::vector<preview::SlotChain> slots() const {
    std::vector<preview::SlotChain> out;
    for (const auto& [prop, steps] : chains_) {
      bool decided = always_shown(prop);
      for (const auto& s : steps)
        decided = decided || (s.source != SourceKind::SchemaDefault && s.source != SourceKind::BuiltinDefault);
      if (decided) out.push_back({prop, steps});
    }
    return out;
  }

  void rule_source(uint32_t rule, uint32_t chunk, ChainStep& c) const {
    if (!rules_) return;
    c.rule = rules_->rule_label(rule);
    uint32_t line = 0;
    vm::rule_position(*rules_, rule, chunk, c.file, line);
    c.line = static_cast<int>(line);
    c.source = c.file.find("/stdlib/") != std::string::npos || c.file.rfind("stdlib/", 0) == 0 ? SourceKind::Profile
                                                                                              : SourceKind::Rule;
  }

 private:
  ChainStep step(const ctx::TraceStep& s) const {
    ChainStep c;
    c.value = s.value;
    switch (s.source) {
      case ctx::TraceStep::Source::Start:
        c.source = SourceKind::SchemaDefault;
        break;
      case ctx::TraceStep::Source::BuiltinDefault:
        c.source = SourceKind::BuiltinDefault;  // the source names it: no rule name, or the page says it twice
        c.text = vm::builtin_rule_text(s.rule);
        break;
      case ctx::TraceStep::Source::Middle:
        c.source = SourceKind::Script;
        c.rule = "--fill-angle-script";
        break;
      case ctx::TraceStep::Source::Rule:
        rule_source(s.rule, s.chunk, c);
        if (s.depth > 0) c.text = "read by the rule after it";
        break;
      case ctx::TraceStep::Source::Set:
        c.source = SourceKind::Set;
        c.text = fmt::format("{}={:g}", schema::property(s.prop).name, s.value);
        break;
    }
    return c;
  }

  const vm::RuleSet* rules_;
  std::map<PropId, std::vector<ChainStep>> chains_;
};

preview::PointMm mm(const setup::PrintSetup& S, const geo::Point& p) {
  return {static_cast<float>(geo::to_mm(p.X + S.shift.X)), static_cast<float>(geo::to_mm(p.Y + S.shift.Y))};
}

// Builds the layer's paths and travels in print order.
class LayerBuilder {
 public:
  LayerBuilder(const setup::PrintSetup& s, const plan::LayerPlan& lp, const gcode::LayerText* text,
               const vm::RuleSet* rules)
      : S(s), L(lp), text_(text), rules_(rules) {
    out_.index = lp.index;
    out_.z = static_cast<float>(lp.z);
    out_.height = static_cast<float>(lp.height);
  }

  preview::PreviewLayer run() {
    for (const PathPlan& p : L.skirt) path(nullptr, p, nullptr);
    for (const IslandPlan& ip : L.islands) {
      if (!ip.replaced) {
        for (const PathPlan& p : ip.paths) path(&ip, p, nullptr);
        continue;
      }
      auto note = replacer_note(ip.trace ? ip.trace->replacer : UINT32_MAX, ip.ops);
      ops(&ip, nullptr, ip.ops, note, [&] {
        for (const PathPlan& p : ip.paths) path(&ip, p, note);
      });
    }
    return std::move(out_);
  }

 private:
  std::shared_ptr<const preview::ReplacerNote> replacer_note(uint32_t rule, const std::vector<Op>& ops) const {
    auto n = std::make_shared<preview::ReplacerNote>();
    if (rule != UINT32_MAX && rules_) {
      n->rule = rules_->rule_label(rule);
      uint32_t line = 0;
      vm::rule_position(*rules_, rule, UINT32_MAX, n->file, line);
      n->line = static_cast<int>(line);
    }
    for (const Op& o : ops) n->emitted_default = n->emitted_default || o.kind == Op::Kind::Default;
    return n;
  }

  // What a path's record is made of, as bytes: paths (and pieces) decided alike get one record,
  // built once (the encoder stores each distinct record once, and skips the paths that share it).
  std::string record_key(const IslandPlan* ip, const PathPlan& p, const plan::TraceLog* piece) const {
    std::string key;
    auto put = [&key](const auto& v) { key.append(reinterpret_cast<const char*>(&v), sizeof v); };
    const plan::TraceLog* logs[] = {L.trace.get(), ip ? ip->trace.get() : nullptr, p.trace.get(), piece};
    for (const plan::TraceLog* log : logs) {
      put(log ? log->steps.size() : size_t(0));
      if (log)
        for (const ctx::TraceStep& t : log->steps) {
          put(t.prop), put(t.source), put(t.rule), put(t.chunk), put(t.value), put(t.depth);
        }
    }
    put(L.slowed && !p.pieces.empty() ? p.pieces[0].speed : 0.0f);
    if (text_)
      for (const auto& h : text_->hooks)
        if (h.path == &p) {
          put(h.after), put(h.level), put(h.rule), put(h.text.size());
          key += h.text;
        }
    return key;
  }

  std::shared_ptr<const preview::Provenance> provenance(const IslandPlan* ip, const PathPlan& p,
                                                        const plan::TraceLog* piece,
                                                        std::shared_ptr<const preview::ReplacerNote> replacer) {
    if (!S.provenance) return nullptr;
    const bool shareable = !replacer && !p.replaced;  // a replacer's note is the path's own
    std::string key;
    if (shareable) {
      key = record_key(ip, p, piece);
      if (auto it = records_.find(key); it != records_.end()) return it->second;
    }
    auto pr = std::make_shared<preview::Provenance>();
    Chains c(rules_);
    c.add(L.trace.get());
    if (ip) c.add(ip->trace.get());
    c.add(p.trace.get());
    c.add(piece);
    // The min_layer_time slowdown, after the cascade.
    if (L.slowed && c.has(PropId::Speed) && !p.pieces.empty() && p.pieces[0].speed != static_cast<float>(c.last(PropId::Speed))) {
      ChainStep s;
      s.value = p.pieces[0].speed;
      s.source = SourceKind::Slicer;
      s.rule = "min_layer_time slowdown";
      s.text = fmt::format("the layer took less than min_layer_time = {:g} s", L.props[PropId::MinLayerTime]);
      c.add_step(PropId::Speed, s);
    }
    pr->slots = c.slots();
    if (text_)
      for (const auto& h : text_->hooks)
        if (h.path == &p) {
          preview::ExecutorNote n;
          n.after = h.after;
          n.level = h.level;
          n.text = h.text;
          ChainStep where;
          Chains(rules_).rule_source(h.rule, UINT32_MAX, where);
          n.rule = where.rule, n.file = where.file, n.line = where.line;
          pr->executors.push_back(std::move(n));
        }
    if (!replacer && p.replaced && p.trace) replacer = replacer_note(p.trace->replacer, p.ops);
    pr->replacer = std::move(replacer);
    if (shareable) records_.emplace(std::move(key), pr);
    return pr;
  }

  void travel_to(const geo::Point& to, const geo::Ring& via, bool retract) {
    if (has_pos_ && pos_ != to) {
      preview::PreviewTravel t;
      t.from = mm(S, pos_);
      t.to = mm(S, to);
      for (const auto& q : via) t.via.push_back(mm(S, q));
      t.retracted = retract;
      out_.travels.push_back(std::move(t));
    }
    has_pos_ = true;
    pos_ = to;
  }

  preview::PreviewPath base(const IslandPlan* ip, const PathPlan& p) const {
    preview::PreviewPath pp;
    pp.kind = p.kind;
    pp.island = ip ? ip->index : -1;
    pp.cell = p.cell;
    pp.perimeter = p.perimeter;
    pp.fan = p.fan;
    pp.nozzle_temp = static_cast<float>(L.props[PropId::NozzleTemp]);
    pp.width = {p.width};
    return pp;
  }

  // The path as its default output prints it.
  void path(const IslandPlan* ip, const PathPlan& p, std::shared_ptr<const preview::ReplacerNote> note) {
    if (p.replaced) {
      auto own = replacer_note(p.trace ? p.trace->replacer : UINT32_MAX, p.ops);
      ops(ip, &p, p.ops, own, [&] { default_path(ip, p, own); });
      return;
    }
    default_path(ip, p, std::move(note));
  }

  void default_path(const IslandPlan* ip, const PathPlan& p, std::shared_ptr<const preview::ReplacerNote> note) {
    if (p.pts.size() < 2) return;
    travel_to(p.pts.front(), p.via, p.retract);
    preview::PreviewPath pp = base(ip, p);
    for (const auto& q : p.pts) pp.points.push_back(mm(S, q));
    const size_t n = p.piece_count();
    bool varies = false;  // one entry for the whole path unless a piece differs
    for (size_t i = 0; i + 1 < n && !varies; ++i)
      varies = p.piece_scale(i) != p.piece_scale(i + 1) || p.piece(i).speed != p.piece(i + 1).speed ||
               p.piece(i).flow != p.piece(i + 1).flow;
    for (size_t i = 0; i < (varies ? n : 1); ++i) {
      pp.speed.push_back(p.piece(i).speed);
      pp.flow.push_back(static_cast<float>(p.piece(i).flow * p.piece_scale(i)));
    }
    if (!p.widths.empty()) {  // gap fill: each piece's width
      pp.width.clear();
      for (size_t i = 0; i < n; ++i) pp.width.push_back(p.piece_width(i));
    }
    // Decided per piece: the path shows its first piece's decisions, and each piece its own
    // only where the pieces were decided differently.
    const plan::TraceLog* first = p.piece_traces.empty() ? nullptr : p.piece_traces[0].get();
    pp.provenance = provenance(ip, p, first, note);
    bool differ = false;
    for (size_t i = 1; i < p.pieces.size() && !differ; ++i)
      differ = p.pieces[i].speed != p.pieces[0].speed || p.pieces[i].flow != p.pieces[0].flow;
    if (S.provenance && differ)
      for (size_t i = 0; i < n && i < p.piece_traces.size(); ++i)
        pp.piece_provenance.push_back(provenance(ip, p, p.piece_traces[i].get(), note));
    out_.paths.push_back(std::move(pp));
    pos_ = p.pts.back();
  }

  // A replacer's output: runs of extruding moves become paths; `default` prints the element.
  template <class Default>
  void ops(const IslandPlan* ip, const PathPlan* p, const std::vector<Op>& list,
           const std::shared_ptr<const preview::ReplacerNote>& note, Default&& emit_default) {
    preview::PreviewPath run;
    auto flush = [&] {
      if (run.points.size() >= 2) out_.paths.push_back(std::move(run));
      run = {};
    };
    for (const Op& o : list) {
      if (o.kind == Op::Kind::Default) {
        flush();
        emit_default();
      } else if (o.kind == Op::Kind::Travel) {
        flush();
        travel_to(o.to, {}, false);
      } else if (o.kind == Op::Kind::Extrude) {
        if (run.points.empty()) {
          run = p ? base(ip, *p) : preview::PreviewPath{};
          if (!p) run.kind = schema::PathKind::Custom, run.island = ip ? ip->index : -1;
          run.width.clear();
          if (has_pos_) run.points.push_back(mm(S, pos_));
          if (S.provenance) {
            auto pr = std::make_shared<preview::Provenance>();
            pr->replacer = note;
            run.provenance = pr;
          }
        }
        if (run.points.empty()) run.points.push_back(mm(S, o.to));
        run.points.push_back(mm(S, o.to));
        run.width.push_back(o.width);
        run.speed.push_back(o.speed);
        run.flow.push_back(o.flow);
        has_pos_ = true;
        pos_ = o.to;
      }
    }
    flush();
  }

  const setup::PrintSetup& S;
  const plan::LayerPlan& L;
  const gcode::LayerText* text_;
  const vm::RuleSet* rules_;
  preview::PreviewLayer out_;
  std::unordered_map<std::string, std::shared_ptr<const preview::Provenance>> records_;  // by record_key
  bool has_pos_ = false;
  geo::Point pos_;
};

}  // namespace

preview::PreviewLayer preview_layer(const setup::PrintSetup& setup, const plan::LayerPlan& plan,
                                    const gcode::LayerText* text, const vm::RuleSet* rules) {
  return LayerBuilder(setup, plan, text, rules).run();
}

}  // namespace tranche::pipeline
