#include "runtime/vm/vm.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <string>

#include "runtime/vm/machine.h"
#include "runtime/vm/verify.h"

namespace tranche::vm {

using schema::Level;
using schema::Stage;

ThreadState& state() {
  thread_local ThreadState s;
  return s;
}

namespace {

std::string format_number(double v, uint16_t decimals) {
  if (decimals != kDefaultDecimals) {
    std::string s = fmt::format("{:.{}f}", v, decimals);
    if (s.starts_with('-') && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
    return s;
  }
  std::string s = fmt::format("{:.3f}", v);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

double round_half_away(double v) { return std::round(v); }

}  // namespace

size_t Machine::count(Coll c) const {
  switch (c) {
    case Coll::Points: return ctx_.points().size();
    case Coll::Pieces: return ctx_.pieces().size();
    case Coll::Islands: return ctx_.islands().size();
  }
  return 0;
}

double Machine::elem(Coll c, size_t i, uint16_t m) const {
  switch (c) {
    case Coll::Points: {
      auto pts = ctx_.points();
      if (i >= pts.size()) return 0;
      return m == kPointX ? pts[i].x : m == kPointY ? pts[i].y : static_cast<double>(i);
    }
    case Coll::Pieces: return ctx_.pieces().get(i, static_cast<schema::FieldId>(m));
    case Coll::Islands: return ctx_.islands().get(i, static_cast<schema::FieldId>(m));
  }
  return 0;
}

bool Machine::emit(bool comment, uint32_t ci, uint32_t pc) {
  std::string& t = st_.text;
  size_t start = 0;
  while (start <= t.size()) {
    size_t nl = t.find('\n', start);
    if (nl == std::string::npos) nl = t.size();
    std::string_view line(t.data() + start, nl - start);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
    size_t lead = line.find_first_not_of(" \t");
    if (lead != std::string_view::npos) {
      line.remove_prefix(lead);
      emitted_ += line.size() + 3;
      if (emitted_ > kMaxOutputBytes) return fault(Fault::OutputTooLong, ci, pc);
      if (comment) {
        std::string c = "; ";
        c += line;
        if (api) api->comment(line);
        else if (out) out->line(c);
      } else {
        if (api) api->gcode(line);
        else if (out) out->line(line);
      }
    }
    start = nl + 1;
  }
  t.clear();
  return true;
}

inline bool Machine::conj(uint32_t k, uint32_t r, bool& ok) {
  ++run_;
  const RuleSet::Simple& t = rs_.simple_[k];
  if (t.on) {
    double v = ctx_.values()[t.field];
    bool hit;
    switch (t.cmp) {
      case 0: hit = v == t.k; break;
      case 1: hit = v != t.k; break;
      case 2: hit = v < t.k; break;
      case 3: hit = v <= t.k; break;
      case 4: hit = v > t.k; break;
      default: hit = v >= t.k; break;
    }
    ok = hit != t.negate;
    return true;
  }
  uint32_t saved = rule_;
  rule_ = r;
  double v;
  if (!exec(p_.conjuncts[k].chunk, v)) return false;
  rule_ = saved;
  ok = v != 0;
  return true;
}

bool Machine::test(uint32_t r, bool& result) {
  const Rule& rule = p_.rules[r];
  for (uint32_t k = rule.first; k < rule.first + rule.count; ++k) {
    if (!conj(k, r, result)) return false;
    if (!result) return true;
  }
  return result = true, true;
}

bool Machine::live_list(schema::PropId q, const ThreadState::Live*& found) {
  const auto qi = static_cast<size_t>(q);
  const Level outer = rs_.decided_at_[qi];
  const uint64_t key = outer > Level::Print ? ctx_.generation(static_cast<Level>(static_cast<int>(outer) - 1)) : 0;
  found = nullptr;
  if (key == 0) return true;
  ThreadState::Live& live = st_.live[qi];
  if (live.key != key || live.owner != rs_.uid_) {
    const Candidates& cands = p_.props[qi];
    const auto& split = rs_.split_[qi];
    const uint32_t* list = rs_.split_list_.data();
    ++rebuilds_;
    live.entries.clear();
    live.key = 0;  // not valid until built whole
    for (uint32_t i = 0; i < cands.size(); ++i) {
      bool ok = true;
      for (uint32_t j = 0; j < split[i].outer && ok; ++j)
        if (!conj(list[split[i].first + j], cands[i].rule, ok)) return false;
      if (ok) live.entries.push_back({i, split[i].first + split[i].outer, split[i].inner});
    }
    live.key = key;
    live.owner = rs_.uid_;
  }
  found = &live;
  return true;
}

bool Machine::winner(schema::PropId q, uint32_t below, int& index) {
  const auto qi = static_cast<size_t>(q);
  const Candidates& cands = p_.props[qi];
  const auto& split = rs_.split_[qi];
  const uint32_t* list = rs_.split_list_.data();
  size_t start = 0;
  if (below != UINT32_MAX)  // descending rule order: the first candidate below rule `below`
    start = static_cast<size_t>(std::lower_bound(cands.begin(), cands.end(), below,
                                                 [](const Candidate& c, uint32_t rule) { return c.rule >= rule; }) -
                                cands.begin());
  auto all = [&](const uint32_t* ks, uint32_t n, uint32_t r, bool& ok) {
    ok = true;
    for (uint32_t j = 0; j < n && ok; ++j)
      if (!conj(ks[j], r, ok)) return false;
    return true;
  };
  const ThreadState::Live* live;
  if (!live_list(q, live)) return false;
  if (live) {
    const auto& levels = rs_.cand_level_[qi];
    for (const auto& e : live->entries) {
      if (e.candidate < start || levels[e.candidate] > limit_) continue;
      bool ok = true;
      for (uint32_t j = 0; j < e.count && ok; ++j)
        if (!conj(list[e.first + j], cands[e.candidate].rule, ok)) return false;
      if (ok) return index = static_cast<int>(e.candidate), true;
    }
    return index = -1, true;
  }
  for (size_t i = start; i < cands.size(); ++i) {
    if (rs_.cand_level_[qi][i] > limit_) continue;
    bool ok;
    if (!all(list + split[i].first, split[i].outer + split[i].inner, cands[i].rule, ok)) return false;
    if (ok) return index = static_cast<int>(i), true;
  }
  return index = -1, true;
}

bool Machine::value(schema::PropId q, int i, double& result) {
  const Candidate& c = p_.props[static_cast<size_t>(q)][static_cast<size_t>(i)];
  if (rs_.is_const_[c.chunk]) return result = rs_.const_value_[c.chunk], true;
  uint32_t saved = rule_;
  rule_ = c.rule;
  if (!exec(c.chunk, result)) return false;
  rule_ = saved;
  return true;
}

bool Machine::resolve(schema::PropId q, uint32_t below, double& result) {
  int i;
  if (!winner(q, below, i)) return false;
  if (i < 0) return result = props_->base[static_cast<size_t>(q)], true;
  ++depth_read_;
  const bool ok = value(q, i, result);
  --depth_read_;
  if (ok)
    if (ctx::Trace* t = ctx_.trace()) {
      const Candidate& c = p_.props[static_cast<size_t>(q)][static_cast<size_t>(i)];
      t->step({q, ctx::TraceStep::Source::Rule, c.rule, c.chunk, result, static_cast<uint16_t>(depth_read_ + 1)});
    }
  return ok;
}

#if defined(__GNUC__)
// Dispatch through a table of label addresses (a GNU extension that both GCC and Clang have):
// one indirect jump per instruction, predicted per opcode.
#define TRANCHE_COMPUTED_GOTO 1
#pragma GCC diagnostic ignored "-Wpedantic"
#endif

bool Machine::exec(uint32_t ci, double& result) {
  const Chunk& ch = p_.chunks[ci];
  if (st_.top + ch.regs > kStackRegs || depth_ >= kMaxInheritDepth) return fault(Fault::Depth, ci, 0);
  double* r = st_.regs.get() + st_.top;
  st_.top += ch.regs;
  ++depth_;
  struct Pop {
    ThreadState& s;
    size_t n;
    int& depth;
    ~Pop() {
      s.top -= n;
      --depth;
    }
  } pop{st_, ch.regs, depth_};

  const Instr* code = p_.code.data() + ch.start;
  const double* K = p_.consts.data();
  const double* F = ctx_.values().data();
  const Instr* ip = code;
  const Instr* in;
  auto jump = [&](uint16_t target) {
    if (code + target <= in && ++steps_ > kMaxLoopSteps) return false;
    ip = code + target;
    return true;
  };
  auto pc = [&] { return static_cast<uint32_t>(in - code); };

#define A (in->a)
#define B (in->b)
#define C (in->c)
#define D (in->d)
#define JUMP(t)                                          \
  do {                                                   \
    if (!jump(t)) return fault(Fault::Steps, ci, pc());  \
  } while (0)

#ifdef TRANCHE_COMPUTED_GOTO
  static const void* labels[] = {
#define TRANCHE_OP(Name, mnemonic, a, b, c, d, Class) &&op_##Name,
#include "runtime/vm/opcodes.def"
#undef TRANCHE_OP
  };
#define CASE(Name) op_##Name:
#define NEXT                   \
  do {                         \
    in = ip++;                 \
    goto* labels[in->op];      \
  } while (0)
  NEXT;
#else
#define CASE(Name) case Op::Name:
#define NEXT break
  for (;;) {
    in = ip++;
    switch (in->code()) {
#endif

  CASE(LoadK) r[A] = K[B]; NEXT;
  CASE(LoadS) r[A] = B; NEXT;
  CASE(Field) r[A] = F[B]; NEXT;
  CASE(Prop) r[A] = props_->values[B]; NEXT;
  CASE(Inherit) {
    double v;
    if (!resolve(static_cast<schema::PropId>(B), C, v)) return false;
    r[A] = v;
    NEXT;
  }
  CASE(Layer) {
    double i = r[B];
    r[A] = std::isfinite(i) ? ctx_.layer(static_cast<long>(std::llround(std::clamp(i, -1e9, 1e9))),
                                         static_cast<schema::FieldId>(C))
                            : 0.0;
    NEXT;
  }
  CASE(LayerRel) {
    long idx = static_cast<long>(F[static_cast<size_t>(schema::FieldId::LayerIndex)]) + static_cast<long>(B) - 1;
    r[A] = ctx_.layer(idx, static_cast<schema::FieldId>(C));
    NEXT;
  }
  CASE(Move) r[A] = r[B]; NEXT;
  CASE(Count) r[A] = static_cast<double>(count(static_cast<Coll>(B))); NEXT;
  CASE(Elem) {
    double i = r[B];
    r[A] = i >= 0 && std::isfinite(i) ? elem(static_cast<Coll>(C), static_cast<size_t>(i), D) : 0.0;
    NEXT;
  }
  CASE(Neg) r[A] = -r[B]; NEXT;
  CASE(Not) r[A] = r[B] == 0 ? 1.0 : 0.0; NEXT;
  CASE(Add) r[A] = r[B] + r[C]; NEXT;
  CASE(Sub) r[A] = r[B] - r[C]; NEXT;
  CASE(Mul) r[A] = r[B] * r[C]; NEXT;
  CASE(Div) {
    if (r[C] == 0) return fault(Fault::DivZero, ci, pc());
    r[A] = r[B] / r[C];
    NEXT;
  }
  CASE(Mod) {
    double a = r[B], b = r[C];
    if (b == 0) return fault(Fault::ModZero, ci, pc());
    r[A] = a - b * std::floor(a / b);
    NEXT;
  }
  CASE(Eq) r[A] = r[B] == r[C]; NEXT;
  CASE(Ne) r[A] = r[B] != r[C]; NEXT;
  CASE(Lt) r[A] = r[B] < r[C]; NEXT;
  CASE(Le) r[A] = r[B] <= r[C]; NEXT;
  CASE(Min) r[A] = std::min(r[B], r[C]); NEXT;
  CASE(Max) r[A] = std::max(r[B], r[C]); NEXT;
  CASE(Clamp) r[A] = std::min(std::max(r[B], r[C]), r[D]); NEXT;
  CASE(Lerp) r[A] = r[B] + (r[C] - r[B]) * r[D]; NEXT;
  CASE(Abs) r[A] = std::abs(r[B]); NEXT;
  CASE(Round) r[A] = round_half_away(r[B]); NEXT;
  CASE(Floor) r[A] = std::floor(r[B]); NEXT;
  CASE(Ceil) r[A] = std::ceil(r[B]); NEXT;
  CASE(Sqrt) {
    if (r[B] < 0) return fault(Fault::SqrtNeg, ci, pc());
    r[A] = std::sqrt(r[B]);
    NEXT;
  }
  CASE(Sin) r[A] = std::sin(r[B]); NEXT;
  CASE(Cos) r[A] = std::cos(r[B]); NEXT;
  CASE(Tan) r[A] = std::tan(r[B]); NEXT;
  CASE(Atan2) r[A] = std::atan2(r[B], r[C]) * 180 / std::numbers::pi; NEXT;
  CASE(Incr) r[A] += 1; NEXT;
  CASE(Jmp) JUMP(B); NEXT;
  CASE(Jt) if (r[A] != 0) JUMP(B); NEXT;
  CASE(Jf) if (r[A] == 0) JUMP(B); NEXT;

#define TRANCHE_FUSED_CASES(Cmp, op)                   \
  CASE(J##Cmp##FK) if (F[B] op K[C]) JUMP(D); NEXT;     \
  CASE(Jn##Cmp##FK) if (!(F[B] op K[C])) JUMP(D); NEXT; \
  CASE(J##Cmp##RK) if (r[A] op K[B]) JUMP(C); NEXT;     \
  CASE(Jn##Cmp##RK) if (!(r[A] op K[B])) JUMP(C); NEXT; \
  CASE(J##Cmp##RR) if (r[A] op r[B]) JUMP(C); NEXT;     \
  CASE(Jn##Cmp##RR) if (!(r[A] op r[B])) JUMP(C); NEXT;
  TRANCHE_FUSED_CASES(Eq, ==)
  TRANCHE_FUSED_CASES(Ne, !=)
  TRANCHE_FUSED_CASES(Lt, <)
  TRANCHE_FUSED_CASES(Le, <=)
  TRANCHE_FUSED_CASES(Gt, >)
  TRANCHE_FUSED_CASES(Ge, >=)
#undef TRANCHE_FUSED_CASES

  CASE(Ret) result = r[A]; return true;
  CASE(RetK) result = K[B]; return true;
  CASE(Halt) result = 0; return true;

  CASE(TLit) {
    st_.text += p_.strings[B];
    if (st_.text.size() > kMaxTextBytes) return fault(Fault::TextTooLong, ci, pc());
    NEXT;
  }
  CASE(TNum) {
    if (!std::isfinite(r[A])) return fault(Fault::NotFinite, ci, pc());
    st_.text += format_number(r[A], B);
    if (st_.text.size() > kMaxTextBytes) return fault(Fault::TextTooLong, ci, pc());
    NEXT;
  }
  CASE(TInt) {
    if (!std::isfinite(r[A])) return fault(Fault::NotFinite, ci, pc());
    st_.text += format_number(std::trunc(r[A]), 0);
    if (st_.text.size() > kMaxTextBytes) return fault(Fault::TextTooLong, ci, pc());
    NEXT;
  }
  CASE(TBool) st_.text += r[A] != 0 ? '1' : '0'; NEXT;
  CASE(TEnum) {
    double v = r[A];
    const auto& info = schema::enums()[B];
    st_.text += v >= 0 && v < static_cast<double>(info.values.size()) ? info.values[static_cast<size_t>(v)]
                                                                       : std::string_view("?");
    if (st_.text.size() > kMaxTextBytes) return fault(Fault::TextTooLong, ci, pc());
    NEXT;
  }
  CASE(Gcode) if (!emit(false, ci, pc())) return false; NEXT;
  CASE(Comment) if (!emit(true, ci, pc())) return false; NEXT;

  CASE(MoveTo) {
    if (!std::isfinite(r[A]) || !std::isfinite(r[B])) return fault(Fault::NotFinite, ci, pc());
    ctx::MoveOptions o;
    o.travel = (C & kMoveTravel) != 0;
    uint16_t k = D;
    auto opt = [&](uint16_t flag, std::optional<double>& v, schema::PropId q) {
      if (!(C & flag)) return true;
      auto checked = RuleSet::check_value(q, r[k++]);
      if (!checked) return false;
      v = *checked;
      return true;
    };
    if (!opt(kMoveSpeed, o.speed, schema::PropId::Speed) || !opt(kMoveFlow, o.flow, schema::PropId::Flow) ||
        !opt(kMoveWidth, o.width, schema::PropId::Width))
      return fault(Fault::NotFinite, ci, pc());
    emitted_ += 40;
    if (emitted_ > kMaxOutputBytes) return fault(Fault::OutputTooLong, ci, pc());
    if (api) api->move_to(r[A], r[B], o);
    NEXT;
  }
  CASE(Default) {
    if (api)
      if (Status s = api->emit_default(); !s) {
        fail_api(s.error());
        fault_chunk_ = ci;
        fault_pc_ = pc();
        return false;
      }
    NEXT;
  }
  CASE(Offset) {
    if (!std::isfinite(r[A])) return fault(Fault::NotFinite, ci, pc());
    if (api)
      if (Status s = api->offset(r[A]); !s) {
        fail_api(s.error());
        fault_chunk_ = ci;
        fault_pc_ = pc();
        return false;
      }
    NEXT;
  }
  CASE(Retract) {
    emitted_ += 24;
    if (emitted_ > kMaxOutputBytes) return fault(Fault::OutputTooLong, ci, pc());
    if (api) api->retract();
    NEXT;
  }
  CASE(Reverse) {
    if (api)
      if (Status s = api->reverse(); !s) {
        fail_api(s.error());
        fault_chunk_ = ci;
        fault_pc_ = pc();
        return false;
      }
    NEXT;
  }

#ifndef TRANCHE_COMPUTED_GOTO
      default:
        return fault(Fault::Api, ci, pc());
    }
  }
#endif
#undef A
#undef B
#undef C
#undef D
#undef JUMP
#undef CASE
#undef NEXT
}

Error Machine::error() const {
  std::string what;
  switch (fault_) {
    case Fault::None: what = "no error"; break;
    case Fault::DivZero: what = "division by zero"; break;
    case Fault::ModZero: what = "remainder of a division by zero"; break;
    case Fault::SqrtNeg: what = "square root of a negative number"; break;
    case Fault::NotFinite: what = "a value that is not a finite number, or outside its range, was computed"; break;
    case Fault::TextTooLong: what = fmt::format("a template produced more than {} characters", kMaxTextBytes); break;
    case Fault::OutputTooLong:
      what = fmt::format("one element's G-code grew beyond {} MiB", kMaxOutputBytes >> 20);
      break;
    case Fault::Steps: what = fmt::format("loops ran more than {} steps for one element", kMaxLoopSteps); break;
    case Fault::Depth:
      what = "properties read their own earlier values too deeply (or rules nest too many registers)";
      break;
    case Fault::Api: what = api_error_ ? api_error_->message : std::string("invalid instruction"); break;
  }
  std::string where = instruction_location(p_, p_.chunks[fault_chunk_].start + fault_pc_);
  std::string rule = rule_ != UINT32_MAX ? rs_.rule_name(rule_) : std::string("a rule");
  if (where.empty() && rule_ != UINT32_MAX) where = rs_.rule_where(rule_);
  std::string help;
  if (fault_ == Fault::DivZero || fault_ == Fault::ModZero)
    help = "; guard it in the filter or with `if`, e.g. `below.area > 0 and ...`";
  else if (fault_ == Fault::SqrtNeg)
    help = "; take `sqrt(max(x, 0))` or guard it with `if`";
  return Error{where.empty() ? std::string("rules") : where, fmt::format("in {}: {}{}", rule, what, help)};
}

Result<ctx::Decider::Dependence> RuleSet::depends(Stage stage, const ctx::Context& c) const {
  Dependence d;
  const auto& list = stage_props_[static_cast<size_t>(stage)];
  if (list.empty()) return d;
  // Only outer conjuncts run here, and they read fields alone: no properties are needed.
  Machine m(*this, c, nullptr);
  for (auto q : list) {
    const auto qi = static_cast<size_t>(q);
    if (schema::property(q).stage != stage) {  // decided again at this finer stage: all of it counts
      for (size_t i = 0; i < cand_level_[qi].size(); ++i) {
        d.level = std::max(d.level, cand_level_[qi][i]);
        d.fields |= dep_fields_[qi][i];
      }
      continue;
    }
    const ThreadState::Live* live;
    if (!m.live_list(q, live)) return m.error();
    auto add = [&](size_t i) {
      d.level = std::max(d.level, dep_level_[qi][i]);
      d.fields |= dep_fields_[qi][i];
    };
    if (live)
      for (const auto& e : live->entries) add(e.candidate);
    else
      for (size_t i = 0; i < dep_level_[qi].size(); ++i) add(i);
  }
  return d;
}

Status RuleSet::decide(Stage stage, const ctx::Context& c, ctx::PropertyValues& props) const {
  const auto& list = stage_props_[static_cast<size_t>(stage)];
  if (list.empty()) return ok_status();
  // A property decided again at a finer stage starts again from what the rules started from.
  for (auto q : list)
    if (schema::property(q).stage == stage) props.base[static_cast<size_t>(q)] = props[q];
    else props[q] = props.base[static_cast<size_t>(q)];
  Machine m(*this, c, &props);
  for (auto q : list) {
    const bool finer_later = schema::finest_stage(q) != stage && schema::property(q).stage == stage;
    m.limit_ = finer_later ? schema::stage_level(stage) : Level::Piece;
    int i;
    if (!m.winner(q, UINT32_MAX, i)) return m.error();
    if (i < 0) continue;
    double v;
    if (!m.value(q, i, v)) return m.error();
    const Range& range = ranges_[static_cast<size_t>(q)];
    ctx::Trace* trace = c.trace();
    if (range.plain && v >= range.min && v <= range.max) {  // the common case: a number in range
      props[q] = v;
      if (trace) trace->step({q, ctx::TraceStep::Source::Rule, cand_rule(q, i), cand_chunk(q, i), v, 0});
      continue;
    }
    auto checked = check_value(q, v);
    if (!checked) {
      const Candidate& cand = program_.props[static_cast<size_t>(q)][static_cast<size_t>(i)];
      std::string where = instruction_location(program_, program_.chunks[cand.chunk].start);
      if (where.empty()) where = rule_where(cand.rule);
      return Error{where.empty() ? "rules" : where,
                   fmt::format("in {}: {}", rule_name(cand.rule), checked.error().message)};
    }
    props[q] = *checked;
    if (trace) trace->step({q, ctx::TraceStep::Source::Rule, cand_rule(q, i), cand_chunk(q, i), *checked, 0});
  }
  return ok_status();
}

}  // namespace tranche::vm
