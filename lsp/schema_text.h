// How the language server describes the schema's fields, properties, functions and hooks.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "grammar/ast/ast.h"
#include "grammar/ast/types.h"
#include "runtime/schema/schema.h"

namespace tranche::lsp {

// "mm/s", "integer", "boolean", "ratio (write 50% or 0.5)", "path_kind".
std::string type_text(schema::Type type, schema::Unit unit, schema::EnumType e);
// A value as rules write it: "0.4 mm", "20%", "2", "true".
std::string quantity(double v, schema::Unit unit);
std::string value_text(double v, const ast::Type& type);
// A property's type, stage, physical range, default and documentation (markdown).
std::string property_text(const schema::PropInfo& p);
// A built-in function's signature and what it gives; empty if there is no such function.
std::string function_text(std::string_view name);
// `before path` / `replace island`: when it runs.
std::string hook_text(const ast::Stmt& s);

struct FunctionDoc {
  std::string_view name, signature, doc;
};
const std::vector<FunctionDoc>& functions();

}  // namespace tranche::lsp
