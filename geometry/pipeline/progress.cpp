#include "geometry/pipeline/progress.h"

#include <unistd.h>

#include <cstdio>

#include <fmt/format.h>

namespace tranche::pipeline {

Progress::Progress(bool enabled) : enabled_(enabled && isatty(STDERR_FILENO)) {}

void Progress::start(const std::string& stage, size_t total, const std::string& unit) {
  if (!enabled_) return;
  std::lock_guard lock(mu_);
  stage_ = stage;
  unit_ = unit;
  total_ = total;
  started_ = std::chrono::steady_clock::now();
  last_draw_ns_ = 0;
  draw(0);
}

void Progress::update(size_t done) {
  if (!enabled_) return;
  const int64_t now =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - started_)
          .count();
  int64_t last = last_draw_ns_.load(std::memory_order_relaxed);
  if (now - last < 100'000'000 && done < total_) return;
  if (!last_draw_ns_.compare_exchange_strong(last, now)) return;  // another thread draws
  std::unique_lock lock(mu_, std::try_to_lock);
  if (lock) draw(done);
}

void Progress::draw(size_t done) {
  if (total_ > 0)
    fmt::print(stderr, "\r\x1b[K{:<8} {}/{} {}", stage_, done, total_, unit_);
  else
    fmt::print(stderr, "\r\x1b[K{:<8} ...", stage_);
  std::fflush(stderr);
}

void Progress::finish(const std::string& detail) {
  if (!enabled_) return;
  std::lock_guard lock(mu_);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  fmt::print(stderr, "\r\x1b[K{:<8} {}{}{:.2f} s\n", stage_, detail, detail.empty() ? "" : "  ", s);
  std::fflush(stderr);
}

}  // namespace tranche::pipeline
