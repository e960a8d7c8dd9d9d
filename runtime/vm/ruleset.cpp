// The RuleSet as a program is loaded: created from a verified program, analysed once (what each
// chunk reads, conjuncts the VM tests without the interpreter, constant values, hoisting), and
// its values checked and rules named for messages.
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <optional>
#include <string>

#include "runtime/vm/machine.h"
#include "runtime/vm/opcodes.h"
#include "runtime/vm/verify.h"
#include "runtime/vm/vm.h"

namespace tranche::vm {

using schema::Level;
using schema::Stage;

namespace {
std::atomic<uint32_t> next_uid{1};
}

Counters& thread_counters() { return state().counters; }

RuleSet::RuleSet(Program p) : program_(std::move(p)), uid_(next_uid.fetch_add(1)) {}

Result<std::shared_ptr<const RuleSet>> RuleSet::create(Program program) {
  if (Status s = verify(program); !s) return s.error();
  std::shared_ptr<RuleSet> rs(new RuleSet(std::move(program)));
  rs->analyse();
  return std::shared_ptr<const RuleSet>(std::move(rs));
}

void RuleSet::analyse() {
  const ChunkFacts facts = analyse_chunks();
  analyse_simple();
  analyse_constants();
  analyse_splits(facts);
  analyse_dependence(facts);
}

// Per chunk: the innermost level it reads and whether it reads only fields; every field read.
RuleSet::ChunkFacts RuleSet::analyse_chunks() {
  const Program& p = program_;
  ChunkFacts facts;
  facts.level.assign(p.chunks.size(), Level::Print);
  facts.pure.assign(p.chunks.size(), 1);
  facts.own.assign(p.chunks.size(), Level::Print);
  facts.stages.assign(p.chunks.size(), 0);
  facts.fields.assign(p.chunks.size(), {});
  for (size_t c = 0; c < p.chunks.size(); ++c) {
    const Chunk& ch = p.chunks[c];
    Level lv = Level::Print, own = Level::Print;
    for (uint32_t i = 0; i < ch.size; ++i) {
      const Instr& in = p.code[ch.start + i];
      const OpInfo& info = op_info(in.code());
      auto field = [&](uint16_t f) {
        reads_[f] = true;
        facts.fields[c].set(f);
        own = std::max(own, schema::fields()[f].level);
      };
      if (info.b == Operand::Field) field(in.b);
      if (info.c == Operand::Field) field(in.c);
      switch (in.code()) {
        case Op::Prop:
        case Op::Inherit: {
          facts.pure[c] = 0;
          const Stage st = schema::property(static_cast<schema::PropId>(in.b)).stage;
          facts.stages[c] |= 1u << static_cast<unsigned>(st);
          lv = std::max(lv, schema::stage_level(st));
          break;
        }
        case Op::Layer:
        case Op::LayerRel:
          own = std::max(own, Level::Layer);
          break;
        case Op::Count:
        case Op::Elem: {
          facts.pure[c] = 0;
          auto coll = static_cast<Coll>(in.code() == Op::Count ? in.b : in.c);
          own = std::max(own, coll == Coll::Islands ? Level::Layer : Level::Path);
          if (in.code() == Op::Elem && coll != Coll::Points) {
            reads_[in.d] = true;
            facts.fields[c].set(in.d);
          }
          break;
        }
        default:
          break;
      }
    }
    facts.own[c] = own;
    facts.level[c] = std::max(lv, own);
  }
  return facts;
}

// Conjuncts of the form `field CMP constant`: [j(n)CMP.fk field, K, ->2; retk 1; retk 0].
void RuleSet::analyse_simple() {
  const Program& p = program_;
  simple_.assign(p.conjuncts.size(), Simple{});
  for (size_t k = 0; k < p.conjuncts.size(); ++k) {
    const Chunk& ch = p.chunks[p.conjuncts[k].chunk];
    if (ch.size != 3) continue;
    const Instr* c = &p.code[ch.start];
    if (c[1].code() != Op::RetK || c[2].code() != Op::RetK || p.consts[c[1].b] != 1 || p.consts[c[2].b] != 0)
      continue;
    static constexpr Op kFused[6][2] = {{Op::JnEqFK, Op::JEqFK}, {Op::JnNeFK, Op::JNeFK}, {Op::JnLtFK, Op::JLtFK},
                                        {Op::JnLeFK, Op::JLeFK}, {Op::JnGtFK, Op::JGtFK}, {Op::JnGeFK, Op::JGeFK}};
    for (uint8_t cmp = 0; cmp < 6; ++cmp)
      for (int when = 0; when < 2; ++when)
        if (c[0].code() == kFused[cmp][when] && c[0].d == 2)
          // jn: jump to "false" when the comparison fails, so the result is the comparison;
          // j: jump to "false" when it holds, so the result is its negation.
          simple_[k] = Simple{true, when == 1, cmp, c[0].b, p.consts[c[0].c]};
  }
}

// Value chunks that are one constant, and every property's plain range.
void RuleSet::analyse_constants() {
  const Program& p = program_;
  is_const_.assign(p.chunks.size(), 0);
  const_value_.assign(p.chunks.size(), 0);
  for (size_t c = 0; c < p.chunks.size(); ++c) {
    const Chunk& ch = p.chunks[c];
    if (ch.kind == ChunkKind::Value && ch.size == 1 && p.code[ch.start].code() == Op::RetK) {
      is_const_[c] = 1;
      const_value_[c] = p.consts[p.code[ch.start].b];
    }
  }
  for (const auto& info : schema::properties()) {
    Range& r = ranges_[static_cast<size_t>(info.id)];
    r.plain = info.type == schema::Type::Number && !info.wraps();
    r.min = info.min;
    r.max = info.max;
  }
}

// Per property: the level it is decided at, each candidate's conjuncts split into those read
// before that level (outer, hoisted) and the others, the stages' properties with candidates, and
// the level each stage's decisions vary at.
void RuleSet::analyse_splits(const ChunkFacts& facts) {
  const Program& p = program_;
  const auto& chunk_level = facts.level;
  const auto& pure = facts.pure;
  auto rule_level = [&](uint32_t r) {
    Level lv = Level::Print;
    for (uint32_t k = p.rules[r].first; k < p.rules[r].first + p.rules[r].count; ++k)
      lv = std::max(lv, std::max(p.conjuncts[k].level, chunk_level[p.conjuncts[k].chunk]));
    return lv;
  };
  varies_.fill(Level::Print);
  for (auto q : p.property_order) {
    const auto& cands = p.props[static_cast<size_t>(q)];
    auto st = schema::property(q).stage;
    Level decided = st == Stage::Piece ? Level::Piece : schema::stage_level(st);
    decided_at_[static_cast<size_t>(q)] = decided;
    // Each candidate's conjuncts, those read before the decision's level first.
    for (const auto& c : cands) {
      Split sp;
      sp.first = static_cast<uint32_t>(split_list_.size());
      const Rule& rule = p.rules[c.rule];
      for (int pass = 0; pass < 2; ++pass)
        for (uint32_t k = rule.first; k < rule.first + rule.count; ++k) {
          bool outer = pure[p.conjuncts[k].chunk] && p.conjuncts[k].level < decided &&
                       chunk_level[p.conjuncts[k].chunk] < decided;
          if (outer != (pass == 0)) continue;
          split_list_.push_back(k);
          (outer ? sp.outer : sp.inner) += 1;
        }
      split_[static_cast<size_t>(q)].push_back(sp);
    }
    auto& levels = cand_level_[static_cast<size_t>(q)];
    levels.clear();
    for (const auto& c : cands) levels.push_back(std::max(rule_level(c.rule), chunk_level[c.chunk]));
    if (cands.empty()) continue;
    stage_props_[static_cast<size_t>(st)].push_back(q);
    const Stage finest = schema::finest_stage(q);
    for (Level lv : levels) {
      const bool finer = finest != st && lv > decided;
      Level& v = varies_[static_cast<size_t>(finer ? finest : st)];
      v = std::max(v, lv);
    }
    if (finest != st && std::any_of(levels.begin(), levels.end(), [&](Level lv) { return lv > decided; }))
      stage_props_[static_cast<size_t>(finest)].push_back(q);
  }
}

// For depends() and reads_beyond(): per property and candidate, the deepest level its rule and
// value read and the fields they read, where reading a property of the stage being decided does
// not count (it is resolved from that stage's other candidates, which depends() covers too);
// per stage, the fields read by any code other than the candidates of that stage's properties.
void RuleSet::analyse_dependence(const ChunkFacts& facts) {
  const Program& p = program_;
  for (auto q : p.property_order) {
    const auto qi = static_cast<size_t>(q);
    const Stage st = schema::property(q).stage;
    auto& own = dep_level_[qi];
    auto& fields = dep_fields_[qi];
    own.clear();
    fields.clear();
    for (const auto& c : p.props[qi]) {
      Level lv = Level::Print;
      FieldSet fs;
      auto add = [&](uint32_t chunk) {
        lv = std::max(lv, facts.own[chunk]);
        fs |= facts.fields[chunk];
        for (int s = 0; s < schema::kStageCount; ++s)
          if (s != static_cast<int>(st) && (facts.stages[chunk] >> s & 1u))
            lv = std::max(lv, schema::stage_level(static_cast<Stage>(s)));
      };
      const Rule& rule = p.rules[c.rule];
      for (uint32_t k = rule.first; k < rule.first + rule.count; ++k) add(p.conjuncts[k].chunk);
      add(c.chunk);
      for (const auto& f : schema::fields())  // only those of the decision's level and deeper
        if (f.level < schema::stage_level(st)) fs.reset(static_cast<size_t>(f.id));
      own.push_back(lv);
      fields.push_back(fs);
    }
  }
  // Chunks used by anything but the candidates of stage s's properties read "beyond" s.
  for (int s = 0; s < schema::kStageCount; ++s) {
    FieldSet& beyond = beyond_[static_cast<size_t>(s)];
    beyond.reset();
    auto chunk = [&](uint32_t c) { beyond |= facts.fields[c]; };
    auto rule = [&](uint32_t r) {
      for (uint32_t k = p.rules[r].first; k < p.rules[r].first + p.rules[r].count; ++k) chunk(p.conjuncts[k].chunk);
    };
    for (size_t qi = 0; qi < p.props.size(); ++qi) {
      if (static_cast<int>(schema::property(static_cast<schema::PropId>(qi)).stage) == s) continue;
      for (const auto& c : p.props[qi]) {
        rule(c.rule);
        chunk(c.chunk);
      }
    }
    for (const auto& level : p.hooks)
      for (const auto& when : level)
        for (const auto& c : when) {
          rule(c.rule);
          chunk(c.chunk);
        }
    for (const auto& level : p.replace)
      for (const auto& c : level) {
        rule(c.rule);
        chunk(c.chunk);
      }
  }
}

Result<double> RuleSet::check_value(schema::PropId q, double v) {
  const auto& info = schema::property(q);
  if (!std::isfinite(v)) return Error{"", fmt::format("`{}` was given a value that is not a number", info.name)};
  switch (info.type) {
    case schema::Type::Bool:
      return v != 0 ? 1.0 : 0.0;
    case schema::Type::Enum:
      if (v < 0 || v >= static_cast<double>(schema::enum_info(info.enum_type).values.size()) || v != std::floor(v))
        return Error{"", fmt::format("`{}` was given {}, which is not one of its values", info.name, v)};
      return v;
    default:
      break;
  }
  if (info.wraps()) {
    v = std::fmod(v, 360.0);
    if (v < 0) v += 360.0;
    return v;
  }
  if (v < info.min || v > info.max) {
    auto show = [&](double x) {
      if (info.unit == schema::Unit::Ratio) return fmt::format("{:g}%", x * 100);
      auto u = schema::unit_name(info.unit);
      return u.empty() ? fmt::format("{:g}", x) : fmt::format("{:g} {}", x, u);
    };
    return Error{"", fmt::format("`{}` was given {}, outside its physical range {} to {}", info.name, show(v),
                                 show(info.min), show(info.max))};
  }
  if (info.type == schema::Type::Int) v = std::round(v);
  return v;
}

std::string RuleSet::rule_name(uint32_t r) const {
  if (r < program_.debug.rule_names.size()) {
    const std::string& n = program_.debug.rule_names[r];
    if (n.empty()) return fmt::format("rule {}", r);
    return n.starts_with('"') || std::isdigit(static_cast<unsigned char>(n[0])) ? "rule " + n : n;
  }
  return fmt::format("rule {}", r);
}

int RuleSet::text_index(std::string_view name) const {
  const auto& s = program_.strings;
  for (size_t i = 0; i < s.size(); ++i)
    if (s[i] == name) return static_cast<int>(i);  // the verifier makes each text unique
  return -1;
}

std::vector<std::pair<std::string, std::string>> RuleSet::compared_texts() const {
  const Debug& d = program_.debug;
  std::vector<std::optional<std::string>> where(program_.strings.size());
  for (size_t pc = 0; pc < program_.code.size(); ++pc) {
    const Instr& in = program_.code[pc];
    if (in.code() != Op::LoadS || in.b >= where.size() || where[in.b]) continue;
    std::string at;
    if (pc < d.instr_loc.size() && d.instr_loc[pc] < d.locs.size()) {
      const Loc& l = d.locs[d.instr_loc[pc]];
      if (l.file < d.files.size()) at = l.line ? fmt::format("{}:{}:{}", d.files[l.file], l.line, l.col) : d.files[l.file];
    }
    where[in.b] = std::move(at);
  }
  std::vector<std::pair<std::string, std::string>> out;
  for (size_t i = 0; i < where.size(); ++i)
    if (where[i]) out.emplace_back(program_.strings[i], std::move(*where[i]));
  return out;
}

std::string RuleSet::rule_where(uint32_t r) const {
  const Debug& d = program_.debug;
  if (r >= d.rule_loc.size()) return {};
  const Loc& l = d.locs[d.rule_loc[r]];
  if (l.line == 0) return d.files[l.file];
  return fmt::format("{}:{}:{}", d.files[l.file], l.line, l.col);
}

std::string RuleSet::rule_label(uint32_t r) const {
  if (r < program_.debug.rule_names.size() && !program_.debug.rule_names[r].empty()) {
    std::string n = program_.debug.rule_names[r];
    if (n.size() >= 2 && n.front() == '"' && n.back() == '"') n = n.substr(1, n.size() - 2);
    return n;
  }
  return fmt::format("rule {}", r);
}

std::pair<std::string, uint32_t> RuleSet::chunk_source(uint32_t chunk) const {
  const Debug& d = program_.debug;
  if (chunk >= program_.chunks.size()) return {};
  const uint32_t instr = program_.chunks[chunk].start;
  if (instr >= d.instr_loc.size() || d.instr_loc[instr] >= d.locs.size()) return {};
  const Loc& l = d.locs[d.instr_loc[instr]];
  return {l.file < d.files.size() ? d.files[l.file] : std::string(), l.line};
}

}  // namespace tranche::vm
