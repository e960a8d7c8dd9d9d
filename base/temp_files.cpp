#include "base/temp_files.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>

namespace tranche::temp_files {
namespace {

// A slot is free (0), being filled or emptied (1), or holds a path the handler may unlink (2).
struct Slot {
  std::atomic<int> state{0};
  char path[4096];
};
constexpr int kSlots = 32;
Slot g_slots[kSlots];

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGXFSZ, SIGABRT};

void on_signal(int sig) {
  const int saved = errno;
  unlink_all();
  // Die of the same signal, as without the handler: the default action, re-raised. The signal is
  // blocked while the handler runs, so it is delivered as soon as the handler returns.
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  sigaction(sig, &dfl, nullptr);
  raise(sig);
  errno = saved;
}

// Installs the handler for each signal still at its default (checked at every registration, so
// that a signal set back to its default later is covered too; the calls are cheap).
void install() {
  static std::mutex mu;
  std::lock_guard lock(mu);
  for (int sig : kSignals) {
    struct sigaction old {};
    if (sigaction(sig, nullptr, &old) != 0 || (old.sa_flags & SA_SIGINFO) || old.sa_handler != SIG_DFL) continue;
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    for (int other : kSignals) sigaddset(&sa.sa_mask, other);  // one cleanup at a time
    sa.sa_flags = SA_RESTART;
    sigaction(sig, &sa, nullptr);
  }
}

}  // namespace

int add(const char* path) {
  const size_t n = std::strlen(path);
  if (n >= sizeof g_slots[0].path) return -1;
  install();
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!g_slots[i].state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(g_slots[i].path, path, n + 1);
    g_slots[i].state.store(2);
    return i;
  }
  return -1;
}

void remove(int slot) {
  if (slot < 0 || slot >= kSlots) return;
  g_slots[slot].state.store(1);
  g_slots[slot].path[0] = '\0';
  g_slots[slot].state.store(0);
}

void unlink_all() noexcept {
  for (Slot& s : g_slots)
    if (s.state.load() == 2) ::unlink(s.path);
}

}  // namespace tranche::temp_files
