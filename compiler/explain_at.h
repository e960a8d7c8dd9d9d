// The context of `rulec explain --at "..."`: fields of the element (`path.kind=infill`), fields
// of other layers (`below.area=30mm2`, `above.z=0.6`, `layers[3].z=0.8`, held in a LayerTable
// bound to the context, as the slicer binds its own) and property values below the rules
// (`speed=60`).
#pragma once

#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "base/result.h"
#include "runtime/context/context.h"

namespace tranche::compiler {

struct ExplainAt {
  ctx::Context context;  // bound to `table` (do not copy an ExplainAt: the binding would dangle)
  ctx::LayerTable table;
  std::set<schema::FieldId> given;                       // the element's fields
  std::map<std::pair<long, schema::FieldId>, double> other;  // (layer index, field) of other layers
  std::vector<std::pair<schema::PropId, double>> props;  // below the rules, in order
  // Name fields as given (`object.name=lid`); the context holds each one's index among the rules'
  // texts, as when slicing (resolve_texts).
  std::map<schema::FieldId, std::string> texts;

  ExplainAt() = default;
  ExplainAt(const ExplainAt&) = delete;
  ExplainAt& operator=(const ExplainAt&) = delete;
  // "layer.index = 3; below.area = 30 mm2; speed = 60 mm/s (below the rules)", or "(nothing given)".
  std::string text() const;
  // How the user would name layer `index`'s field: "below.area", "above.z", "layers[3].z".
  std::string layer_field_name(long index, schema::FieldId field) const;
};

// A field's value as written: "3", "30 mm2", "outer_perimeter", "true".
std::string field_text(schema::FieldId field, double value);

// Parses `at` (comma-separated `name=value`) into `out`. Errors name the item and say what to write.
Status parse_explain_at(const std::string& at, ExplainAt& out);

// Sets each name field of `at` to its text's index among `rules`' texts (-1: none compares with it).
template <class Rules>
void resolve_texts(ExplainAt& at, const Rules& rules) {
  for (const auto& [f, text] : at.texts) at.context.set(f, rules.text_index(text));
}

}  // namespace tranche::compiler
