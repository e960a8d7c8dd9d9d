#include "base/memory.h"

#include <doctest/doctest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <new>

#if defined(__SANITIZE_ADDRESS__)
#define TRANCHE_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TRANCHE_ASAN 1
#endif
#endif

namespace {

// In a child process: load_unwinder(), then an address-space cap a little above what is mapped,
// all of it taken in ever smaller blocks, and a std::bad_alloc thrown out of std::call_once (its
// function runs inside glibc's pthread_once). Exit 0: the handler caught it. Returns the child's
// wait status.
int throw_with_no_memory_left() {
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    if (!tranche::load_unwinder()) ::_exit(3);
    unsigned long pages = 0;
    FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f || std::fscanf(f, "%lu", &pages) != 1) ::_exit(4);
    std::fclose(f);
    struct rlimit r {};
    if (::getrlimit(RLIMIT_AS, &r) != 0) ::_exit(4);
    r.rlim_cur = static_cast<rlim_t>(pages * static_cast<unsigned long>(::sysconf(_SC_PAGESIZE)) + (16ul << 20));
    if (r.rlim_max != RLIM_INFINITY && r.rlim_cur > r.rlim_max) ::_exit(4);
    if (::setrlimit(RLIMIT_AS, &r) != 0) ::_exit(4);
    size_t taken = 0;
    for (size_t size = 1 << 20; size >= 16; size /= 2)
      while (std::malloc(size)) taken += size;
    if (taken == 0) ::_exit(4);
    std::once_flag once;
    try {
      std::call_once(once, [] { throw std::bad_alloc(); });
    } catch (const std::bad_alloc&) {
      ::_exit(0);
    }
    ::_exit(5);
  }
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid) return -1;
  return status;
}

}  // namespace

// The hostile_limits flake: under `ulimit -v`, an allocation failing inside std::call_once (the
// travel comber's grids) aborted with "libgcc_s.so.1 must be installed for unwinding to work"
// when glibc's first dlopen of the unwinder found no memory left. Without load_unwinder() this
// child is killed by SIGABRT.
TEST_CASE("load_unwinder: with no memory left, a std::bad_alloc out of std::call_once reaches its handler") {
#if defined(TRANCHE_ASAN)
  MESSAGE("skipped: the sanitizers' allocator does not run out under an address-space cap");
#else
  const int status = throw_with_no_memory_left();
  REQUIRE(status != -1);
  INFO("wait status " << status << (WIFSIGNALED(status) ? ", killed by signal " : ", exit ")
                      << (WIFSIGNALED(status) ? WTERMSIG(status) : WEXITSTATUS(status)));
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
#endif
}
