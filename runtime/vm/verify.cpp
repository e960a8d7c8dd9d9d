#include "runtime/vm/verify.h"

#include <fmt/format.h>

#include <cmath>
#include <string_view>
#include <unordered_map>

namespace tranche::vm {

namespace {


const char* kind_name(ChunkKind k) {
  switch (k) {
    case ChunkKind::Test: return "test";
    case ChunkKind::Value: return "value";
    case ChunkKind::Hook: return "hook";
    case ChunkKind::Replace: return "replace";
  }
  return "?";
}

int move_options(uint16_t flags) {
  return ((flags & kMoveSpeed) ? 1 : 0) + ((flags & kMoveFlow) ? 1 : 0) + ((flags & kMoveWidth) ? 1 : 0);
}

class Verifier {
 public:
  explicit Verifier(const Program& p) : p_(p) {}

  Status run() {
    if (p_.code.size() > kMaxCode) return fail("code", fmt::format("{} instructions (at most {})", p_.code.size(), kMaxCode));
    if (p_.consts.size() > kMaxConsts) return fail("constants", "too many constants");
    if (p_.strings.size() > kMaxStrings) return fail("strings", "too many strings");
    if (p_.rules.size() > kMaxRules) return fail("rules", "too many rules");
    for (size_t i = 0; i < p_.consts.size(); ++i)
      if (!std::isfinite(p_.consts[i])) return fail(fmt::format("constant {}", i), "not a finite number");
    for (size_t i = 0; i < p_.strings.size(); ++i)
      if (p_.strings[i].size() > kMaxStringBytes) return fail(fmt::format("string {}", i), "longer than 1 MiB");
    // A name matches the index of its text (RuleSet::text_index): each text is there once.
    std::unordered_map<std::string_view, size_t> seen;
    for (size_t i = 0; i < p_.strings.size(); ++i)
      if (auto [it, fresh] = seen.emplace(p_.strings[i], i); !fresh)
        return fail(fmt::format("string {}", i), fmt::format("repeats string {}", it->second));
    for (uint32_t c = 0; c < p_.chunks.size(); ++c)
      if (Status s = chunk(c); !s) return s;
    for (size_t i = 0; i < p_.conjuncts.size(); ++i) {
      const auto& cj = p_.conjuncts[i];
      if (cj.chunk >= p_.chunks.size() || p_.chunks[cj.chunk].kind != ChunkKind::Test)
        return fail(fmt::format("conjunct {}", i), "does not name a test chunk");
      if (static_cast<int>(cj.level) >= schema::kLevelCount) return fail(fmt::format("conjunct {}", i), "bad level");
    }
    for (size_t i = 0; i < p_.rules.size(); ++i) {
      const auto& r = p_.rules[i];
      if (uint64_t(r.first) + r.count > p_.conjuncts.size())
        return fail(fmt::format("rule {}", i), "conjuncts out of range");
    }
    for (int q = 0; q < schema::kPropCount; ++q)
      if (Status s = slot(p_.props[static_cast<size_t>(q)], ChunkKind::Value,
                          fmt::format("property {}", schema::properties()[static_cast<size_t>(q)].name));
          !s)
        return s;
    for (int l = 0; l < schema::kLevelCount; ++l) {
      auto lv = static_cast<schema::Level>(l);
      for (int w = 0; w < 2; ++w) {
        const auto& hook = p_.hooks[static_cast<size_t>(l)][static_cast<size_t>(w)];
        if (lv == schema::Level::Piece && !hook.empty()) return fail("hooks", "there is no hook on pieces");
        if (Status s = slot(hook, ChunkKind::Hook,
                            fmt::format("{} {}", w == 0 ? "before" : "after", schema::level_name(lv)));
            !s)
          return s;
      }
      const auto& rep = p_.replace[static_cast<size_t>(l)];
      if (lv != schema::Level::Island && lv != schema::Level::Path && !rep.empty())
        return fail("replacers", fmt::format("{} cannot be replaced", schema::level_name(lv)));
      if (Status s = slot(rep, ChunkKind::Replace, fmt::format("replace {}", schema::level_name(lv))); !s) return s;
      for (const auto& c : rep)
        if (c.append) return fail("replacers", "a replacement cannot be appended");
    }
    if (Status s = order(); !s) return s;
    return debug();
  }

 private:
  Status fail(const std::string& where, const std::string& what) const {
    return Error{"bundle", fmt::format("{}: {}", where, what)};
  }

  Status chunk(uint32_t ci) {
    const Chunk& ch = p_.chunks[ci];
    std::string where = fmt::format("chunk {}", ci);
    if (static_cast<int>(ch.kind) > static_cast<int>(ChunkKind::Replace)) return fail(where, "unknown kind");
    if (ch.size == 0 || ch.size > kMaxChunkSize || uint64_t(ch.start) + ch.size > p_.code.size())
      return fail(where, "code range out of bounds");
    if (ch.regs == 0 || ch.regs > 256) return fail(where, fmt::format("{} registers (1 to 256)", ch.regs));
    for (uint32_t i = 0; i < ch.size; ++i) {
      const Instr& in = p_.code[ch.start + i];
      std::string at = fmt::format("{}, instruction {}", where, i);
      if (in.op >= kOpCount) return fail(at, fmt::format("unknown opcode {}", in.op));
      const OpInfo& info = op_info(in.code());
      bool allowed = info.cls == OpClass::Expr ||
                     (info.cls == OpClass::Stmt && (ch.kind == ChunkKind::Hook || ch.kind == ChunkKind::Replace)) ||
                     (info.cls == OpClass::Repl && ch.kind == ChunkKind::Replace);
      if (info.cls == OpClass::Term) {
        Op op = in.code();
        bool body = ch.kind == ChunkKind::Hook || ch.kind == ChunkKind::Replace;
        allowed = body ? op == Op::Halt : op != Op::Halt;
      }
      if (!allowed) return fail(at, fmt::format("`{}` is not allowed in a {} chunk", info.mnemonic, kind_name(ch.kind)));
      uint16_t ops[4] = {in.a, in.b, in.c, in.d};
      Operand kinds[4] = {info.a, info.b, info.c, info.d};
      for (int k = 0; k < 4; ++k)
        if (Status s = operand(ch, in, kinds[k], ops[k], at, "ABCD"[k]); !s) return s;
      if (in.code() == Op::MoveTo && move_options(in.c) > 0 && in.d + move_options(in.c) > ch.regs)
        return fail(at, "move options out of the chunk's registers");
    }
    if (op_info(p_.code[ch.start + ch.size - 1].code()).cls != OpClass::Term)
      return fail(where, "does not end with a return or halt");
    return ok_status();
  }

  Status operand(const Chunk& ch, const Instr& in, Operand k, uint16_t v, const std::string& at, char name) {
    auto bad = [&](const std::string& what) { return fail(at, fmt::format("operand {}: {}", name, what)); };
    switch (k) {
      case Operand::None:
        if (v != 0) return bad("must be 0");
        break;
      case Operand::Reg:
        if (v >= ch.regs) return bad(fmt::format("register {} out of range (chunk has {})", v, ch.regs));
        break;
      case Operand::Const:
        if (v >= p_.consts.size()) return bad(fmt::format("constant {} out of range", v));
        break;
      case Operand::Field:
        if (v >= schema::kFieldCount) return bad(fmt::format("field {} out of range", v));
        break;
      case Operand::Prop:
        if (v >= schema::kPropCount) return bad(fmt::format("property {} out of range", v));
        break;
      case Operand::Jump:
        if (v >= ch.size) return bad(fmt::format("jump target {} outside the chunk", v));
        break;
      case Operand::String:
        if (v >= p_.strings.size()) return bad(fmt::format("string {} out of range", v));
        break;
      case Operand::Rule:
        if (v > p_.rules.size()) return bad(fmt::format("rule {} out of range", v));
        break;
      case Operand::Enum:
        if (v == 0 || v >= schema::enums().size()) return bad(fmt::format("enum type {} out of range", v));
        break;
      case Operand::Coll:
        if (v > static_cast<uint16_t>(Coll::Islands)) return bad("unknown collection");
        break;
      case Operand::Member: {
        auto coll = static_cast<Coll>(in.c);
        if (coll == Coll::Points ? v > kPointIndex : v >= schema::kFieldCount) return bad("unknown member");
        break;
      }
      case Operand::Decimals:
        if (v > 12 && v != kDefaultDecimals) return bad("decimals out of range");
        break;
      case Operand::LayerOffset:
        if (v != 0 && v != 2) return bad("layer offset must be 0 (below) or 2 (above)");
        break;
      case Operand::MoveFlags:
        if (v > 15) return bad("unknown move flags");
        break;
    }
    return ok_status();
  }

  Status slot(const Candidates& cands, ChunkKind kind, const std::string& where) const {
    for (size_t i = 0; i < cands.size(); ++i) {
      const Candidate& c = cands[i];
      if (c.rule >= p_.rules.size()) return fail(where, "candidate names no rule");
      if (c.chunk >= p_.chunks.size() || p_.chunks[c.chunk].kind != kind)
        return fail(where, fmt::format("candidate's chunk is not a {} chunk", kind_name(kind)));
      if (i > 0 && c.rule > cands[i - 1].rule) return fail(where, "candidates not in descending rule order");
      if (kind == ChunkKind::Value && c.append) return fail(where, "a property cannot be appended");
    }
    return ok_status();
  }

  Status order() const {
    if (p_.property_order.size() != static_cast<size_t>(schema::kPropCount))
      return fail("property order", "must list every property once");
    std::vector<bool> seen(static_cast<size_t>(schema::kPropCount));
    schema::Stage last = schema::Stage::Print;
    for (auto id : p_.property_order) {
      auto i = static_cast<size_t>(id);
      if (i >= seen.size() || seen[i]) return fail("property order", "must list every property once");
      seen[i] = true;
      auto st = schema::property(id).stage;
      if (st < last) return fail("property order", "must go stage by stage");
      last = st;
    }
    return ok_status();
  }

  Status debug() const {
    const Debug& d = p_.debug;
    if (d.empty()) return ok_status();
    if (d.instr_loc.size() != p_.code.size()) return fail("debug", "one location per instruction expected");
    if (d.rule_names.size() != p_.rules.size() || d.rule_loc.size() != p_.rules.size())
      return fail("debug", "one name and location per rule expected");
    if (d.conj_text.size() != p_.conjuncts.size() || d.conj_loc.size() != p_.conjuncts.size())
      return fail("debug", "one text and location per conjunct expected");
    for (const auto& l : d.locs)
      if (l.file >= d.files.size()) return fail("debug", "location in an unknown file");
    auto loc_ok = [&](uint32_t i) { return i < d.locs.size(); };
    for (uint32_t i : d.instr_loc)
      if (!loc_ok(i)) return fail("debug", "instruction location out of range");
    for (uint32_t i : d.rule_loc)
      if (!loc_ok(i)) return fail("debug", "rule location out of range");
    for (uint32_t i : d.conj_loc)
      if (!loc_ok(i)) return fail("debug", "conjunct location out of range");
    return ok_status();
  }

  const Program& p_;
};

}  // namespace

Status verify(const Program& program) { return Verifier(program).run(); }

namespace {

std::string num(double v) { return fmt::format("{:g}", v); }

std::string operand_text(const Program& p, Operand k, uint16_t v, const Instr& in) {
  switch (k) {
    case Operand::None: return {};
    case Operand::Reg: return fmt::format("r{}", v);
    case Operand::Const: return v < p.consts.size() ? fmt::format("K{}({})", v, num(p.consts[v])) : fmt::format("K{}", v);
    case Operand::Field:
      return v < schema::kFieldCount ? std::string(schema::fields()[v].name) : fmt::format("field{}", v);
    case Operand::Prop:
      return v < schema::kPropCount ? std::string(schema::properties()[v].name) : fmt::format("prop{}", v);
    case Operand::Jump: return fmt::format("->{}", v);
    case Operand::String: {
      if (v >= p.strings.size()) return fmt::format("S{}", v);
      std::string s;
      for (char c : p.strings[v]) {
        if (c == '\n') s += "\\n";
        else if (c == '"' || c == '\\') s += '\\', s += c;
        else s += c;
      }
      return fmt::format("\"{}\"", s);
    }
    case Operand::Rule: return fmt::format("rule{}", v);
    case Operand::Enum:
      return v < schema::enums().size() ? std::string(schema::enums()[v].name) : fmt::format("enum{}", v);
    case Operand::Coll: return v == 0 ? "points" : v == 1 ? "pieces" : v == 2 ? "islands" : "?";
    case Operand::Member:
      if (in.c == static_cast<uint16_t>(Coll::Points)) return v == 0 ? ".x" : v == 1 ? ".y" : ".index";
      return v < schema::kFieldCount ? fmt::format(".{}", schema::fields()[v].name) : "?";
    case Operand::Decimals: return v == kDefaultDecimals ? ":default" : fmt::format(":.{}", v);
    case Operand::LayerOffset: return v == 0 ? "below" : "above";
    case Operand::MoveFlags: {
      std::string s = (v & kMoveTravel) ? "travel" : "extrude";
      if (v & kMoveSpeed) s += "+speed";
      if (v & kMoveFlow) s += "+flow";
      if (v & kMoveWidth) s += "+width";
      return s;
    }
  }
  return "?";
}

}  // namespace

std::string instruction_location(const Program& p, uint32_t instr) {
  const Debug& d = p.debug;
  if (instr >= d.instr_loc.size() || d.instr_loc[instr] >= d.locs.size()) return {};
  const Loc& l = d.locs[d.instr_loc[instr]];
  if (l.line == 0) return {};
  return fmt::format("{}:{}:{}", l.file < d.files.size() ? d.files[l.file] : "?", l.line, l.col);
}

std::string disassemble_chunk(const Program& p, uint32_t ci) {
  std::string out;
  if (ci >= p.chunks.size()) return out;
  const Chunk& ch = p.chunks[ci];
  for (uint32_t i = 0; i < ch.size && ch.start + i < p.code.size(); ++i) {
    const Instr& in = p.code[ch.start + i];
    if (in.op >= kOpCount) {
      out += fmt::format("{:4}  ??? {}\n", i, in.op);
      continue;
    }
    const OpInfo& info = op_info(in.code());
    std::string line = fmt::format("{:4}  {:<10}", i, info.mnemonic);
    uint16_t ops[4] = {in.a, in.b, in.c, in.d};
    Operand kinds[4] = {info.a, info.b, info.c, info.d};
    bool first = true;
    for (int k = 0; k < 4; ++k) {
      if (kinds[k] == Operand::None) continue;
      line += first ? " " : ", ";
      line += operand_text(p, kinds[k], ops[k], in);
      first = false;
    }
    std::string where = instruction_location(p, ch.start + i);
    if (!where.empty()) {
      if (line.size() < 48) line.resize(48, ' ');
      line += " ; " + where;
    }
    out += line + "\n";
  }
  return out;
}

std::string disassemble(const Program& p) {
  std::string out;
  out += fmt::format("; {} rules, {} chunks, {} instructions, {} constants, {} strings{}\n", p.rules.size(),
                     p.chunks.size(), p.code.size(), p.consts.size(), p.strings.size(),
                     p.debug.empty() ? "" : ", debug information");
  auto rule_name = [&](uint32_t r) {
    return r < p.debug.rule_names.size() ? fmt::format("rule{} {}", r, p.debug.rule_names[r]) : fmt::format("rule{}", r);
  };
  out += "\n; rules (cascade order) and their filters' conjuncts\n";
  for (uint32_t r = 0; r < p.rules.size(); ++r) {
    const Rule& rule = p.rules[r];
    out += fmt::format("{}:", rule_name(r));
    if (rule.count == 0) out += " always";
    for (uint32_t k = 0; k < rule.count; ++k) {
      uint32_t cj = rule.first + k;
      if (cj >= p.conjuncts.size()) break;
      out += fmt::format(" [chunk{} per {}", p.conjuncts[cj].chunk, schema::level_name(p.conjuncts[cj].level));
      if (cj < p.debug.conj_text.size()) out += ": " + p.debug.conj_text[cj];
      out += "]";
    }
    out += "\n";
  }
  auto list = [&](const std::string& slot, const Candidates& cands) {
    if (cands.empty()) return;
    out += fmt::format("{:<24}", slot);
    for (const auto& c : cands) out += fmt::format(" rule{}/chunk{}{}", c.rule, c.chunk, c.append ? "+" : "");
    out += "\n";
  };
  out += "\n; slots: candidates, last rule first\n";
  for (auto id : p.property_order) list(std::string(schema::property(id).name), p.props[static_cast<size_t>(id)]);
  for (int l = 0; l < schema::kLevelCount; ++l) {
    auto name = schema::level_name(static_cast<schema::Level>(l));
    list(fmt::format("before {}", name), p.hooks[static_cast<size_t>(l)][0]);
    list(fmt::format("after {}", name), p.hooks[static_cast<size_t>(l)][1]);
    list(fmt::format("replace {}", name), p.replace[static_cast<size_t>(l)]);
  }
  for (uint32_t c = 0; c < p.chunks.size(); ++c) {
    const Chunk& ch = p.chunks[c];
    out += fmt::format("\nchunk{} ({}, {} registers):\n", c, kind_name(ch.kind), ch.regs);
    out += disassemble_chunk(p, c);
  }
  return out;
}

}  // namespace tranche::vm
