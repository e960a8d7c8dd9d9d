// Internal to compiler/: the checker's state while it walks a program. check_expr.cpp types
// expressions (fold.cpp folds constants), check_names.cpp resolves references, check_rules.cpp
// handles rules, check_body.cpp the statements of bodies, stages.cpp decides what each slot may
// read.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "grammar/ast/ast.h"
#include "grammar/ast/diagnostic.h"

namespace tranche::compiler {

// A `let` or a loop variable.
struct Local {
  std::string name;
  ast::Span span;
  ast::Type type;  // Int for range loops; Error for collection elements (they have fields)
  ast::Element element = ast::Element::None;
  int slot = -1;
  bool used = false;
  bool loop = false;
};

// Where the expression being checked sits.
struct ExprContext {
  enum class Where { Filter, Value, Body } where = Where::Filter;
  std::vector<Local>* locals = nullptr;  // in hook and replace bodies
};

// What a slot may read: fields known by `stage` (modifiers, replacement filters) and/or of
// levels up to `level` (hooks, replacement bodies).
struct Limit {
  std::optional<schema::Stage> stage;
  std::optional<schema::Stage> fields_until;  // fields known until then may be read (default: stage)
  std::optional<schema::Level> level;
  std::string what;                    // "`fill_angle` is decided per island, before any path exists"
  ast::Span site;                      // where the slot is written (a secondary label)
  std::optional<schema::PropId> prop;  // modifiers: same-stage reads become dependencies
};

// A read of one property by the modifier of another at the same stage.
struct Dependency {
  schema::PropId from, to;
  ast::Span at;
  const ast::Rule* rule;
};

struct FuncInfo;  // a built-in function (check_names.cpp)

// Shared by the checker's files (defined in check_rules.cpp).
// The level a name such as `layer` or `island` names, if any.
std::optional<schema::Level> level_named(std::string_view name);
// Whether `s` lies in a user's file (warnings are for those, not for the stdlib).
bool user_file(const ast::SourceMap& sources, const ast::Span& s);
// A statement kind as messages name it: "an assignment", "`before`/`after`", ...
std::string_view stmt_word(ast::StmtKind k);

class Checker {
 public:
  Checker(ast::Program& program, diag::Sink& sink)
      : program_(program), sources_(program.sources), sink_(sink) {}
  bool run();

  // Expressions (check_expr.cpp). `hint` names the enum expected, so that bare enum values
  // resolve (`path.kind == infill`, `seam = rear`).
  ast::Type expr(ast::Expr& e, ExprContext& ctx, schema::EnumType hint = schema::EnumType::None);
  // The expression as a value for `want` (a property's type): reports mismatches (E0202/E0203).
  bool assignable(ast::Expr& value, const ast::Type& want, std::string_view target,
                  const ast::Span& target_span);

 private:
  friend class StageChecker;
  // check_names.cpp
  ast::Type name(ast::Expr& e, ExprContext& ctx, schema::EnumType hint);
  ast::Type local_value(ast::Expr& e, Local& local);
  ast::Type misplaced_enum(ast::Expr& e, const schema::EnumInfo& info, schema::EnumType hint);
  ast::Type unknown_name(ast::Expr& e, ExprContext& ctx, schema::EnumType hint);
  ast::Type member(ast::Expr& e, ExprContext& ctx);
  ast::Type element_field(ast::Expr& e, Local& local);
  ast::Type level_field(ast::Expr& e);
  ast::Type unknown_level(ast::Expr& e, ExprContext& ctx);
  ast::Type layer_access(ast::Expr& e, ExprContext& ctx);
  ast::Type other_layer_field(ast::Expr& e, const ast::Span& object_span);
  ast::Type call(ast::Expr& e, ExprContext& ctx);
  bool call_arguments(ast::Expr& e, const FuncInfo& fn, const std::vector<ast::Type>& args);
  ast::Type call_result(ast::Expr& e, const FuncInfo& fn, const std::vector<ast::Type>& args);
  ast::Type property_ref(ast::Expr& e, schema::PropId id);
  Local* find_local(ExprContext& ctx, std::string_view name);
  // check_expr.cpp
  ast::Type binary(ast::Expr& e, ExprContext& ctx);
  ast::Type compare(ast::Expr& e, ExprContext& ctx);
  ast::Type in_set(ast::Expr& e, ExprContext& ctx);
  std::optional<ast::Type> text_compare(ast::Expr& e, ExprContext& ctx);
  bool text_operand(ast::Expr& text, const ast::Expr& name);
  bool names_value(const ast::Expr& e, ExprContext& ctx);
  ast::Type in_range(ast::Expr& e, ExprContext& ctx);
  ast::Type if_expr(ast::Expr& e, ExprContext& ctx, schema::EnumType hint);
  ast::Type quantifier(ast::Expr& e, ExprContext& ctx);
  ast::Type number(ast::Expr& e);
  bool same_units(const ast::Expr& a, const ast::Expr& b, const ast::Span& op, std::string_view verb);
  void fold(ast::Expr& e);

  // check_rules.cpp
  void rule(ast::Rule& r);
  void modifier(ast::Rule& r, ast::Stmt& s);
  void hook(ast::Rule& r, ast::Stmt& s, bool replace);
  void conjuncts(ast::Rule& r);
  // check_body.cpp: statements in hook and replacer bodies
  void statements(std::vector<ast::StmtPtr>& body, ast::Stmt& action, std::vector<Local>& locals,
                  int loop_depth, double loop_steps, bool& emitted);
  void statement(ast::Stmt& s, ast::Stmt& action, std::vector<Local>& locals, int loop_depth,
                 double loop_steps, bool& emitted);
  void loop(ast::Stmt& s, ast::Stmt& action, std::vector<Local>& locals, int loop_depth, double loop_steps,
            bool& emitted);
  Limit body_limit(const ast::Stmt& action) const;
  void if_statement(ast::Stmt& s, ast::Stmt& action, std::vector<Local>& locals, int loop_depth,
                    double loop_steps, bool& emitted, ExprContext& ctx, const Limit& limit);
  void alteration(ast::Stmt& s, ast::Stmt& action, int loop_depth, bool emitted, ExprContext& ctx,
                  const char* where);
  double range_loop(ast::Stmt& s, Local& var, ExprContext& ctx, double loop_steps);
  void collection_loop(ast::Stmt& s, ast::Stmt& action, Local& var);
  void move(ast::Stmt& s, ExprContext& ctx);
  void text(ast::Template& t, ExprContext& ctx);
  void placeholders(const ast::Template& t);  // check_values.cpp
  bool declare(std::vector<Local>& locals, Local local, ast::Stmt& action);
  void unused_locals(std::vector<Local>& locals, size_t from);

  // stages.cpp
  void require(const ast::Expr& e, const Limit& limit, const ast::Rule& r);
  void dependencies();
  Limit limit_for(const ast::Slot& slot, const ast::Rule& r) const;

  // Params (`param NAME = VALUE`): the value so far while the params are checked in cascade
  // order, then the final one (the last definition) while the rules are.
  struct ParamValue {
    ast::Type type;
    double value = 0;
    const ast::Param* first = nullptr;
  };
  void params();
  std::map<std::string, ParamValue> params_;

  ast::Program& program_;
  const ast::SourceMap& sources_;
  diag::Sink& sink_;
  void range(const ast::Expr& value, schema::PropId prop);
  ast::Rule* rule_ = nullptr;           // the rule being checked
  std::optional<ast::Unit> expected_unit_;  // of the value being checked, for unit suggestions
  // The variables of the quantifiers (`any(i in 1..3: ...)`) around the expression being checked.
  struct BoundVar {
    std::string name;
    ast::Span span;
    bool used = false;
  };
  std::vector<BoundVar> bound_;
  std::set<schema::PropId> rule_sets_;  // properties the current rule sets
  std::set<uint32_t> stage_reported_;   // offsets of reads already reported in this rule
  std::vector<Dependency> deps_;
};

// Human descriptions of stages, used in E03xx messages.
std::string decided_at(schema::Stage s);  // "decided per island, before any path exists"
std::string known_at(schema::Stage s);    // "known when a path is planned"
// A property value as written in rules: "0.1 mm/s", "100%" for ratios, "2" for plain numbers.
std::string format_quantity(double value, schema::Unit unit);

}  // namespace tranche::compiler
