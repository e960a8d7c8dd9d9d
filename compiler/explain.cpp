#include "compiler/explain.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>

#include "compiler/explain_at.h"
#include "runtime/context/cascade.h"
#include "runtime/context/overrides.h"
#include "runtime/vm/trace_text.h"

namespace tranche::compiler {

namespace {

using schema::FieldId;
using schema::PropId;

// What the cascade did to each property, recorded as the preview records it (ctx::Trace).
struct ChainRecorder final : ctx::Trace {
  std::map<PropId, std::vector<ctx::TraceStep>> chains;
  void step(const ctx::TraceStep& s) override { chains[s.prop].push_back(s); }
};

Status check_slots(const std::vector<std::string>& only) {
  for (const auto& name : only) {
    bool known = schema::find_property(name).has_value();
    for (const char* w : {"before ", "after ", "replace "})
      if (name.starts_with(w)) known = true;
    if (!known)
      return Error{"--slot", fmt::format("`{}` is not a slot: give a property (`speed`), a hook (`before path`) or "
                                         "a replacement (`replace island`)",
                                         name)};
  }
  return ok_status();
}

// The composition of the cascade: runs of consecutive rules from one file.
std::string cascade_text(const ast::Program& program) {
  std::string out = "cascade, lowest first (later rules win):\n";
  size_t i = 0;
  while (i < program.cascade.size()) {
    const ast::Rule* r = program.cascade[i];
    size_t j = i;
    while (j + 1 < program.cascade.size() && program.cascade[j + 1]->span.file == r->span.file &&
           program.cascade[j + 1]->from_set == r->from_set)
      ++j;
    std::string what = r->from_set ? std::string("--set")
                       : r->span.file < program.sources.size()
                           ? program.sources.file(r->span.file).path +
                                 (program.sources.file(r->span.file).user ? "" : " (stdlib)")
                           : std::string("?");
    std::string which = i == j ? fmt::format("rule {}", i) : fmt::format("rules {}-{}", i, j);
    out += fmt::format("  {:<14} {}\n", which, what);
    i = j + 1;
  }
  return out;
}

// Params: their final values, and where they were last set.
std::string params_text(const ast::Program& program) {
  std::map<std::string, const ast::Param*> last;
  for (const ast::Param* prm : program.params)
    if (prm->constant) last[prm->name] = prm;
  if (last.empty()) return {};
  std::string out = "params:";
  for (const auto& [name, prm] : last) {
    std::string value = prm->type.kind == ast::Kind::Bool ? (*prm->constant != 0 ? "true" : "false")
                        : prm->type.kind == ast::Kind::Number && !prm->type.unit.plain()
                            ? fmt::format("{:g} {}", *prm->constant, prm->type.unit.name())
                            : fmt::format("{:g}", *prm->constant);
    std::string from = prm->from_set ? std::string("--set")
                                     : fmt::format("{}:{}", program.sources.file(prm->span.file).path, prm->span.line);
    out += fmt::format(" {} = {} ({});", name, value, from);
  }
  out.back() = '\n';
  return out;
}

// The fields the rules read that the context does not give: the element's (`island.area`) and
// other layers' (`below.area`; `layers[...].z` for an index computed at run time).
std::string missing_text(const vm::RuleSet& rs, const ExplainAt& at) {
  const vm::Program& p = rs.program();
  const long current = static_cast<long>(at.context.get(FieldId::LayerIndex));
  std::set<std::string> missing;
  std::set<FieldId> own;
  for (const vm::Instr& in : p.code) {
    const vm::OpInfo& info = vm::op_info(in.code());
    if (in.code() == vm::Op::LayerRel) {
      const long i = current + static_cast<long>(in.b) - 1;
      if (!at.other.count({i, static_cast<FieldId>(in.c)})) missing.insert(at.layer_field_name(i, static_cast<FieldId>(in.c)));
    } else if (in.code() == vm::Op::Layer) {
      bool any = false;
      for (const auto& [key, v] : at.other) any = any || key.second == static_cast<FieldId>(in.c);
      if (!any) missing.insert(fmt::format("layers[...].{}", schema::field(static_cast<FieldId>(in.c)).name.substr(6)));
    } else if (info.b == vm::Operand::Field) {
      own.insert(static_cast<FieldId>(in.b));
    }
  }
  std::string out;
  for (FieldId f : own)
    if (!at.given.count(f)) out += fmt::format(" {}", schema::field(f).name);
  for (const auto& m : missing) out += " " + m;
  return out.empty() ? out : "not given, read as 0:" + out + "\n";
}

// "60 mm/s schema default -> 25 mm/s built-in default (speed = 25 mm/s when ...) -> 7.5 mm/s
// rule "small islands" (my.rules:9)".
std::string chain_text(PropId q, const std::vector<ctx::TraceStep>& steps, const vm::RuleSet& rs) {
  std::string out;
  for (const ctx::TraceStep& s : steps) {
    const vm::StepSource src = vm::step_source(s, &rs);
    std::string who;
    switch (src.source) {
      case ctx::TraceStep::Source::Start: who = "schema default"; break;
      case ctx::TraceStep::Source::BuiltinDefault: who = fmt::format("built-in default ({})", src.text); break;
      case ctx::TraceStep::Source::Middle: who = "given with --at"; break;
      case ctx::TraceStep::Source::Set: who = "--set"; break;
      case ctx::TraceStep::Source::Rule:
        who = fmt::format("rule \"{}\" ({}:{}{})", src.rule, src.file, src.line, src.read ? ", read by the rule after it" : "");
        break;
    }
    out += fmt::format("{}{} {}", out.empty() ? "" : " -> ", vm::value_text(q, s.value), who);
  }
  return out;
}

enum class SlotKind { Property, Hook, Replace };

// Explains the slots of one context: the decider, the chain, the rules that did not match and
// the rules that matched but lose the slot.
class Explainer {
 public:
  Explainer(const vm::RuleSet& rs, const ExplainAt& at, const ctx::PropertyValues& props, const ChainRecorder& chains)
      : rs_(rs), p_(rs.program()), at_(at), props_(props), chains_(chains) {}

  Status slot(const std::string& title, const vm::Candidates& cands, SlotKind kind, PropId prop, std::string& out) const;

 private:
  std::string rule_text(uint32_t r) const {
    std::string where = rs_.rule_where(r);
    return where.empty() ? rs_.rule_name(r) : fmt::format("{} at {}", rs_.rule_name(r), where);
  }
  Result<bool> matches(const vm::Candidate& c) const {
    auto m = rs_.first_match(vm::Candidates{c}, at_.context, props_);
    if (!m) return m.error();
    return *m == 0;
  }
  Result<std::string> why_not(uint32_t r) const;
  std::string read_values(const vm::Chunk& ch) const;

  const vm::RuleSet& rs_;
  const vm::Program& p_;
  const ExplainAt& at_;
  const ctx::PropertyValues& props_;
  const ChainRecorder& chains_;
};

// The values a piece of code reads: "path.kind = infill, below.area = 30 mm2".
std::string Explainer::read_values(const vm::Chunk& ch) const {
  std::set<std::pair<long, uint16_t>> fields;  // (layer offset + 1, or 0 for the element; field)
  for (uint32_t n = 0; n < ch.size; ++n) {
    const vm::Instr& in = p_.code[ch.start + n];
    if (in.code() == vm::Op::LayerRel) fields.insert({static_cast<long>(in.b) + 1, in.c});
    else if (vm::op_info(in.code()).b == vm::Operand::Field) fields.insert({0, in.b});
  }
  const long current = static_cast<long>(at_.context.get(FieldId::LayerIndex));
  std::string values;
  for (auto [rel, f] : fields) {
    const auto id = static_cast<FieldId>(f);
    const long layer = current + rel - 2;
    const std::string name = rel == 0 ? std::string(schema::field(id).name) : at_.layer_field_name(layer, id);
    const double v = rel == 0 ? at_.context.get(id) : at_.context.layer(layer, id);
    const bool text = rel == 0 && at_.texts.count(id);
    values += fmt::format("{}{} = {}", values.empty() ? "" : ", ", name,
                          text ? fmt::format("\"{}\"", at_.texts.at(id)) : field_text(id, v));
  }
  return values;
}

// Why rule r does not match: its first false conjunct and the fields it reads.
Result<std::string> Explainer::why_not(uint32_t r) const {
  const vm::Rule& rule = p_.rules[r];
  for (uint32_t k = rule.first; k < rule.first + rule.count; ++k) {
    auto v = rs_.evaluate(p_.conjuncts[k].chunk, at_.context, props_);
    if (!v) return v.error();
    if (*v != 0) continue;
    std::string text = k < p_.debug.conj_text.size() ? p_.debug.conj_text[k] : "a condition";
    const std::string values = read_values(p_.chunks[p_.conjuncts[k].chunk]);
    return fmt::format("`{}` is false{}", text, values.empty() ? "" : " (" + values + ")");
  }
  return std::string("its filter holds");  // not reached for a non-matching rule
}

Status Explainer::slot(const std::string& title, const vm::Candidates& cands, SlotKind kind, PropId prop,
                       std::string& out) const {
  // The deciding candidate: the first (last written) match; for hooks, the first match that is
  // not `append` (matching `append` ones before it add to it).
  int decider = -1;
  std::vector<size_t> appended;
  for (size_t k = 0; k < cands.size() && decider < 0; ++k) {
    auto m = matches(cands[k]);
    if (!m) return m.error();
    if (!*m) continue;
    if (kind != SlotKind::Property && cands[k].append) appended.push_back(k);
    else decider = static_cast<int>(k);
  }
  out += "\n" + title + "\n";
  if (decider >= 0)
    out += fmt::format("  decided by {}\n", rule_text(cands[static_cast<size_t>(decider)].rule));
  else if (appended.empty())
    out += kind == SlotKind::Hook      ? "  no rule matched: nothing is emitted\n"
           : kind == SlotKind::Replace ? "  no replacer matched: the default G-code is printed\n"
                                       : "  no rule matched: the value from below the rules\n";
  for (auto it = appended.rbegin(); it != appended.rend(); ++it)
    out += fmt::format("  {}appended: {}\n", decider >= 0 ? "and, " : "", rule_text(cands[*it].rule));
  if (kind == SlotKind::Property)
    if (auto c = chains_.chains.find(prop); c != chains_.chains.end())
      out += "  chain: " + chain_text(prop, c->second, rs_) + "\n";
  const size_t stop = decider < 0 ? cands.size() : static_cast<size_t>(decider);
  bool header = false;
  for (size_t k = 0; k < stop; ++k) {
    if (std::find(appended.begin(), appended.end(), k) != appended.end()) continue;
    auto w = why_not(cands[k].rule);
    if (!w) return w.error();
    if (!header) out += "  later rules that did not match:\n";
    header = true;
    out += fmt::format("    {}: {}\n", rule_text(cands[k].rule), *w);
  }
  // Earlier rules whose filter matched too: the decider overrides them.
  std::set<uint32_t> read;  // rules whose value a later one read (`speed = speed * 50%`)
  if (auto c = chains_.chains.find(prop); kind == SlotKind::Property && c != chains_.chains.end())
    for (const auto& s : c->second)
      if (s.source == ctx::TraceStep::Source::Rule && s.depth > 0) read.insert(s.rule);
  std::string losers;
  for (size_t k = stop + 1; k < cands.size(); ++k) {
    auto m = matches(cands[k]);
    if (!m) return m.error();
    if (*m)
      losers += fmt::format("{} {}{}", losers.empty() ? "" : ",", rs_.rule_name(cands[k].rule),
                            read.count(cands[k].rule) ? " (its value read by a later rule)" : "");
  }
  if (decider >= 0 && !losers.empty()) out += "  earlier rules that match but lose this slot:" + losers + "\n";
  return ok_status();
}

// Every slot of the program the caller asked for, in the order the program holds them.
Status explain_slots(const Explainer& e, const vm::Program& p, const ctx::PropertyValues& props,
                     const std::vector<std::string>& only, std::string& out) {
  auto shown = [&](const std::string& slot) {
    return only.empty() || std::find(only.begin(), only.end(), slot) != only.end();
  };
  for (auto q : p.property_order) {
    const auto& cands = p.props[static_cast<size_t>(q)];
    const std::string name(schema::property(q).name);
    if (cands.empty() || !shown(name)) continue;
    if (Status s = e.slot(fmt::format("{} = {}", name, vm::value_text(q, props[q])), cands, SlotKind::Property, q, out); !s)
      return s;
  }
  for (int l = 0; l < schema::kLevelCount; ++l) {
    const auto name = schema::level_name(static_cast<schema::Level>(l));
    for (int w = 0; w < 2; ++w) {
      const std::string hook = fmt::format("{} {}", w == 0 ? "before" : "after", name);
      const auto& cands = p.hooks[static_cast<size_t>(l)][static_cast<size_t>(w)];
      if (!cands.empty() && shown(hook))
        if (Status s = e.slot(hook, cands, SlotKind::Hook, PropId::Speed, out); !s) return s;
    }
    const std::string rep = fmt::format("replace {}", name);
    const auto& cands = p.replace[static_cast<size_t>(l)];
    if (!cands.empty() && shown(rep))
      if (Status s = e.slot(rep, cands, SlotKind::Replace, PropId::Speed, out); !s) return s;
  }
  return ok_status();
}

}  // namespace

Result<std::string> explain(const ast::Program& program, const vm::RuleSet& rs, const std::string& at_text,
                            const std::vector<std::string>& only) {
  if (Status s = check_slots(only); !s) return s.error();
  ExplainAt at;
  if (Status s = parse_explain_at(at_text, at); !s) return s.error();
  resolve_texts(at, rs);
  // Decide every stage as the slicer would, through the same cascade, recording the chains:
  // built-in defaults, the given values (where a --fill-angle-script's angle would sit), the rules.
  auto cascade = ctx::Cascade::create({}, &rs);
  if (!cascade) return cascade.error();
  ctx::Overrides below;
  below.recorded_as = ctx::TraceStep::Source::Middle;
  for (auto [q, v] : at.props) below.add({q, v});
  (*cascade)->set_middle(&below);
  ChainRecorder chains;
  at.context.set_trace(&chains);
  auto props = ctx::PropertyValues::schema_defaults();
  for (int s = 0; s < schema::kStageCount; ++s)
    if (Status st = (*cascade)->decide(static_cast<schema::Stage>(s), at.context, props); !st) return st.error();
  at.context.set_trace(nullptr);  // testing filters below records nothing

  std::string out = cascade_text(program);
  out += "context: " + at.text() + "\n";
  out += params_text(program);
  out += missing_text(rs, at);
  if (Status s = explain_slots(Explainer(rs, at, props, chains), rs.program(), props, only, out); !s) return s.error();
  return out;
}

}  // namespace tranche::compiler
