// The statements of hook and replacer bodies: templates, `if`, loops, moves, replacer edits.
#include <cmath>
#include <numbers>

#include "compiler/generator.h"

namespace tranche::compiler::gen {

// ---- statements -------------------------------------------------------------------------
void Generator::statements(const std::vector<ast::StmtPtr>& body) {
  for (const auto& s : body) statement(*s);
}

void Generator::statement(const Stmt& s) {
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

void Generator::text(const ast::Template& t) {
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

void Generator::loop(const Stmt& s) {
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

}  // namespace tranche::compiler::gen
