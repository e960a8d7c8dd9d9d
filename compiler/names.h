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

}  // namespace tranche::compiler
