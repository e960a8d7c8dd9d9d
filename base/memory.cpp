#include "base/memory.h"

#include <fmt/format.h>
#include <sys/resource.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>

#if defined(__GLIBC__)
#include <execinfo.h>
#endif

namespace tranche {
namespace {
std::atomic<uint64_t> g_limit_mb{0};
}

uint64_t peak_memory_bytes() {
  struct rusage u {};
  if (::getrusage(RUSAGE_SELF, &u) != 0) return 0;
  return static_cast<uint64_t>(u.ru_maxrss) * 1024;  // kilobytes on Linux
}

Error out_of_memory(const std::string& where, const std::string& doing, const std::string& advice) {
  // Formatting needs a little memory; a failure here still ends in a short message.
  try {
    const uint64_t limit = g_limit_mb.load();
    return Error{where, fmt::format("out of memory while {} (peak {} MB{}); {}", doing, peak_memory_bytes() >> 20,
                                    limit ? fmt::format(", --max-memory {} MB", limit) : std::string(), advice)};
  } catch (...) {
    return Error{where, "out of memory"};
  }
}

Status set_memory_limit(uint64_t mb) {
  struct rlimit r {};
  if (::getrlimit(RLIMIT_AS, &r) != 0) return Error{"--max-memory", std::strerror(errno)};
  const uint64_t bytes = mb << 20;
  if (r.rlim_max != RLIM_INFINITY && bytes > r.rlim_max)
    return Error{"--max-memory", fmt::format("{} MB is above this system's hard limit ({} MB)", mb, r.rlim_max >> 20)};
  r.rlim_cur = static_cast<rlim_t>(bytes);
  if (::setrlimit(RLIMIT_AS, &r) != 0) return Error{"--max-memory", std::strerror(errno)};
  g_limit_mb = mb;
  return ok_status();
}

uint64_t memory_limit_mb() { return g_limit_mb.load(); }

bool load_unwinder() {
#if defined(__GLIBC__)
  // backtrace() loads the unwinder (glibc's documented way to have it loaded ahead of time); it
  // returns no frame when it could not. Then the path that failed, once, so that glibc's
  // forwarders in pthread_once's frame are bound too (older glibc binds those separately). A throw
  // without an unwinder would abort, hence only after backtrace() succeeded.
  void* frame[1];
  if (::backtrace(frame, 1) < 1) return false;
  std::once_flag once;
  try {
    std::call_once(once, [] { throw 0; });
  } catch (int) {
  }
#endif
  return true;
}

}  // namespace tranche
