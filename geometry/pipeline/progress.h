// Progress on stderr for long runs: one line per stage, updated in place ("slice  312/750
// layers"), finished with the stage's time. Silent when disabled (--quiet, or stderr is not a
// terminal), so logs and pipes never see carriage returns.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace tranche::pipeline {

class Progress {
 public:
  // Enabled only when `enabled` and stderr is a terminal.
  explicit Progress(bool enabled);

  // Starts a stage; `total` > 0 shows "done/total unit" as update() is called.
  void start(const std::string& stage, size_t total = 0, const std::string& unit = "layers");
  // Thread-safe; redraws at most every 100 ms.
  void update(size_t done);
  // Ends the stage's line with `detail` and the time the stage took.
  void finish(const std::string& detail = {});
  bool enabled() const { return enabled_; }

 private:
  void draw(size_t done);

  bool enabled_;
  std::string stage_, unit_;
  size_t total_ = 0;
  std::chrono::steady_clock::time_point started_;
  std::atomic<int64_t> last_draw_ns_{0};
  std::mutex mu_;
};

}  // namespace tranche::pipeline
