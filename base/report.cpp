#include "base/report.h"

namespace tranche {

void Report::warn(std::string code, std::string where, std::string message) {
  std::lock_guard lock(mu_);
  warnings_.push_back({std::move(where), std::move(message), std::move(code)});
}

std::vector<Warning> Report::warnings() const {
  std::lock_guard lock(mu_);
  return warnings_;
}

size_t Report::count(const std::string& code) const {
  std::lock_guard lock(mu_);
  size_t n = 0;
  for (const auto& w : warnings_) n += (w.code == code);
  return n;
}

size_t Report::size() const {
  std::lock_guard lock(mu_);
  return warnings_.size();
}

}  // namespace tranche
