// "Did you mean": the closest candidate to a misspelt name, by edit distance.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tranche::compiler {

// Levenshtein distance (insertions, deletions, substitutions; a swap of two neighbours counts one).
int edit_distance(std::string_view a, std::string_view b);

// The best candidate within a distance that grows with the name's length (1 for short names,
// up to a third of the length), or nothing. Ties go to the earlier candidate.
std::optional<std::string> suggest(std::string_view name, const std::vector<std::string>& candidates);

// "`a`, `b` or `c`"; at most `limit` names, then "...".
std::string quoted_list(const std::vector<std::string>& names, size_t limit = 8);

// A name users carry over from another slicer (a placeholder, a setting, a feature name), and
// what it is called here. `whose` says where it comes from: "PrusaSlicer's", "Cura's"...
struct Foreign {
  std::string_view ours;
  std::string_view whose;
};
// Placeholders and variables of PrusaSlicer, OrcaSlicer, Cura and Klipper that read the print
// (`layer_z`, `layer_nr`, `first_layer_temperature_0`: an extruder suffix `_N` is ignored):
// ours is a field or a property to read (`layer.z`, `nozzle_temp`).
std::optional<Foreign> foreign_value(std::string_view name);
// Settings of other slicers (`temperature`, `fill_density`, `wall_line_count`): ours is a property.
std::optional<Foreign> foreign_property(std::string_view name);
// Other names of a field of `level` (`path.type`, `layer.number`): ours is the field's full name.
std::optional<std::string_view> field_synonym(std::string_view level, std::string_view member);
// Other names of an enum value (`perimeter`, `top_surface`): ours is a value of enum `enum_name`.
std::optional<std::string_view> enum_synonym(std::string_view enum_name, std::string_view value);

}  // namespace tranche::compiler
