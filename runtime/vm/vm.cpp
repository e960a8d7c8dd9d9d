#include "runtime/vm/vm.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "runtime/vm/verify.h"

namespace tranche::vm {

using schema::Level;
using schema::Stage;

namespace {

// Registers of every frame of the calling thread: frames nest (a value that reads its own
// property's earlier value runs another candidate's chunk), so they are carved from one block
// that never moves.
constexpr size_t kStackRegs = 1u << 17;

struct ThreadState {
  std::unique_ptr<double[]> regs{new double[kStackRegs]()};
  size_t top = 0;
  // Per property: the candidates live for the current outer element (see vm.h, hoisting).
  struct Live {
    uint64_t key = 0;  // Context::generation of the level outside the decision; 0: none
    uint32_t owner = 0;
    struct Entry {
      uint32_t candidate;       // index into the property's candidates
      uint32_t first, count;    // its inner conjuncts in RuleSet::split_list_
    };
    std::vector<Entry> entries;  // in candidate order
  };
  std::array<Live, schema::kPropCount> live;
  std::string text;  // the template being built
  Counters counters;
};

ThreadState& state() {
  thread_local ThreadState s;
  return s;
}


enum class Fault : uint8_t { None, DivZero, ModZero, SqrtNeg, NotFinite, TextTooLong, OutputTooLong, Steps,
                             Depth, Api };

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

// Runs chunks for one call into the RuleSet (one decision, one hook, one replacement).
class Machine {
 public:
  Machine(const RuleSet& rs, const ctx::Context& c, const ctx::PropertyValues* props)
      : rs_(rs), p_(rs.program_), ctx_(c), props_(props), st_(state()) {}

  ctx::LineSink* out = nullptr;
  ctx::ReplaceApi* api = nullptr;

  ~Machine() {
    st_.counters.conjuncts_run += run_;
    st_.counters.live_rebuilds += rebuilds_;
  }

  // Runs chunk `ci`; false on a fault (see error()).
  bool exec(uint32_t ci, double& result);
  // Whether conjunct k holds (for rule r, named in errors).
  bool conj(uint32_t k, uint32_t r, bool& ok);
  // Whether every conjunct of rule r holds.
  bool test(uint32_t r, bool& result);
  // The candidate of property q that decides it, among those of rules before `below` (all when
  // UINT32_MAX): its index, or -1 when none matches.
  bool winner(schema::PropId q, uint32_t below, int& index);
  // The value of property q as the rules before `below` decide it (else its base).
  bool resolve(schema::PropId q, uint32_t below, double& result);
  // The value of candidate i of property q.
  bool value(schema::PropId q, int i, double& result);

  Error error() const;
  bool faulted() const { return fault_ != Fault::None; }
  void fail_api(Error e) {
    fault_ = Fault::Api;
    api_error_ = std::make_unique<Error>(std::move(e));
  }

 private:
  bool fault(Fault f, uint32_t ci, uint32_t pc) {
    fault_ = f;
    fault_chunk_ = ci;
    fault_pc_ = pc;
    return false;
  }
  double elem(Coll c, size_t index, uint16_t member) const;
  size_t count(Coll c) const;
  bool emit(bool comment, uint32_t ci, uint32_t pc);

  const RuleSet& rs_;
  const Program& p_;
  const ctx::Context& ctx_;
  const ctx::PropertyValues* props_;
  ThreadState& st_;
  uint64_t steps_ = 0;
  size_t emitted_ = 0;
  int depth_ = 0;
  Fault fault_ = Fault::None;
  uint32_t fault_chunk_ = 0, fault_pc_ = 0;
  std::unique_ptr<Error> api_error_;  // set with Fault::Api
  uint32_t rule_ = UINT32_MAX;  // the rule whose code runs (for messages)
  uint16_t depth_read_ = 0;     // values read as "the rules before" being computed (for traces)
  uint64_t run_ = 0, rebuilds_ = 0;

  friend class RuleSet;
};

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
  Level outer = rs_.decided_at_[qi];
  uint64_t key = outer > Level::Print ? ctx_.generation(static_cast<Level>(static_cast<int>(outer) - 1)) : 0;
  if (key != 0) {
    ThreadState::Live& live = st_.live[qi];
    if (live.key != key || live.owner != rs_.uid_) {
      ++rebuilds_;
      live.entries.clear();
      for (uint32_t i = 0; i < cands.size(); ++i) {
        bool ok;
        if (!all(list + split[i].first, split[i].outer, cands[i].rule, ok)) return false;
        if (ok) live.entries.push_back({i, split[i].first + split[i].outer, split[i].inner});
      }
      live.key = key;
      live.owner = rs_.uid_;
    }
    for (const auto& e : live.entries) {
      if (e.candidate < start) continue;
      bool ok = true;
      for (uint32_t j = 0; j < e.count && ok; ++j)
        if (!conj(list[e.first + j], cands[e.candidate].rule, ok)) return false;
      if (ok) return index = static_cast<int>(e.candidate), true;
    }
    return index = -1, true;
  }
  for (size_t i = start; i < cands.size(); ++i) {
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
  const Program& p = program_;
  // Per chunk: the innermost level it reads and whether it reads only fields.
  std::vector<Level> chunk_level(p.chunks.size(), Level::Print);
  std::vector<uint8_t> pure(p.chunks.size(), 1);
  for (size_t c = 0; c < p.chunks.size(); ++c) {
    const Chunk& ch = p.chunks[c];
    Level lv = Level::Print;
    for (uint32_t i = 0; i < ch.size; ++i) {
      const Instr& in = p.code[ch.start + i];
      const OpInfo& info = op_info(in.code());
      auto field = [&](uint16_t f) {
        reads_[f] = true;
        lv = std::max(lv, schema::fields()[f].level);
      };
      if (info.b == Operand::Field) field(in.b);
      if (info.c == Operand::Field) field(in.c);
      switch (in.code()) {
        case Op::Prop:
        case Op::Inherit:
          pure[c] = 0;
          lv = std::max(lv, schema::stage_level(schema::property(static_cast<schema::PropId>(in.b)).stage));
          break;
        case Op::Layer:
        case Op::LayerRel:
          lv = std::max(lv, Level::Layer);
          break;
        case Op::Count:
        case Op::Elem: {
          pure[c] = 0;
          auto coll = static_cast<Coll>(in.code() == Op::Count ? in.b : in.c);
          lv = std::max(lv, coll == Coll::Islands ? Level::Layer : Level::Path);
          if (in.code() == Op::Elem && coll != Coll::Points) reads_[in.d] = true;
          break;
        }
        default:
          break;
      }
    }
    chunk_level[c] = lv;
  }
  // Conjuncts of the form `field CMP constant`: [j(n)CMP.fk field, K, ->2; retk 1; retk 0].
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
  is_const_.assign(p.chunks.size(), 0);
  const_value_.assign(p.chunks.size(), 0);
  for (size_t c = 0; c < p.chunks.size(); ++c) {
    const Chunk& ch = p.chunks[c];
    if (ch.kind == ChunkKind::Value && ch.size == 1 && p.code[ch.start].code() == Op::RetK) {
      is_const_[c] = 1;
      const_value_[c] = p.consts[p.code[ch.start].b];
    }
  }
  auto rule_level = [&](uint32_t r) {
    Level lv = Level::Print;
    for (uint32_t k = p.rules[r].first; k < p.rules[r].first + p.rules[r].count; ++k)
      lv = std::max(lv, std::max(p.conjuncts[k].level, chunk_level[p.conjuncts[k].chunk]));
    return lv;
  };
  for (const auto& info : schema::properties()) {
    Range& r = ranges_[static_cast<size_t>(info.id)];
    r.plain = info.type == schema::Type::Number && info.unit != schema::Unit::Deg;
    r.min = info.min;
    r.max = info.max;
  }
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
    if (cands.empty()) continue;
    stage_props_[static_cast<size_t>(st)].push_back(q);
    Level& v = varies_[static_cast<size_t>(st)];
    for (const auto& c : cands) v = std::max(v, std::max(rule_level(c.rule), chunk_level[c.chunk]));
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
  if (info.unit == schema::Unit::Deg) {
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

std::string RuleSet::rule_where(uint32_t r) const {
  const Debug& d = program_.debug;
  if (r >= d.rule_loc.size()) return {};
  const Loc& l = d.locs[d.rule_loc[r]];
  if (l.line == 0) return d.files[l.file];
  return fmt::format("{}:{}:{}", d.files[l.file], l.line, l.col);
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

Status RuleSet::decide(Stage stage, const ctx::Context& c, ctx::PropertyValues& props) const {
  const auto& list = stage_props_[static_cast<size_t>(stage)];
  if (list.empty()) return ok_status();
  for (auto q : list) props.base[static_cast<size_t>(q)] = props[q];
  Machine m(*this, c, &props);
  for (auto q : list) {
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
