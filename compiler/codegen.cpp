#include "compiler/codegen.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <unordered_map>

#include "runtime/vm/verify.h"

namespace tranche::compiler {

using ast::Expr;
using ast::ExprKind;
using ast::Op;
using ast::RefKind;
using ast::Stmt;
using ast::StmtKind;
using vm::Instr;
using VOp = vm::Op;

namespace {

// Thrown inside the generator when a VM limit is exceeded; caught at its boundary.
struct CodegenLimit {
  std::string message;
};

// The six comparisons as they appear in fused opcodes, and their mirror (operands swapped).
enum class Cmp { Eq, Ne, Lt, Le, Gt, Ge };

Cmp mirror(Cmp c) {
  switch (c) {
    case Cmp::Lt: return Cmp::Gt;
    case Cmp::Le: return Cmp::Ge;
    case Cmp::Gt: return Cmp::Lt;
    case Cmp::Ge: return Cmp::Le;
    default: return c;
  }
}

std::optional<Cmp> cmp_of(Op op) {
  switch (op) {
    case Op::Eq: return Cmp::Eq;
    case Op::Ne: return Cmp::Ne;
    case Op::Lt: return Cmp::Lt;
    case Op::Le: return Cmp::Le;
    case Op::Gt: return Cmp::Gt;
    case Op::Ge: return Cmp::Ge;
    default: return std::nullopt;
  }
}

// Fused opcode for (comparison, operand form, polarity). Form: 0 FK, 1 RK, 2 RR.
VOp fused(Cmp c, int form, bool when_true) {
  static constexpr VOp table[6][3][2] = {
      {{VOp::JnEqFK, VOp::JEqFK}, {VOp::JnEqRK, VOp::JEqRK}, {VOp::JnEqRR, VOp::JEqRR}},
      {{VOp::JnNeFK, VOp::JNeFK}, {VOp::JnNeRK, VOp::JNeRK}, {VOp::JnNeRR, VOp::JNeRR}},
      {{VOp::JnLtFK, VOp::JLtFK}, {VOp::JnLtRK, VOp::JLtRK}, {VOp::JnLtRR, VOp::JLtRR}},
      {{VOp::JnLeFK, VOp::JLeFK}, {VOp::JnLeRK, VOp::JLeRK}, {VOp::JnLeRR, VOp::JLeRR}},
      {{VOp::JnGtFK, VOp::JGtFK}, {VOp::JnGtRK, VOp::JGtRK}, {VOp::JnGtRR, VOp::JGtRR}},
      {{VOp::JnGeFK, VOp::JGeFK}, {VOp::JnGeRK, VOp::JGeRK}, {VOp::JnGeRR, VOp::JGeRR}},
  };
  return table[static_cast<int>(c)][form][when_true ? 1 : 0];
}

bool plain_field(const Expr& e) { return e.ref == RefKind::Field && !e.constant; }

class Generator {
 public:
  Generator(const ast::Program& ast, const CodegenOptions& options) : ast_(ast), options_(options) {}

  vm::Program run() {
    if (ast_.cascade.size() > vm::kMaxRules) throw CodegenLimit{"more than 65535 rules"};
    if (options_.debug) {
      for (size_t f = 0; f < ast_.sources.size(); ++f) p_.debug.files.push_back(ast_.sources.file(static_cast<uint32_t>(f)).path);
      p_.debug.locs.push_back({0, 0, 0});  // "nowhere"
    }
    // Per slot, the candidates in cascade order; reversed at the end.
    std::array<vm::Candidates, schema::kPropCount> props;
    std::array<std::array<vm::Candidates, 2>, schema::kLevelCount> hooks;
    std::array<vm::Candidates, schema::kLevelCount> replace;
    for (const ast::Rule* r : ast_.cascade) {
      rule_ = r;
      uint32_t index = static_cast<uint32_t>(p_.rules.size());
      vm::Rule rule;
      rule.first = static_cast<uint32_t>(p_.conjuncts.size());
      for (const auto& cj : r->conjuncts) {
        if (cj.expr->constant && *cj.expr->constant != 0) continue;  // always true: nothing to test
        p_.conjuncts.push_back({test_chunk(*cj.expr), cj.level});
        if (options_.debug) {
          p_.debug.conj_text.emplace_back(ast_.sources.text(cj.expr->span));
          p_.debug.conj_loc.push_back(loc(cj.expr->span));
        }
      }
      rule.count = static_cast<uint32_t>(p_.conjuncts.size()) - rule.first;
      p_.rules.push_back(rule);
      if (options_.debug) {
        p_.debug.rule_names.push_back(r->display(ast_.sources));
        p_.debug.rule_loc.push_back(loc(r->span));
      }
      for (const auto& slot : r->slots) {
        const Stmt& a = *slot.action;
        switch (slot.kind) {
          case ast::SlotKind::Property: {
            auto& list = props[static_cast<size_t>(slot.prop)];
            uint32_t chunk = value_chunk(*a.value);
            if (!list.empty() && list.back().rule == index) list.pop_back();  // set twice: the last wins
            list.push_back({index, chunk, false});
            break;
          }
          case ast::SlotKind::Hook: {
            auto& list = hooks[static_cast<size_t>(slot.level)][slot.when == ast::When::Before ? 0 : 1];
            list.push_back({index, body_chunk(a, vm::ChunkKind::Hook), slot.append});
            break;
          }
          case ast::SlotKind::Replace: {
            auto& list = replace[static_cast<size_t>(slot.level)];
            uint32_t chunk = body_chunk(a, vm::ChunkKind::Replace);
            if (!list.empty() && list.back().rule == index) list.pop_back();
            list.push_back({index, chunk, false});
            break;
          }
        }
      }
    }
    auto reversed = [](vm::Candidates c) {
      std::reverse(c.begin(), c.end());
      return c;
    };
    for (size_t i = 0; i < props.size(); ++i) p_.props[i] = reversed(props[i]);
    for (size_t l = 0; l < hooks.size(); ++l)
      for (size_t w = 0; w < 2; ++w) p_.hooks[l][w] = reversed(hooks[l][w]);
    for (size_t l = 0; l < replace.size(); ++l) p_.replace[l] = reversed(replace[l]);
    p_.property_order = ast_.property_order;
    if (p_.property_order.size() != static_cast<size_t>(schema::kPropCount)) {
      p_.property_order.clear();
      for (const auto& info : schema::properties()) p_.property_order.push_back(info.id);
      std::stable_sort(p_.property_order.begin(), p_.property_order.end(),
                       [](auto a, auto b) { return schema::property(a).stage < schema::property(b).stage; });
    }
    return std::move(p_);
  }

 private:
  // ---- chunks ---------------------------------------------------------------------------
  struct ChunkState {
    uint32_t start = 0;
    int next = 0;   // first free register
    int max = 0;    // registers used
    int base = 0;   // locals occupy [0, base)
  };

  void begin(int locals) {
    cs_ = ChunkState{};
    cs_.start = static_cast<uint32_t>(p_.code.size());
    cs_.next = cs_.max = cs_.base = locals;
    if (locals > 256) throw CodegenLimit{fmt::format("{} uses more than 256 names", rule_->display(ast_.sources))};
  }
  uint32_t end(vm::ChunkKind kind) {
    uint32_t size = static_cast<uint32_t>(p_.code.size()) - cs_.start;
    if (size > vm::kMaxChunkSize)
      throw CodegenLimit{fmt::format("{} compiles to more than {} instructions in one action", rule_->display(ast_.sources),
                              vm::kMaxChunkSize)};
    p_.chunks.push_back({cs_.start, size, static_cast<uint16_t>(std::max(cs_.max, 1)), kind});
    return static_cast<uint32_t>(p_.chunks.size() - 1);
  }
  int alloc() {
    int r = cs_.next++;
    if (r >= 256)
      throw CodegenLimit{fmt::format("{} needs more than 256 registers in one action", rule_->display(ast_.sources))};
    cs_.max = std::max(cs_.max, cs_.next);
    return r;
  }
  // Registers allocated after `mark` are free again.
  int mark() const { return cs_.next; }
  void release(int m) { cs_.next = m; }

  uint32_t test_chunk(const Expr& e) {
    begin(0);
    span_ = e.span;
    Label fail;
    cond(e, false, fail);
    emit(VOp::RetK, 0, konst(1));
    place(fail);
    emit(VOp::RetK, 0, konst(0));
    return end(vm::ChunkKind::Test);
  }

  uint32_t value_chunk(const Expr& e) {
    begin(0);
    span_ = e.span;
    if (e.constant) {
      emit(VOp::RetK, 0, konst(*e.constant));
    } else {
      int r = value(e);
      emit(VOp::Ret, static_cast<uint8_t>(r));
    }
    return end(vm::ChunkKind::Value);
  }

  uint32_t body_chunk(const Stmt& action, vm::ChunkKind kind) {
    begin(action.frame_size);
    action_ = &action;
    span_ = action.span;
    statements(action.body);
    span_ = action.span;
    emit(VOp::Halt);
    return end(kind);
  }

  // ---- emission, labels ---------------------------------------------------------------
  struct Label {
    int target = -1;               // chunk-relative, once placed
    std::vector<uint32_t> fixups;  // absolute indices of jumps to patch
  };

  uint32_t emit(VOp op, uint8_t a = 0, uint16_t b = 0, uint16_t c = 0, uint16_t d = 0) {
    p_.code.push_back(Instr{static_cast<uint8_t>(op), a, b, c, d});
    if (options_.debug) p_.debug.instr_loc.push_back(loc(span_));
    return static_cast<uint32_t>(p_.code.size() - 1);
  }
  void jump_to(uint32_t at, Label& l) {
    if (l.target >= 0) set_target(at, static_cast<uint16_t>(l.target));
    else l.fixups.push_back(at);
  }
  void place(Label& l) {
    l.target = static_cast<int>(p_.code.size() - cs_.start);
    if (l.target > static_cast<int>(vm::kMaxChunkSize))
      throw CodegenLimit{fmt::format("{} compiles to too much code in one action", rule_->display(ast_.sources))};
    for (uint32_t at : l.fixups) set_target(at, static_cast<uint16_t>(l.target));
    l.fixups.clear();
  }
  void set_target(uint32_t at, uint16_t target) {
    Instr& in = p_.code[at];
    const vm::OpInfo& info = vm::op_info(in.code());
    if (info.b == vm::Operand::Jump) in.b = target;
    else if (info.c == vm::Operand::Jump) in.c = target;
    else in.d = target;
  }
  void jmp(Label& l) { jump_to(emit(VOp::Jmp), l); }

  uint16_t konst(double v) {
    if (v == 0) v = 0;  // one entry for -0 and 0
    uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    auto [it, fresh] = konst_.try_emplace(bits, static_cast<uint16_t>(p_.consts.size()));
    if (fresh) {
      if (p_.consts.size() >= vm::kMaxConsts) throw CodegenLimit{"more than 65536 distinct constants"};
      p_.consts.push_back(v);
    }
    return it->second;
  }
  uint16_t string(const std::string& s) {
    auto [it, fresh] = strings_.try_emplace(s, static_cast<uint16_t>(p_.strings.size()));
    if (fresh) {
      if (p_.strings.size() >= vm::kMaxStrings) throw CodegenLimit{"more than 65536 distinct texts (templates and names)"};
      p_.strings.push_back(s);
    }
    return it->second;
  }
  uint32_t loc(const ast::Span& s) {
    if (!s.valid()) return 0;
    uint64_t key = uint64_t(s.file) << 48 ^ uint64_t(s.line) << 20 ^ s.col;
    auto [it, fresh] = locs_.try_emplace(key, static_cast<uint32_t>(p_.debug.locs.size()));
    if (fresh) p_.debug.locs.push_back({s.file, s.line, s.col});
    return it->second;
  }

  // ---- expressions --------------------------------------------------------------------
  // The register holding e's value: a local's own register, or a new one.
  int value(const Expr& e) {
    if (!e.constant && e.ref == RefKind::Local) return e.local;
    if (!e.constant && e.ref == RefKind::Bound) return bound_[static_cast<size_t>(e.local)];
    if (!e.constant && e.ref == RefKind::ElementField && e.element == ast::Element::Point &&
        e.point_field == ast::PointField::Index)
      return e.local;
    int r = alloc();
    into(e, r);
    return r;
  }

  // Computes e into register dst.
  void into(const Expr& e, int dst) {
    ast::Span saved = span_;
    if (e.span.valid()) span_ = e.span;
    auto d = static_cast<uint8_t>(dst);
    if (e.constant) {
      emit(VOp::LoadK, d, konst(*e.constant));
      span_ = saved;
      return;
    }
    switch (e.ref) {
      case RefKind::Field:
        emit(VOp::Field, d, static_cast<uint16_t>(e.field));
        span_ = saved;
        return;
      case RefKind::OtherLayer:
        if (e.other == ast::OtherLayer::Indexed) {
          int m = mark();
          int i = value(*e.args[0]);
          emit(VOp::Layer, d, static_cast<uint16_t>(i), static_cast<uint16_t>(e.field));
          release(m);
        } else {
          emit(VOp::LayerRel, d, e.other == ast::OtherLayer::Below ? 0 : 2, static_cast<uint16_t>(e.field));
        }
        span_ = saved;
        return;
      case RefKind::Property:
        emit(VOp::Prop, d, static_cast<uint16_t>(e.prop));
        span_ = saved;
        return;
      case RefKind::Inherited:
        emit(VOp::Inherit, d, static_cast<uint16_t>(e.prop), static_cast<uint16_t>(rule_->index));
        span_ = saved;
        return;
      case RefKind::Local:
        if (e.local != dst) emit(VOp::Move, d, static_cast<uint16_t>(e.local));
        span_ = saved;
        return;
      case RefKind::ElementField: {
        auto coll = e.element == ast::Element::Point   ? vm::Coll::Points
                    : e.element == ast::Element::Piece ? vm::Coll::Pieces
                                                       : vm::Coll::Islands;
        if (coll == vm::Coll::Points && e.point_field == ast::PointField::Index) {
          if (e.local != dst) emit(VOp::Move, d, static_cast<uint16_t>(e.local));
        } else {
          uint16_t member = coll == vm::Coll::Points
                                ? (e.point_field == ast::PointField::X ? vm::kPointX : vm::kPointY)
                                : static_cast<uint16_t>(e.field);
          emit(VOp::Elem, d, static_cast<uint16_t>(e.local), static_cast<uint16_t>(coll), member);
        }
        span_ = saved;
        return;
      }
      case RefKind::EnumValue:
        emit(VOp::LoadK, d, konst(e.enum_value));
        span_ = saved;
        return;
      case RefKind::Bound:
        if (bound_[static_cast<size_t>(e.local)] != dst)
          emit(VOp::Move, d, static_cast<uint16_t>(bound_[static_cast<size_t>(e.local)]));
        span_ = saved;
        return;
      case RefKind::None:
        break;
    }
    int m = mark();
    switch (e.kind) {
      case ExprKind::Number:
        emit(VOp::LoadK, d, konst(e.number));
        break;
      case ExprKind::Bool:
        emit(VOp::LoadK, d, konst(e.boolean ? 1 : 0));
        break;
      case ExprKind::Unary: {
        int a = value(*e.args[0]);
        emit(e.op == Op::Neg ? VOp::Neg : VOp::Not, d, static_cast<uint16_t>(a));
        break;
      }
      case ExprKind::Binary: {
        if (e.op == Op::And || e.op == Op::Or || cmp_of(e.op)) {
          boolean(e, dst);
          break;
        }
        int a = value(*e.args[0]);
        int b = value(*e.args[1]);
        VOp op = e.op == Op::Add ? VOp::Add : e.op == Op::Sub ? VOp::Sub : e.op == Op::Mul ? VOp::Mul
                 : e.op == Op::Div ? VOp::Div : VOp::Mod;
        emit(op, d, static_cast<uint16_t>(a), static_cast<uint16_t>(b));
        break;
      }
      case ExprKind::InRange:
      case ExprKind::InSet:
        boolean(e, dst);
        break;
      case ExprKind::If: {
        Label other, done;
        cond(*e.args[0], false, other);
        into(*e.args[1], dst);
        jmp(done);
        place(other);
        into(*e.args[2], dst);
        place(done);
        break;
      }
      case ExprKind::Call:
        call(e, dst);
        break;
      case ExprKind::Quantifier:
        quantifier(e, dst);
        break;
      case ExprKind::String:
        // Quoted text compared with a name: its index in the strings, the value the name takes
        // for the same text (vm::RuleSet::text_index); linking keeps each text once.
        emit(VOp::LoadS, d, string(e.str));
        break;
      default:
        // Names, members and strings are resolved (ref) or reported by the checker.
        emit(VOp::LoadK, d, konst(0));
        break;
    }
    release(m);
    span_ = saved;
  }

  // `any(i in lo..hi: c)` (`all`) into dst: i counts up from lo, and the loop stops at the first
  // step that decides (c true for `any`, false for `all`). The VM bounds backward jumps.
  void quantifier(const Expr& e, int dst) {
    bool any = e.text == "any";
    auto d = static_cast<uint8_t>(dst);
    int i = alloc();
    into(*e.args[0], i);
    bound_.push_back(i);
    emit(VOp::LoadK, d, konst(any ? 0 : 1));
    Label top, hit, done;
    place(top);
    jump_to(emit(VOp::JGtRK, static_cast<uint8_t>(i), konst(*e.args[1]->constant)), done);
    cond(*e.args[2], any, hit);
    emit(VOp::Incr, static_cast<uint8_t>(i));
    jmp(top);
    place(hit);
    emit(VOp::LoadK, d, konst(any ? 1 : 0));
    place(done);
    bound_.pop_back();
  }

  // A boolean expression into a register: 1 or 0.
  void boolean(const Expr& e, int dst) {
    Label no, done;
    cond(e, false, no);
    emit(VOp::LoadK, static_cast<uint8_t>(dst), konst(1));
    jmp(done);
    place(no);
    emit(VOp::LoadK, static_cast<uint8_t>(dst), konst(0));
    place(done);
  }

  void call(const Expr& e, int dst) {
    auto d = static_cast<uint8_t>(dst);
    auto arg = [&](size_t i) { return static_cast<uint16_t>(value(*e.args[i])); };
    switch (e.func) {
      case ast::Func::Min:
      case ast::Func::Max: {
        VOp op = e.func == ast::Func::Min ? VOp::Min : VOp::Max;
        int acc = alloc();
        into(*e.args[0], acc);
        for (size_t i = 1; i < e.args.size(); ++i) {
          int m = mark();
          emit(op, static_cast<uint8_t>(acc), static_cast<uint16_t>(acc), arg(i));
          release(m);
        }
        emit(VOp::Move, d, static_cast<uint16_t>(acc));
        return;
      }
      case ast::Func::Clamp: {
        uint16_t x = arg(0), lo = arg(1), hi = arg(2);
        emit(VOp::Clamp, d, x, lo, hi);
        return;
      }
      case ast::Func::Lerp: {
        uint16_t a = arg(0), b = arg(1), t = arg(2);
        emit(VOp::Lerp, d, a, b, t);
        return;
      }
      case ast::Func::Atan2: {
        uint16_t y = arg(0), x = arg(1);
        emit(VOp::Atan2, d, y, x);
        return;
      }
      case ast::Func::Sin:
      case ast::Func::Cos:
      case ast::Func::Tan: {
        int a = value(*e.args[0]);
        const auto& t = e.args[0]->type;
        if (t.kind == ast::Kind::Number && t.unit.deg == 1) {
          int k = alloc();
          emit(VOp::LoadK, static_cast<uint8_t>(k), konst(std::numbers::pi / 180));
          emit(VOp::Mul, static_cast<uint8_t>(k), static_cast<uint16_t>(a), static_cast<uint16_t>(k));
          a = k;
        }
        VOp op = e.func == ast::Func::Sin ? VOp::Sin : e.func == ast::Func::Cos ? VOp::Cos : VOp::Tan;
        emit(op, d, static_cast<uint16_t>(a));
        return;
      }
      case ast::Func::Abs:
      case ast::Func::Round:
      case ast::Func::Floor:
      case ast::Func::Ceil:
      case ast::Func::Sqrt: {
        VOp op = e.func == ast::Func::Abs     ? VOp::Abs
                 : e.func == ast::Func::Round ? VOp::Round
                 : e.func == ast::Func::Floor ? VOp::Floor
                 : e.func == ast::Func::Ceil  ? VOp::Ceil
                                              : VOp::Sqrt;
        emit(op, d, arg(0));
        return;
      }
    }
  }

  // ---- conditions -------------------------------------------------------------------------
  // Jumps to `target` when e is `when`; falls through otherwise.
  void cond(const Expr& e, bool when, Label& target) {
    ast::Span saved = span_;
    if (e.span.valid()) span_ = e.span;
    int m = mark();
    if (e.constant) {
      if ((*e.constant != 0) == when) jmp(target);
    } else if (e.kind == ExprKind::Unary && e.op == Op::Not) {
      cond(*e.args[0], !when, target);
    } else if (e.kind == ExprKind::Binary && (e.op == Op::And || e.op == Op::Or)) {
      bool is_and = e.op == Op::And;
      if (is_and != when) {
        // and/false or or/true: either operand decides alone.
        cond(*e.args[0], when, target);
        cond(*e.args[1], when, target);
      } else {
        Label skip;
        cond(*e.args[0], !when, skip);
        cond(*e.args[1], when, target);
        place(skip);
      }
    } else if (e.kind == ExprKind::Binary && cmp_of(e.op)) {
      compare(*e.args[0], *cmp_of(e.op), *e.args[1], when, target);
    } else if (e.kind == ExprKind::InRange) {
      // x in lo..hi  ==  x >= lo and x <= hi
      const Expr& x = *e.args[0];
      Shared sx = share(x);
      if (when) {
        Label skip;
        compare_shared(sx, Cmp::Ge, *e.args[1], false, skip);
        compare_shared(sx, Cmp::Le, *e.args[2], true, target);
        place(skip);
      } else {
        compare_shared(sx, Cmp::Ge, *e.args[1], false, target);
        compare_shared(sx, Cmp::Le, *e.args[2], false, target);
      }
    } else if (e.kind == ExprKind::InSet) {
      const Expr& x = *e.args[0];
      Shared sx = share(x);
      if (when) {
        for (size_t i = 1; i < e.args.size(); ++i) compare_shared(sx, Cmp::Eq, *e.args[i], true, target);
      } else {
        Label hit;
        for (size_t i = 1; i < e.args.size(); ++i) compare_shared(sx, Cmp::Eq, *e.args[i], true, hit);
        jmp(target);
        place(hit);
      }
    } else if (plain_field(e)) {
      // A boolean field: one fused test against 0.
      jump_to(emit(fused(Cmp::Ne, 0, when), 0, static_cast<uint16_t>(e.field), konst(0)), target);
    } else {
      int r = value(e);
      jump_to(emit(when ? VOp::Jt : VOp::Jf, static_cast<uint8_t>(r)), target);
    }
    release(m);
    span_ = saved;
  }

  // An operand compared several times (`x in a..b`, `x in (a, b)`): a field is read in place,
  // anything else is computed once into a register.
  struct Shared {
    const Expr* e;
    int reg = -1;  // -1: a plain field or a constant
  };
  Shared share(const Expr& x) {
    if (plain_field(x) || x.constant) return {&x, -1};
    return {&x, value(x)};
  }

  void compare(const Expr& a, Cmp c, const Expr& b, bool when, Label& target) {
    compare_shared(share(a), c, b, when, target);
  }

  void compare_shared(const Shared& sa, Cmp c, const Expr& b, bool when, Label& target) {
    const Expr& a = *sa.e;
    // Put a field or a computed value on the left and a constant on the right when possible.
    if (a.constant && !b.constant && sa.reg < 0) {
      Shared sb = share(b);
      compare_operands(sb, mirror(c), a, when, target);
      return;
    }
    compare_operands(sa, c, b, when, target);
  }

  void compare_operands(const Shared& sa, Cmp c, const Expr& b, bool when, Label& target) {
    const Expr& a = *sa.e;
    if (b.constant) {
      uint16_t k = konst(*b.constant);
      if (sa.reg < 0 && plain_field(a)) {
        jump_to(emit(fused(c, 0, when), 0, static_cast<uint16_t>(a.field), k), target);
        return;
      }
      int r = sa.reg >= 0 ? sa.reg : value(a);
      jump_to(emit(fused(c, 1, when), static_cast<uint8_t>(r), k), target);
      return;
    }
    int ra = sa.reg >= 0 ? sa.reg : value(a);
    int rb = value(b);
    jump_to(emit(fused(c, 2, when), static_cast<uint8_t>(ra), static_cast<uint16_t>(rb)), target);
  }

  // ---- statements -------------------------------------------------------------------------
  void statements(const std::vector<ast::StmtPtr>& body) {
    for (const auto& s : body) statement(*s);
  }

  void statement(const Stmt& s) {
    span_ = s.span;
    int m = mark();
    switch (s.kind) {
      case StmtKind::Gcode:
      case StmtKind::Comment:
        text(s.text);
        span_ = s.span;
        emit(s.kind == StmtKind::Gcode ? VOp::Gcode : VOp::Comment);
        break;
      case StmtKind::Let:
        if (s.local >= 0) into(*s.value, s.local);
        break;
      case StmtKind::If: {
        Label other, done;
        cond(*s.value, false, other);
        statements(s.body);
        if (!s.else_body.empty()) {
          jmp(done);
          place(other);
          statements(s.else_body);
          place(done);
        } else {
          place(other);
        }
        break;
      }
      case StmtKind::For:
        loop(s);
        break;
      case StmtKind::Move: {
        int x = value(*s.x);
        int y = value(*s.y);
        uint16_t flags = s.travel ? vm::kMoveTravel : 0;
        const Expr* opt[3] = {nullptr, nullptr, nullptr};
        for (const auto& o : s.options) {
          if (o.prop == schema::PropId::Speed) opt[0] = o.value.get();
          else if (o.prop == schema::PropId::Flow) opt[1] = o.value.get();
          else if (o.prop == schema::PropId::Width) opt[2] = o.value.get();
        }
        const uint16_t bits[3] = {vm::kMoveSpeed, vm::kMoveFlow, vm::kMoveWidth};
        int first = -1;
        for (int i = 0; i < 3; ++i) {
          if (!opt[i]) continue;
          int r = alloc();
          if (first < 0) first = r;
          flags |= bits[i];
          into(*opt[i], r);
        }
        span_ = s.span;
        emit(VOp::MoveTo, static_cast<uint8_t>(x), static_cast<uint16_t>(y), flags,
             static_cast<uint16_t>(first < 0 ? 0 : first));
        break;
      }
      case StmtKind::Default:
        emit(VOp::Default);
        break;
      case StmtKind::Offset: {
        int r = value(*s.value);
        span_ = s.span;
        emit(VOp::Offset, static_cast<uint8_t>(r));
        break;
      }
      case StmtKind::Reverse:
        emit(VOp::Reverse);
        break;
      case StmtKind::Retract:
        emit(VOp::Retract);
        break;
      case StmtKind::Assign:
      case StmtKind::Hook:
      case StmtKind::Replace:
        break;  // rejected by the checker inside bodies
    }
    release(m);
  }

  void text(const ast::Template& t) {
    for (const auto& part : t.parts) {
      if (!part.expr) {
        if (!part.text.empty()) emit(VOp::TLit, 0, string(part.text));
        continue;
      }
      int m = mark();
      int r = value(*part.expr);
      span_ = part.span.valid() ? part.span : span_;
      const ast::Type& type = part.expr->type;
      auto reg = static_cast<uint8_t>(r);
      if (type.kind == ast::Kind::Enum)
        emit(VOp::TEnum, reg, static_cast<uint16_t>(type.enum_type));
      else if (type.kind == ast::Kind::Bool)
        emit(VOp::TBool, reg);
      else if (type.kind == ast::Kind::Int && part.decimals < 0)
        emit(VOp::TInt, reg);
      else
        emit(VOp::TNum, reg, part.decimals < 0 ? vm::kDefaultDecimals : static_cast<uint16_t>(part.decimals));
      release(m);
    }
  }

  void loop(const Stmt& s) {
    if (s.local < 0) return;
    auto var = static_cast<uint8_t>(s.local);
    Label top, done;
    if (s.loop == ast::LoopKind::Range) {
      if (s.range_hi < s.range_lo) return;
      emit(VOp::LoadK, var, konst(static_cast<double>(s.range_lo)));
      uint16_t hi = konst(static_cast<double>(s.range_hi));
      place(top);
      jump_to(emit(VOp::JnLeRK, var, hi), done);
      statements(s.body);
      span_ = s.span;
      emit(VOp::Incr, var);
      jmp(top);
      place(done);
      return;
    }
    auto coll = s.loop == ast::LoopKind::Points   ? vm::Coll::Points
                : s.loop == ast::LoopKind::Pieces ? vm::Coll::Pieces
                                                  : vm::Coll::Islands;
    int limit = alloc();  // stays allocated during the body
    emit(VOp::Count, static_cast<uint8_t>(limit), static_cast<uint16_t>(coll));
    emit(VOp::LoadK, var, konst(0));
    place(top);
    jump_to(emit(VOp::JnLtRR, var, static_cast<uint16_t>(limit)), done);
    statements(s.body);
    span_ = s.span;
    emit(VOp::Incr, var);
    jmp(top);
    place(done);
  }

  const ast::Program& ast_;
  const CodegenOptions& options_;
  vm::Program p_;
  ChunkState cs_;
  const ast::Rule* rule_ = nullptr;
  const Stmt* action_ = nullptr;
  ast::Span span_;
  std::unordered_map<uint64_t, uint16_t> konst_;
  std::map<std::string, uint16_t> strings_;
  std::unordered_map<uint64_t, uint32_t> locs_;
  std::vector<int> bound_;  // registers of the quantifier variables around the expression
};

}  // namespace

Result<vm::Program> generate(const ast::Program& program, const CodegenOptions& options) {
  if (!program.checked) return Error{"rules", "the rules have errors: nothing to compile"};
  try {
    Generator g(program, options);
    return g.run();
  } catch (const CodegenLimit& l) {
    return Error{"rules", l.message};
  }
}

}  // namespace tranche::compiler
