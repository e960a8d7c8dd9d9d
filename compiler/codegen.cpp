#include "compiler/codegen.h"

#include <cmath>
#include <numbers>

#include "compiler/generator.h"

namespace tranche::compiler::gen {

vm::Program Generator::run() {
  if (ast_.cascade.size() > vm::kMaxRules) throw CodegenLimit{"more than 65535 rules"};
  if (options_.debug) {
    for (size_t f = 0; f < ast_.sources.size(); ++f)
      p_.debug.files.push_back(ast_.sources.file(static_cast<uint32_t>(f)).path);
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

uint32_t Generator::test_chunk(const Expr& e) {
  begin(0);
  span_ = e.span;
  Label fail;
  cond(e, false, fail);
  emit(VOp::RetK, 0, konst(1));
  place(fail);
  emit(VOp::RetK, 0, konst(0));
  return end(vm::ChunkKind::Test);
}

uint32_t Generator::value_chunk(const Expr& e) {
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

uint32_t Generator::body_chunk(const Stmt& action, vm::ChunkKind kind) {
  begin(action.frame_size);
  action_ = &action;
  span_ = action.span;
  statements(action.body);
  span_ = action.span;
  emit(VOp::Halt);
  return end(kind);
}

}  // namespace tranche::compiler::gen

namespace tranche::compiler {

Result<vm::Program> generate(const ast::Program& program, const CodegenOptions& options) {
  if (!program.checked) return Error{"rules", "the rules have errors: nothing to compile"};
  try {
    gen::Generator g(program, options);
    return g.run();
  } catch (const gen::CodegenLimit& l) {
    return Error{"rules", l.message};
  }
}

}  // namespace tranche::compiler
