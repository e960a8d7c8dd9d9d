#include "compiler/explain.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>

#include "compiler/names.h"
#include "runtime/context/cascade.h"
#include "runtime/context/overrides.h"
#include "runtime/vm/verify.h"

namespace tranche::compiler {

namespace {

using schema::FieldId;
using schema::PropId;

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::string show(double v, schema::Type type, schema::Unit unit, schema::EnumType et) {
  switch (type) {
    case schema::Type::Bool: return v != 0 ? "true" : "false";
    case schema::Type::Enum: return std::string(schema::enum_value_name(et, static_cast<int>(v)));
    case schema::Type::Int: return fmt::format("{:g}", v);
    case schema::Type::Text: return v < 0 ? "a name no rule compares with" : fmt::format("text {:g}", v);
    case schema::Type::Number: break;
  }
  if (unit == schema::Unit::Ratio) return fmt::format("{:g}%", v * 100);
  auto u = schema::unit_name(unit);
  return u.empty() ? fmt::format("{:g}", v) : fmt::format("{:g} {}", v, u);
}

std::string show_field(FieldId f, double v) {
  const auto& i = schema::field(f);
  return show(v, i.type, i.unit, i.enum_type);
}

std::string show_prop(PropId p, double v) {
  const auto& i = schema::property(p);
  return show(v, i.type, i.unit, i.enum_type);
}

}  // namespace

Result<std::string> explain(const ast::Program& program, const vm::RuleSet& rs, const std::string& at,
                            const std::vector<std::string>& only) {
  for (const auto& name : only) {
    bool known = schema::find_property(name).has_value();
    for (const char* w : {"before ", "after ", "replace "})
      if (name.starts_with(w)) known = true;
    if (!known) return Error{"--slot", fmt::format("`{}` is not a slot: give a property (`speed`), a hook "
                                                   "(`before path`) or a replacement (`replace island`)", name)};
  }
  auto shown = [&](const std::string& slot) {
    return only.empty() || std::find(only.begin(), only.end(), slot) != only.end();
  };
  const vm::Program& p = rs.program();
  ctx::Context c;
  std::vector<std::pair<PropId, double>> given_props;
  std::set<FieldId> given;
  std::map<FieldId, std::string> texts;  // name fields as given
  std::string_view rest = at;
  while (!trim(rest).empty()) {
    size_t comma = rest.find(',');
    std::string_view item = trim(rest.substr(0, comma));
    rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
    if (item.empty()) continue;
    size_t eq = item.find('=');
    if (eq == std::string_view::npos)
      return Error{"--at", fmt::format("`{}` needs a value: write `name=value`", item)};
    std::string_view name = trim(item.substr(0, eq)), value = trim(item.substr(eq + 1));
    if (auto tf = schema::find_field(name); tf && schema::field(*tf).type == schema::Type::Text) {
      // A name (`object.name=lid`): the index of its text among the rules' texts, as when slicing.
      std::string text(value.size() >= 2 && value.front() == '"' && value.back() == '"' ? value.substr(1, value.size() - 2)
                                                                                          : value);
      c.set(*tf, rs.text_index(text));
      given.insert(*tf);
      texts[*tf] = text;
    } else if (schema::find_field(name)) {
      auto v = ctx::parse_field_value(name, value);
      if (!v) return Error{"--at", v.error().message};
      c.set(*schema::find_field(name), *v);
      given.insert(*schema::find_field(name));
    } else if (schema::find_property(name)) {
      auto o = ctx::parse_override(name, value);
      if (!o) return Error{"--at", o.error().message};
      given_props.emplace_back(o->prop, o->value);
    } else {
      std::vector<std::string> names;
      for (const auto& f : schema::fields()) names.emplace_back(f.name);
      for (const auto& q : schema::properties()) names.emplace_back(q.name);
      std::string msg = fmt::format("`{}` is neither a context field nor a property", name);
      if (auto best = suggest(std::string(name), names)) msg += fmt::format("; did you mean `{}`?", *best);
      return Error{"--at", msg};
    }
  }

  // Decide every stage as the slicer would, through the same cascade: built-in defaults, the
  // given values (where a --fill-angle-script's angle would sit), then the rules.
  auto cascade = ctx::Cascade::create({}, &rs);
  if (!cascade) return cascade.error();
  ctx::Overrides below;
  for (auto [q, v] : given_props) below.add({q, v});
  (*cascade)->set_middle(&below);
  auto props = ctx::PropertyValues::schema_defaults();
  for (int s = 0; s < schema::kStageCount; ++s)
    if (Status st = (*cascade)->decide(static_cast<schema::Stage>(s), c, props); !st) return st.error();

  std::string out;
  // The composition of the cascade: runs of consecutive rules from one file.
  out += "cascade, lowest first (later rules win):\n";
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
  out += "context:";
  if (given.empty() && given_props.empty()) out += " (nothing given)";
  for (FieldId f : given)
    out += fmt::format(" {} = {};", schema::field(f).name,
                       texts.count(f) ? fmt::format("\"{}\"", texts[f]) : show_field(f, c.get(f)));
  for (auto [q, v] : given_props) out += fmt::format(" {} = {} (below the rules);", schema::property(q).name, show_prop(q, v));
  if (out.back() == ';') out.pop_back();
  out += "\n";
  // Params: their final values, and where they were last set.
  std::map<std::string, const ast::Param*> last;
  for (const ast::Param* prm : program.params)
    if (prm->constant) last[prm->name] = prm;
  if (!last.empty()) {
    out += "params:";
    for (const auto& [name, prm] : last) {
      std::string value = prm->type.kind == ast::Kind::Bool ? (*prm->constant != 0 ? "true" : "false")
                          : prm->type.kind == ast::Kind::Number && !prm->type.unit.plain()
                              ? fmt::format("{:g} {}", *prm->constant, prm->type.unit.name())
                              : fmt::format("{:g}", *prm->constant);
      std::string from = prm->from_set ? std::string("--set")
                                       : fmt::format("{}:{}", program.sources.file(prm->span.file).path, prm->span.line);
      out += fmt::format(" {} = {} ({});", name, value, from);
    }
    out.pop_back();
    out += "\n";
  }
  std::vector<std::string> missing;
  for (const auto& f : schema::fields())
    if (rs.reads(f.id) && !given.count(f.id)) missing.emplace_back(f.name);
  if (!missing.empty()) {
    out += "not given, read as 0:";
    for (const auto& m : missing) out += " " + m;
    out += "\n";
  }

  auto rule_text = [&](uint32_t r) {
    std::string where = rs.rule_where(r);
    return where.empty() ? rs.rule_name(r) : fmt::format("{} at {}", rs.rule_name(r), where);
  };
  // Why rule r does not match: its first false conjunct and the fields it reads.
  auto why_not = [&](uint32_t r) -> Result<std::string> {
    const vm::Rule& rule = p.rules[r];
    for (uint32_t k = rule.first; k < rule.first + rule.count; ++k) {
      auto v = rs.evaluate(p.conjuncts[k].chunk, c, props);
      if (!v) return v.error();
      if (*v != 0) continue;
      std::string text = k < p.debug.conj_text.size() ? p.debug.conj_text[k] : "a condition";
      std::set<uint16_t> fields;
      const vm::Chunk& ch = p.chunks[p.conjuncts[k].chunk];
      for (uint32_t n = 0; n < ch.size; ++n) {
        const vm::Instr& in = p.code[ch.start + n];
        const vm::OpInfo& info = vm::op_info(in.code());
        if (info.b == vm::Operand::Field) fields.insert(in.b);
        if (info.c == vm::Operand::Field && in.code() != vm::Op::Layer && in.code() != vm::Op::LayerRel)
          fields.insert(in.c);
      }
      std::string values;
      for (uint16_t f : fields) {
        auto id = static_cast<FieldId>(f);
        values += fmt::format("{}{} = {}", values.empty() ? "" : ", ", schema::field(id).name,
                              texts.count(id) ? fmt::format("\"{}\"", texts[id]) : show_field(id, c.get(id)));
      }
      return fmt::format("`{}` is false{}", text, values.empty() ? "" : " (" + values + ")");
    }
    return std::string("its filter holds");  // not reached for a non-matching rule
  };
  auto slot = [&](const std::string& name, const std::string& title, const vm::Candidates& cands,
                  bool hook) -> Status {
    if (cands.empty() || !shown(name)) return ok_status();
    // The deciding candidate: the first (last written) match; for hooks, the first match that
    // is not `append` (matching `append` ones before it add to it).
    int decider = -1;
    std::vector<size_t> appended;
    for (size_t k = 0; k < cands.size() && decider < 0; ++k) {
      auto m = rs.first_match(vm::Candidates{cands[k]}, c, props);
      if (!m) return m.error();
      if (*m != 0) continue;
      if (hook && cands[k].append)
        appended.push_back(k);
      else
        decider = static_cast<int>(k);
    }
    out += "\n" + title + "\n";
    if (decider >= 0)
      out += fmt::format("  decided by {}\n", rule_text(cands[static_cast<size_t>(decider)].rule));
    else if (appended.empty())
      out += hook ? "  no rule matched: nothing is emitted\n"
                  : "  no rule matched: the value from below the rules (built-in defaults)\n";
    for (auto it = appended.rbegin(); it != appended.rend(); ++it)
      out += fmt::format("  {}appended: {}\n", decider >= 0 ? "and, " : "", rule_text(cands[*it].rule));
    size_t stop = decider < 0 ? cands.size() : static_cast<size_t>(decider);
    bool header = false;
    for (size_t k = 0; k < stop; ++k) {
      if (std::find(appended.begin(), appended.end(), k) != appended.end()) continue;
      auto w = why_not(cands[k].rule);
      if (!w) return w.error();
      if (!header) out += "  later rules that did not match:\n";
      header = true;
      out += fmt::format("    {}: {}\n", rule_text(cands[k].rule), *w);
    }
    if (decider >= 0 && static_cast<size_t>(decider) + 1 < cands.size()) {
      out += "  earlier rules that lose this slot:";
      for (size_t k = static_cast<size_t>(decider) + 1; k < cands.size(); ++k)
        out += fmt::format(" {}{}", rs.rule_name(cands[k].rule), k + 1 < cands.size() ? "," : "");
      out += "\n";
    }
    return ok_status();
  };
  for (auto q : p.property_order) {
    const auto& cands = p.props[static_cast<size_t>(q)];
    if (cands.empty()) continue;
    if (Status s = slot(std::string(schema::property(q).name),
                        fmt::format("{} = {}", schema::property(q).name, show_prop(q, props[q])), cands, false);
        !s)
      return s.error();
  }
  for (int l = 0; l < schema::kLevelCount; ++l) {
    auto level = static_cast<schema::Level>(l);
    auto name = schema::level_name(level);
    for (int w = 0; w < 2; ++w) {
      std::string hook = fmt::format("{} {}", w == 0 ? "before" : "after", name);
      if (Status s = slot(hook, hook, p.hooks[static_cast<size_t>(l)][static_cast<size_t>(w)], true); !s)
        return s.error();
    }
    std::string rep = fmt::format("replace {}", name);
    if (Status s = slot(rep, rep, p.replace[static_cast<size_t>(l)], true); !s) return s.error();
  }
  return out;
}

}  // namespace tranche::compiler
