// Warnings collected while slicing: every stage reports what it repaired or ignored, with a
// location, instead of silently dropping it. Thread-safe: layers run in parallel.
#pragma once

#include <mutex>
#include <string>
#include <vector>

namespace tranche {

struct Warning {
  std::string where;    // "model.stl:12", "layer 7 at (3.20, 4.10) mm", "triangle 40"
  std::string message;  // lowercase, no trailing period
  std::string code;     // short stable tag, e.g. "open-loop", "stl-normal"; used by --strict and tests
};

class Report {
 public:
  void warn(std::string code, std::string where, std::string message);
  std::vector<Warning> warnings() const;  // in report order (sorted by where within a parallel stage is the caller's job)
  size_t count(const std::string& code) const;
  size_t size() const;
  bool empty() const { return size() == 0; }

 private:
  mutable std::mutex mu_;
  std::vector<Warning> warnings_;
};

}  // namespace tranche
