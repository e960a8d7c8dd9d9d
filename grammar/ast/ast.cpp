#include "grammar/ast/ast.h"

#include <fmt/format.h>

namespace tranche::ast {

uint32_t Slot::key() const {
  switch (kind) {
    case SlotKind::Property:
      return static_cast<uint32_t>(prop);
    case SlotKind::Hook:
      return 1000 + static_cast<uint32_t>(level) * 2 + static_cast<uint32_t>(when);
    case SlotKind::Replace:
      return 2000 + static_cast<uint32_t>(level);
  }
  return 0;
}

std::string Slot::describe() const {
  switch (kind) {
    case SlotKind::Property:
      return fmt::format("`{}`", schema::property(prop).name);
    case SlotKind::Hook:
      return fmt::format("`{} {}`", when == When::Before ? "before" : "after", schema::level_name(level));
    case SlotKind::Replace:
      return fmt::format("`replace {}`", schema::level_name(level));
  }
  return "?";
}

std::string Rule::display(const SourceMap& sources) const {
  if (from_set) return fmt::format("`{}`", name);
  if (has_name) return fmt::format("\"{}\"", name);
  std::string path = span.file < sources.size() ? sources.file(span.file).path : "?";
  return fmt::format("the rule at {}:{}", path, span.line);
}

namespace {

const char* op_name(Op op) {
  static const char* names[] = {"?",  "neg", "not", "+",  "-", "*",  "/",   "mod",
                                "==", "!=",  "<",   "<=", ">", ">=", "and", "or"};
  return names[static_cast<size_t>(op)];
}

const char* func_name(Func f) {
  static const char* names[] = {"min",  "max", "clamp", "abs", "round", "floor", "ceil",
                                "sqrt", "sin", "cos",   "tan", "atan2", "lerp"};
  return names[static_cast<size_t>(f)];
}

std::string type_name(const Type& t) {
  switch (t.kind) {
    case Kind::Error:
      return "error";
    case Kind::Int:
      return "int";
    case Kind::Number:
      return t.unit.plain() ? "num" : t.unit.name();
    case Kind::Bool:
      return "bool";
    case Kind::Enum:
      return std::string(schema::enum_info(t.enum_type).name);
    case Kind::Text:
      return "text";
  }
  return "?";
}

// A resolved name, member or layer access: what it refers to.
std::string ref_str(const Expr& e) {
  switch (e.ref) {
    case RefKind::Field:
      return std::string(schema::field(e.field).name);
    case RefKind::OtherLayer:
      return fmt::format("{}.{}",
                         e.other == OtherLayer::Below   ? "below"
                         : e.other == OtherLayer::Above ? "above"
                                                        : "layers[...]",
                         schema::field(e.field).name);
    case RefKind::Property:
      return fmt::format("prop {}", schema::property(e.prop).name);
    case RefKind::Inherited:
      return fmt::format("inherited {}", schema::property(e.prop).name);
    case RefKind::Local:
      return fmt::format("local#{}", e.local);
    case RefKind::ElementField:
      return fmt::format("local#{}.{}", e.local, e.member);
    case RefKind::EnumValue:
      return fmt::format("enum {}", e.text);
    case RefKind::Bound:
      return fmt::format("bound#{} {}", e.local, e.text);
    case RefKind::None:
      return e.member.empty() ? e.text : e.text + "." + e.member;
  }
  return {};
}

std::string expr_str(const Expr& e) {
  std::string head;
  switch (e.kind) {
    case ExprKind::Number:
      head = fmt::format("{}", e.number);
      break;
    case ExprKind::Bool:
      head = e.boolean ? "true" : "false";
      break;
    case ExprKind::String:
      head = "string";
      break;
    case ExprKind::Name:
    case ExprKind::Member:
    case ExprKind::LayerAccess:
      head = ref_str(e);
      break;
    case ExprKind::Call:
      head = func_name(e.func);
      break;
    case ExprKind::Unary:
    case ExprKind::Binary:
      head = op_name(e.op);
      break;
    case ExprKind::InRange:
      head = "in-range";
      break;
    case ExprKind::InSet:
      head = "in-set";
      break;
    case ExprKind::If:
      head = "if";
      break;
    case ExprKind::Quantifier:
      head = fmt::format("{} {}", e.text, e.member);
      break;
  }
  std::string s = head + ":" + type_name(e.type);
  if (e.constant && e.kind != ExprKind::Number) s += fmt::format("={}", *e.constant);
  bool show_args = e.kind != ExprKind::LayerAccess || e.ref != RefKind::OtherLayer || !e.args.empty();
  if (e.args.empty() || !show_args) return s;
  std::string out = "(";
  out += s;
  for (const auto& a : e.args) {
    out += ' ';
    out += expr_str(*a);
  }
  out += ')';
  return out;
}

void dump_stmts(std::string& out, const std::vector<StmtPtr>& stmts, int depth);

void dump_stmt(std::string& out, const Stmt& st, int depth) {
  std::string pad(static_cast<size_t>(depth) * 2, ' ');
  switch (st.kind) {
    case StmtKind::Assign:
      out += fmt::format("{}{} = {}\n", pad, st.name, expr_str(*st.value));
      break;
    case StmtKind::Hook:
      out += fmt::format("{}{} {}{} frame={}\n", pad, st.when == When::Before ? "before" : "after", st.name,
                         st.append ? " append" : "", st.frame_size);
      dump_stmts(out, st.body, depth + 1);
      break;
    case StmtKind::Replace:
      out += fmt::format("{}replace {} frame={}\n", pad, st.name, st.frame_size);
      dump_stmts(out, st.body, depth + 1);
      break;
    case StmtKind::Gcode:
    case StmtKind::Comment: {
      out += fmt::format("{}{}", pad, st.kind == StmtKind::Gcode ? "gcode" : "comment");
      for (const auto& p : st.text.parts) {
        if (p.expr)
          out += " {" + expr_str(*p.expr) + (p.decimals >= 0 ? fmt::format(":.{}", p.decimals) : "") + "}";
        else
          out += fmt::format(" {:?}", p.text);
      }
      out += "\n";
      break;
    }
    case StmtKind::Let:
      out += fmt::format("{}let local#{} = {}\n", pad, st.local, expr_str(*st.value));
      break;
    case StmtKind::If:
      out += fmt::format("{}if {}\n", pad, expr_str(*st.value));
      dump_stmts(out, st.body, depth + 1);
      if (!st.else_body.empty()) {
        out += pad + "else\n";
        dump_stmts(out, st.else_body, depth + 1);
      }
      break;
    case StmtKind::For: {
      static const char* loops[] = {"range", "path.points", "path.pieces", "layer.islands"};
      out += fmt::format("{}for local#{} in {}", pad, st.local, loops[static_cast<size_t>(st.loop)]);
      if (st.loop == LoopKind::Range) out += fmt::format(" {}..{}", st.range_lo, st.range_hi);
      out += "\n";
      dump_stmts(out, st.body, depth + 1);
      break;
    }
    case StmtKind::Move:
      out += fmt::format("{}move {} {}{}", pad, expr_str(*st.x), expr_str(*st.y), st.travel ? " travel" : "");
      for (const auto& o : st.options) out += fmt::format(" {}={}", o.name, expr_str(*o.value));
      out += "\n";
      break;
    case StmtKind::Default:
      out += pad + "default\n";
      break;
    case StmtKind::Offset:
      out += fmt::format("{}offset {}\n", pad, expr_str(*st.value));
      break;
    case StmtKind::Reverse:
      out += pad + "reverse\n";
      break;
    case StmtKind::Retract:
      out += pad + "retract\n";
      break;
  }
}

void dump_stmts(std::string& out, const std::vector<StmtPtr>& stmts, int depth) {
  for (const auto& s : stmts) dump_stmt(out, *s, depth);
}

}  // namespace

std::string dump(const Program& program) {
  std::string out;
  for (const Rule* r : program.cascade) {
    out += fmt::format("rule {} {}\n", r->index, r->display(program.sources));
    for (const auto& c : r->conjuncts)
      out += fmt::format("  when [{}] {}\n", schema::stage_name(c.stage), expr_str(*c.expr));
    for (const auto& s : r->slots) {
      out += fmt::format("  slot {} [{}]\n", s.describe(), schema::stage_name(s.stage));
      if (s.action) dump_stmt(out, *s.action, 2);
    }
  }
  return out;
}

}  // namespace tranche::ast
