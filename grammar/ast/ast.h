// The rule-language AST. grammar/ builds it (the "syntax" fields); compiler/check.h annotates it
// in place (the "checked" fields), and codegen reads only checked programs. Shape:
//
//   Program
//     sources   every file read: the inputs, then each `use`d file at its first use
//     files     per file, its items (`use` and rules) as written
//     cascade   every rule in cascade order (each `use` expanded where it is written, once;
//               `--set` rules last). Later rules win, slot by slot.
//
//   Rule      filter (null = always) and actions. Checked:
//     index       position in the cascade
//     slots       one per action: the property, hook (level + before/after) or replacement it
//                 fills, the stage the slot is decided at, and its action
//     conjuncts   the filter split at top-level `and`, each with the stage and level it needs
//                 (so the VM can test each conjunct as early and as rarely as possible)
//
//   Expr      checked: `type` (kind, unit, enum type); `stage` (earliest stage it can be
//             evaluated) and `level` (innermost context level it reads); `constant` when it
//             folds. References carry `ref`:
//       Field         `layer.index`            field
//       OtherLayer    `layers[i].area`, `below.area`, `above.z`: field; other = Indexed (args[0]
//                     is the layer index), Below or Above
//       Property      `width` read in a rule that does not set it: prop (its decided value)
//       Inherited     `speed` read in a rule that sets `speed`: prop (the value earlier rules
//                     give it, i.e. the cascade without this rule)
//       Local         a `let` or an integer range loop variable: local (frame slot)
//       ElementField  `p.x` for `for p in path.points|path.pieces|layer.islands`: local (the
//                     loop variable's slot), element, and field (pieces, islands) or
//                     point_field (points)
//       EnumValue     `infill` where a `path_kind` is expected: enum_value (its index)
//       Bound         `i` in `any(i in 1..3: ...)`: local is the quantifier's depth (0 outermost)
//     Calls carry `func`. Number literals are already scaled (`50%` is 0.5).
//
//   Stmt      checked: Assign → prop; Hook/Replace → level; Let/For → local (slot in the
//             action's frame); For → loop kind (and range_lo/range_hi for ranges); Move options
//             → prop. Hook and Replace actions carry frame_size, the local slots they need.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "grammar/ast/source.h"
#include "grammar/ast/types.h"
#include "runtime/schema/schema.h"

namespace tranche::ast {

enum class ExprKind : uint8_t {
  Number,       // number: value (scaled by the unit spelling), unit_text as written
  Bool,         // boolean
  String,       // text: the raw token, str: its value; compared with a name field (`object.name == "lid"`)
  Name,         // text: a bare identifier (`speed`, `infill`, `x`)
  Member,       // text.member: `layer.index`, `below.area`, `p.x`
  LayerAccess,  // text[args[0]].member: `layers[layer.index - 2].area`
  Call,         // text(args...)
  Unary,        // op args[0]: Neg, Not
  Binary,       // args[0] op args[1]
  InRange,      // args[0] in args[1]..args[2] (inclusive)
  InSet,        // args[0] in (args[1], args[2], ...)
  If,           // if args[0] then args[1] else args[2]
  Quantifier,   // text(member in args[0]..args[1]: args[2]): `any` or `all` over an integer range
};

enum class Op : uint8_t { None, Neg, Not, Add, Sub, Mul, Div, Mod, Eq, Ne, Lt, Le, Gt, Ge, And, Or };

enum class RefKind : uint8_t { None, Field, OtherLayer, Property, Inherited, Local, ElementField, EnumValue, Bound };
enum class OtherLayer : uint8_t { Indexed, Below, Above };
enum class Func : uint8_t { Min, Max, Clamp, Abs, Round, Floor, Ceil, Sqrt, Sin, Cos, Tan, Atan2, Lerp };
// What a loop variable stands for.
enum class Element : uint8_t { None, Int, Point, Piece, Island };
enum class PointField : uint8_t { X, Y, Index };

struct Expr {
  ExprKind kind = ExprKind::Number;
  Span span;

  // Syntax.
  Op op = Op::None;
  double number = 0;
  bool integer_literal = false;  // written without `.`/exponent and without a unit
  std::string unit_text;         // Number: the unit as written ("mm/s", "%"), empty if none
  Span unit_span;
  bool boolean = false;
  std::string text;    // Name/Call/Member/LayerAccess: the first name; String: the raw token
  std::string str;     // String: the value, quotes removed and escapes resolved
  Span text_span;      // the first name; Unary/Binary/InRange/InSet: the operator
  std::string member;  // Member/LayerAccess: the name after `.`
  Span member_span;
  std::vector<std::unique_ptr<Expr>> args;
  uint16_t depth = 1;  // nodes on the longest path down from here (the parser bounds it)

  // Checked.
  Type type;
  RefKind ref = RefKind::None;
  schema::FieldId field{};
  schema::PropId prop{};
  OtherLayer other = OtherLayer::Indexed;
  int local = -1;
  Element element = Element::None;
  PointField point_field = PointField::X;
  int enum_value = -1;
  Func func = Func::Min;
  schema::Stage stage = schema::Stage::Print;
  schema::Level level = schema::Level::Print;
  std::optional<double> constant;
  bool from_param = false;  // reads a param: constant, but on purpose (no constant-condition lints)
};
using ExprPtr = std::unique_ptr<Expr>;

enum class StmtKind : uint8_t {
  Assign,   // name = value (a modifier; also the syntax of `move ... with`)
  Hook,     // before|after name [append] { body }
  Replace,  // replace name { body }
  Gcode,    // gcode "template"
  Comment,  // comment "template"
  Let,      // let name = value
  If,       // if value { body } else { else_body }
  For,      // for name in value { body } or for name in value..value2 { body }
  Move,     // move to (x, y) [travel|extrude] [with options]
  Default,
  Offset,  // offset value
  Reverse,
  Retract,  // retract the filament now (replacers); the next extrusion unretracts
};

enum class When : uint8_t { Before, After };
enum class LoopKind : uint8_t { Range, Points, Pieces, Islands };

// A `{expr}` or `{expr:.N}` inside a template, or a run of literal text (expr null).
struct TemplatePart {
  std::string text;  // literal text with `{{`/`}}` and escapes resolved
  ExprPtr expr;
  int decimals = -1;  // `:.N`; -1 = default formatting
  Span span;
};

struct Template {
  std::vector<TemplatePart> parts;
  Span span;
};

struct MoveOption {
  std::string name;
  Span name_span;
  ExprPtr value;
  schema::PropId prop{};  // checked
};

struct Stmt {
  StmtKind kind = StmtKind::Default;
  Span span;

  // Syntax.
  std::string name;  // Assign: property; Hook/Replace: level; Let/For: variable
  Span name_span;
  ExprPtr value;
  ExprPtr value2;  // For: the end of a range
  ExprPtr x, y;    // Move
  When when = When::Before;
  bool append = false;
  bool travel = false;  // Move
  std::vector<MoveOption> options;
  Template text;  // Gcode/Comment
  std::vector<std::unique_ptr<Stmt>> body, else_body;

  // Checked.
  schema::PropId prop{};
  schema::Level level = schema::Level::Print;
  int local = -1;
  LoopKind loop = LoopKind::Range;
  int64_t range_lo = 0, range_hi = -1;
  int frame_size = 0;
};
using StmtPtr = std::unique_ptr<Stmt>;

enum class SlotKind : uint8_t { Property, Hook, Replace };

struct Slot {
  SlotKind kind = SlotKind::Property;
  schema::PropId prop{};                       // Property
  schema::Level level = schema::Level::Print;  // Hook, Replace
  When when = When::Before;                    // Hook
  bool append = false;                         // Hook: adds to the hook instead of replacing it
  schema::Stage stage = schema::Stage::Print;  // when the slot is decided (hooks: at output time)
  const Stmt* action = nullptr;

  // A dense key: equal keys are the same slot of the cascade.
  uint32_t key() const;
  std::string describe() const;  // "`speed`", "`before path`", "`replace island`"
};

struct Conjunct {
  const Expr* expr = nullptr;
  schema::Stage stage = schema::Stage::Print;
  schema::Level level = schema::Level::Print;
};

struct Rule {
  Span span;  // the header: `rule "name" when ...` up to the `{`
  std::string name;
  bool has_name = false;
  bool from_on = false;   // written `on layer.start ...`: one Hook action
  bool from_set = false;  // `--set key=value`
  ExprPtr filter;
  std::vector<StmtPtr> actions;

  // Checked.
  int index = -1;
  std::vector<Slot> slots;
  std::vector<Conjunct> conjuncts;

  // `"first layers slow"`, or "the rule at file:line" when unnamed.
  std::string display(const SourceMap& sources) const;
};
using RulePtr = std::unique_ptr<Rule>;

// `param NAME = VALUE`: a named constant every rule of the program can read. Definitions later
// in the cascade (and `--set NAME=VALUE`, the last) override earlier ones, like rules do.
struct Param {
  Span span;  // the whole item
  std::string name;
  Span name_span;
  ExprPtr value;
  bool from_set = false;
  // Checked.
  Type type;
  std::optional<double> constant;  // its value (every param is a constant)
};
using ParamPtr = std::unique_ptr<Param>;

struct Use {
  Span span;
  std::string target;  // as written
  Span target_span;
  int file = -1;  // resolved file id; -1 if unresolved
};

struct Item {
  std::unique_ptr<Use> use;  // exactly one of use/rule/param
  RulePtr rule;
  ParamPtr param;
};

struct File {
  uint32_t id = 0;
  std::vector<Item> items;
};

struct Program {
  SourceMap sources;
  std::vector<File> files;
  std::vector<RulePtr> set_rules;  // `--set` rules, owned here
  std::vector<ParamPtr> set_params;  // `--set` of a param, owned here
  std::vector<Rule*> cascade;
  std::vector<Param*> params;  // every param definition in cascade order (`--set` ones last)
  // Every property, by stage, each after the same-stage properties its modifiers read
  // (`flow = width / 0.45 mm` puts `width` first): the order codegen decides them in.
  std::vector<schema::PropId> property_order;
  bool checked = false;  // true once the checker ran without errors
};

// Where a copied node lands: spans of the copy are in `file`, `offset` bytes and `line` lines
// further on (a part of a file parsed on its own, put back in place; columns do not change).
struct Relocation {
  uint32_t file = 0;
  uint32_t offset = 0;
  uint32_t line = 0;
  Span operator()(const Span& s) const;
};

// A deep copy of the syntax of an item (the checked fields are left unset), relocated.
Item clone(const Item& item, const Relocation& to);

// An indented tree of the checked AST, one node per line, for tests and `rulec check --dump-ast`.
std::string dump(const Program& program);

}  // namespace tranche::ast
