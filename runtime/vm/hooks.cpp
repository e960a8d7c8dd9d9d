// The RuleSet's executors (hooks), replacers and single evaluations: each call runs the
// interpreter (machine.h) over the matching candidates.
#include <fmt/format.h>

#include <string>
#include <vector>

#include "runtime/vm/machine.h"
#include "runtime/vm/vm.h"

namespace tranche::vm {

using schema::Level;

bool RuleSet::has(Level level, ctx::When when) const {
  return !program_.hooks[static_cast<size_t>(level)][when == ctx::When::Before ? 0 : 1].empty();
}

bool RuleSet::has(Level level) const { return !program_.replace[static_cast<size_t>(level)].empty(); }

Status RuleSet::run(Level level, ctx::When when, const ctx::Context& c, ctx::LineSink& out) const {
  const Candidates& cands = program_.hooks[static_cast<size_t>(level)][when == ctx::When::Before ? 0 : 1];
  if (cands.empty()) return ok_status();
  Machine m(*this, c, &c.props());
  m.out = &out;
  // The last matching executor decides the hook; the `append` ones after it add to it.
  const Candidate* base = nullptr;
  std::vector<const Candidate*> appends;
  for (const auto& cand : cands) {
    bool ok;
    if (!m.test(cand.rule, ok)) return m.error();
    if (!ok) continue;
    if (cand.append) {
      appends.push_back(&cand);
      continue;
    }
    base = &cand;
    break;
  }
  state().text.clear();
  ctx::Trace* trace = c.trace();
  auto body = [&](const Candidate* cand) -> Status {
    double unused;
    m.rule_ = cand->rule;
    if (!trace) {
      if (!m.exec(cand->chunk, unused)) return m.error();
      return ok_status();
    }
    // Traced: the executor's lines, captured on their way to `out`.
    struct Tee final : ctx::LineSink {
      ctx::LineSink& to;
      std::string text;
      explicit Tee(ctx::LineSink& o) : to(o) {}
      void line(std::string_view l) override {
        if (!text.empty()) text.push_back('\n');
        text.append(l);
        to.line(l);
      }
    } tee(out);
    m.out = &tee;
    const bool ok = m.exec(cand->chunk, unused);
    m.out = &out;
    if (!ok) return m.error();
    trace->hook(level, when, cand->rule, tee.text);
    return ok_status();
  };
  if (base)
    if (Status s = body(base); !s) return s;
  for (auto it = appends.rbegin(); it != appends.rend(); ++it)
    if (Status s = body(*it); !s) return s;
  return ok_status();
}

Result<bool> RuleSet::replace(Level level, const ctx::Context& c, ctx::ReplaceApi& api) const {
  const Candidates& cands = program_.replace[static_cast<size_t>(level)];
  if (cands.empty()) return false;
  Machine m(*this, c, &c.props());
  m.api = &api;
  for (const auto& cand : cands) {
    bool ok;
    if (!m.test(cand.rule, ok)) return m.error();
    if (!ok) continue;
    state().text.clear();
    double unused;
    m.rule_ = cand.rule;
    if (!m.exec(cand.chunk, unused)) return m.error();
    if (ctx::Trace* t = c.trace()) t->replaced(level, cand.rule);
    return true;
  }
  return false;
}

Result<double> RuleSet::evaluate(uint32_t chunk, const ctx::Context& c, const ctx::PropertyValues& props) const {
  if (chunk >= program_.chunks.size()) return Error{"rules", "no such chunk"};
  auto kind = program_.chunks[chunk].kind;
  if (kind != ChunkKind::Test && kind != ChunkKind::Value) return Error{"rules", "only tests and values evaluate"};
  Machine m(*this, c, &props);
  double v;
  if (!m.exec(chunk, v)) return m.error();
  return v;
}

Result<int> RuleSet::first_match(const Candidates& cands, const ctx::Context& c,
                                 const ctx::PropertyValues& props) const {
  Machine m(*this, c, &props);
  for (size_t i = 0; i < cands.size(); ++i) {
    bool ok;
    if (!m.test(cands[i].rule, ok)) return m.error();
    if (ok) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace tranche::vm
