#include "compiler/names.h"

#include <fmt/format.h>

#include <algorithm>

namespace tranche::compiler {

int edit_distance(std::string_view a, std::string_view b) {
  const size_t n = a.size(), m = b.size();
  std::vector<int> prev2(m + 1), prev(m + 1), cur(m + 1);
  for (size_t j = 0; j <= m; ++j) prev[j] = static_cast<int>(j);
  for (size_t i = 1; i <= n; ++i) {
    cur[0] = static_cast<int>(i);
    for (size_t j = 1; j <= m; ++j) {
      int cost = a[i - 1] != b[j - 1];
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        cur[j] = std::min(cur[j], prev2[j - 2] + 1);
    }
    prev2.swap(prev);
    prev.swap(cur);
  }
  return prev[m];
}

std::optional<std::string> suggest(std::string_view name, const std::vector<std::string>& candidates) {
  if (name.size() > 64) return std::nullopt;  // nobody misspells a name that long
  int limit = std::max<int>(1, static_cast<int>(name.size()) / 3);
  std::optional<std::string> best;
  int best_d = limit + 1;
  for (const auto& c : candidates) {
    if (c == name) continue;
    int d = edit_distance(name, c);
    // A candidate that merely extends the name (`index` → `layer.index`) is a good guess too.
    if (d > limit && c.size() > name.size() && c.ends_with(name) && c[c.size() - name.size() - 1] == '.')
      d = limit;
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

std::string quoted_list(const std::vector<std::string>& names, size_t limit) {
  std::string s;
  size_t n = std::min(names.size(), limit);
  for (size_t i = 0; i < n; ++i) {
    if (i) s += (i + 1 == n && n == names.size()) ? " or " : ", ";
    s += fmt::format("`{}`", names[i]);
  }
  if (n < names.size()) s += ", ...";
  return s;
}

}  // namespace tranche::compiler
