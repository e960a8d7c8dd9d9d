#include "runtime/vm/link.h"

#include <fmt/format.h>

#include <functional>
#include <map>

#include "runtime/vm/verify.h"

namespace tranche::vm {

namespace {

// Moves an instruction's operands to the linked program: constants and rules by the counts
// before it, strings through `strings` (each text once in the linked program).
void remap(Instr& in, uint32_t consts, const std::vector<uint16_t>& strings, uint32_t rules) {
  const OpInfo& info = op_info(in.code());
  auto fix = [&](Operand k, auto& v) {
    using V = std::remove_reference_t<decltype(v)>;
    if (k == Operand::Const) v = static_cast<V>(v + consts);
    else if (k == Operand::String && v < strings.size()) v = static_cast<V>(strings[v]);
    else if (k == Operand::Rule) v = static_cast<V>(v + rules);
  };
  fix(info.b, in.b);
  fix(info.c, in.c);
  fix(info.d, in.d);
}

}  // namespace

Result<std::vector<schema::PropId>> property_order(const Program& p) {
  const int n = schema::kPropCount;
  // Edges: property -> same-stage properties its candidates read (those come first).
  std::vector<std::vector<int>> reads(static_cast<size_t>(n));
  auto scan = [&](int q, uint32_t chunk) {
    const Chunk& ch = p.chunks[chunk];
    auto stage = schema::properties()[static_cast<size_t>(q)].stage;
    for (uint32_t i = 0; i < ch.size; ++i) {
      const Instr& in = p.code[ch.start + i];
      if (in.code() != Op::Prop || in.b == q) continue;
      if (schema::properties()[in.b].stage == stage) reads[static_cast<size_t>(q)].push_back(in.b);
    }
  };
  for (int q = 0; q < n; ++q)
    for (const auto& c : p.props[static_cast<size_t>(q)]) {
      scan(q, c.chunk);
      const Rule& r = p.rules[c.rule];
      for (uint32_t k = r.first; k < r.first + r.count; ++k) scan(q, p.conjuncts[k].chunk);
    }
  std::vector<int> by_stage(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) by_stage[static_cast<size_t>(i)] = i;
  std::stable_sort(by_stage.begin(), by_stage.end(), [](int a, int b) {
    return schema::properties()[static_cast<size_t>(a)].stage < schema::properties()[static_cast<size_t>(b)].stage;
  });
  std::vector<int> state(static_cast<size_t>(n), 0);
  std::vector<schema::PropId> order;
  std::string cycle;
  std::function<bool(int)> visit = [&](int q) {
    state[static_cast<size_t>(q)] = 1;
    for (int d : reads[static_cast<size_t>(q)]) {
      if (state[static_cast<size_t>(d)] == 1) {
        cycle = fmt::format("`{}` and `{}`", schema::properties()[static_cast<size_t>(q)].name,
                            schema::properties()[static_cast<size_t>(d)].name);
        return false;
      }
      if (state[static_cast<size_t>(d)] == 0 && !visit(d)) return false;
    }
    state[static_cast<size_t>(q)] = 2;
    order.push_back(static_cast<schema::PropId>(q));
    return true;
  };
  for (int q : by_stage)
    if (state[static_cast<size_t>(q)] == 0 && !visit(q))
      return Error{"rules", fmt::format("{} read each other (in different files): one of them must be decided "
                                        "first; read the property in one direction only",
                                        cycle)};
  return order;
}

namespace {

// The debug information of program `p` appended to `d`: its own, or placeholders that name it.
void append_debug(Debug& d, const Program& p, const std::string& name) {
  const auto files = static_cast<uint32_t>(d.files.size());
  const auto locs = static_cast<uint32_t>(d.locs.size());
  if (!p.debug.empty()) {
    d.files.insert(d.files.end(), p.debug.files.begin(), p.debug.files.end());
    for (Loc l : p.debug.locs) {
      l.file += files;
      d.locs.push_back(l);
    }
    for (uint32_t l : p.debug.instr_loc) d.instr_loc.push_back(l + locs);
    d.rule_names.insert(d.rule_names.end(), p.debug.rule_names.begin(), p.debug.rule_names.end());
    for (uint32_t l : p.debug.rule_loc) d.rule_loc.push_back(l + locs);
    d.conj_text.insert(d.conj_text.end(), p.debug.conj_text.begin(), p.debug.conj_text.end());
    for (uint32_t l : p.debug.conj_loc) d.conj_loc.push_back(l + locs);
  } else {
    d.files.push_back(name);
    d.locs.push_back({files, 0, 0});
    d.instr_loc.insert(d.instr_loc.end(), p.code.size(), locs);
    for (size_t r = 0; r < p.rules.size(); ++r) {
      d.rule_names.push_back(fmt::format("{} of {}", r, name));
      d.rule_loc.push_back(locs);
    }
    d.conj_text.insert(d.conj_text.end(), p.conjuncts.size(), std::string("?"));
    d.conj_loc.insert(d.conj_loc.end(), p.conjuncts.size(), locs);
  }
}

}  // namespace

Result<Program> link(std::vector<Program> programs, const std::vector<std::string>& names) {
  if (programs.size() == 1) return std::move(programs[0]);
  Program out;
  out.debug.files.clear();
  std::map<std::string, uint16_t, std::less<>> texts;  // each text once: a name's index is its text's
  for (size_t i = 0; i < programs.size(); ++i) {
    Program& p = programs[i];
    const std::string name = i < names.size() ? names[i] : fmt::format("rule set {}", i + 1);
    const auto consts = static_cast<uint32_t>(out.consts.size());
    const auto rules = static_cast<uint32_t>(out.rules.size());
    const auto chunks = static_cast<uint32_t>(out.chunks.size());
    const auto conjuncts = static_cast<uint32_t>(out.conjuncts.size());
    const auto code = static_cast<uint32_t>(out.code.size());
    if (consts + p.consts.size() > kMaxConsts) return Error{name, "the rule sets together have more than 65536 constants"};
    if (rules + p.rules.size() > kMaxRules) return Error{name, "the rule sets together have more than 65535 rules"};
    out.consts.insert(out.consts.end(), p.consts.begin(), p.consts.end());
    std::vector<uint16_t> strings(p.strings.size());
    for (size_t k = 0; k < p.strings.size(); ++k) {
      auto [it, fresh] = texts.try_emplace(p.strings[k], static_cast<uint16_t>(out.strings.size()));
      if (fresh) {
        if (out.strings.size() >= kMaxStrings) return Error{name, "the rule sets together have more than 65536 texts"};
        out.strings.push_back(p.strings[k]);
      }
      strings[k] = it->second;
    }
    for (Instr in : p.code) {
      remap(in, consts, strings, rules);
      out.code.push_back(in);
    }
    for (Chunk c : p.chunks) {
      c.start += code;
      out.chunks.push_back(c);
    }
    for (Conjunct c : p.conjuncts) {
      c.chunk += chunks;
      out.conjuncts.push_back(c);
    }
    for (Rule r : p.rules) {
      r.first += conjuncts;
      out.rules.push_back(r);
    }
    // Later programs' candidates go first: their rules come later in the cascade.
    auto merge = [&](Candidates& into, const Candidates& from) {
      Candidates c;
      for (Candidate x : from) {
        x.rule += rules;
        x.chunk += chunks;
        c.push_back(x);
      }
      c.insert(c.end(), into.begin(), into.end());
      into = std::move(c);
    };
    for (size_t q = 0; q < out.props.size(); ++q) merge(out.props[q], p.props[q]);
    for (size_t l = 0; l < out.hooks.size(); ++l)
      for (size_t w = 0; w < 2; ++w) merge(out.hooks[l][w], p.hooks[l][w]);
    for (size_t l = 0; l < out.replace.size(); ++l) merge(out.replace[l], p.replace[l]);

    append_debug(out.debug, p, name);
  }
  auto order = property_order(out);
  if (!order) return order.error();
  out.property_order = std::move(*order);
  if (Status s = verify(out); !s) return s.error();
  return out;
}

}  // namespace tranche::vm
