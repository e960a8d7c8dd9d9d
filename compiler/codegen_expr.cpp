// Expressions into registers, and conditions into fused compare-and-jump instructions.
#include <cmath>
#include <numbers>

#include "compiler/generator.h"

namespace tranche::compiler::gen {

// ---- expressions --------------------------------------------------------------------
// The register holding e's value: a local's own register, or a new one.
int Generator::value(const Expr& e) {
  if (!e.constant && e.ref == RefKind::Local) return e.local;
  if (!e.constant && e.ref == RefKind::Bound) return bound_[static_cast<size_t>(e.local)];
  if (!e.constant && e.ref == RefKind::ElementField && e.element == ast::Element::Point &&
      e.point_field == ast::PointField::Index)
    return e.local;
  int r = alloc();
  into(e, r);
  return r;
}

// A reference (field, other layer, property, local, element, enum value, quantifier variable)
// into register dst; false when e is not one.
bool Generator::reference(const Expr& e, int dst) {
  auto d = static_cast<uint8_t>(dst);
  switch (e.ref) {
    case RefKind::Field:
      emit(VOp::Field, d, static_cast<uint16_t>(e.field));
      return true;
    case RefKind::OtherLayer:
      if (e.other == ast::OtherLayer::Indexed) {
        int m = mark();
        int i = value(*e.args[0]);
        emit(VOp::Layer, d, static_cast<uint16_t>(i), static_cast<uint16_t>(e.field));
        release(m);
      } else {
        emit(VOp::LayerRel, d, e.other == ast::OtherLayer::Below ? 0 : 2, static_cast<uint16_t>(e.field));
      }
      return true;
    case RefKind::Property:
      emit(VOp::Prop, d, static_cast<uint16_t>(e.prop));
      return true;
    case RefKind::Inherited:
      emit(VOp::Inherit, d, static_cast<uint16_t>(e.prop), static_cast<uint16_t>(rule_->index));
      return true;
    case RefKind::Local:
      if (e.local != dst) emit(VOp::Move, d, static_cast<uint16_t>(e.local));
      return true;
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
      return true;
    }
    case RefKind::EnumValue:
      emit(VOp::LoadK, d, konst(e.enum_value));
      return true;
    case RefKind::Bound:
      if (bound_[static_cast<size_t>(e.local)] != dst)
        emit(VOp::Move, d, static_cast<uint16_t>(bound_[static_cast<size_t>(e.local)]));
      return true;
    case RefKind::None:
      break;
  }
  return false;
}

// Computes e into register dst.
void Generator::into(const Expr& e, int dst) {
  ast::Span saved = span_;
  if (e.span.valid()) span_ = e.span;
  auto d = static_cast<uint8_t>(dst);
  if (e.constant) {
    emit(VOp::LoadK, d, konst(*e.constant));
    span_ = saved;
    return;
  }
  if (reference(e, dst)) {
    span_ = saved;
    return;
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
void Generator::quantifier(const Expr& e, int dst) {
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
void Generator::boolean(const Expr& e, int dst) {
  Label no, done;
  cond(e, false, no);
  emit(VOp::LoadK, static_cast<uint8_t>(dst), konst(1));
  jmp(done);
  place(no);
  emit(VOp::LoadK, static_cast<uint8_t>(dst), konst(0));
  place(done);
}

void Generator::call(const Expr& e, int dst) {
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
void Generator::cond(const Expr& e, bool when, Label& target) {
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

Generator::Shared Generator::share(const Expr& x) {
  if (plain_field(x) || x.constant) return {&x, -1};
  return {&x, value(x)};
}

void Generator::compare(const Expr& a, Cmp c, const Expr& b, bool when, Label& target) {
  compare_shared(share(a), c, b, when, target);
}

void Generator::compare_shared(const Shared& sa, Cmp c, const Expr& b, bool when, Label& target) {
  const Expr& a = *sa.e;
  // Put a field or a computed value on the left and a constant on the right when possible.
  if (a.constant && !b.constant && sa.reg < 0) {
    Shared sb = share(b);
    compare_operands(sb, mirror(c), a, when, target);
    return;
  }
  compare_operands(sa, c, b, when, target);
}

void Generator::compare_operands(const Shared& sa, Cmp c, const Expr& b, bool when, Label& target) {
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

}  // namespace tranche::compiler::gen
