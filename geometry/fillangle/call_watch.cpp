#include "geometry/fillangle/call_watch.h"

#if TRANCHE_HAVE_PYTHON
#include <Python.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>

#include "base/temp_files.h"

namespace tranche::geo {

using Clock = std::chrono::steady_clock;

struct CallWatch::Shared {
  std::mutex mu;
  std::condition_variable cv;
  bool stop = false;
  bool armed = false;
  bool fired = false;
  uint64_t generation = 0;
  unsigned long thread_id = 0;
  Clock::time_point deadline;
  std::string message;
};

namespace {

// Raises TimeoutError in the script's thread, unless its call ended meanwhile. Runs on its own
// thread: taking the GIL may wait for as long as the script holds it.
void interrupt(std::shared_ptr<CallWatch::Shared> s, uint64_t generation) {
  PyGILState_STATE gil = PyGILState_Ensure();
  {
    std::lock_guard lock(s->mu);
    if (s->armed && s->generation == generation) PyThreadState_SetAsyncExc(s->thread_id, PyExc_TimeoutError);
  }
  PyGILState_Release(gil);
}

}  // namespace

CallWatch::CallWatch(double timeout_s, double grace_s)
    : timeout_s_(timeout_s), grace_s_(grace_s), s_(std::make_shared<Shared>()), thread_([this] { loop(); }) {}

CallWatch::~CallWatch() {
  {
    std::lock_guard lock(s_->mu);
    s_->stop = true;
  }
  s_->cv.notify_all();
  thread_.join();
}

void CallWatch::arm(std::string message) {
  {
    std::lock_guard lock(s_->mu);
    s_->armed = true;
    s_->fired = false;
    ++s_->generation;
    s_->thread_id = PyThread_get_thread_ident();
    s_->deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s_));
    s_->message = std::move(message);
  }
  s_->cv.notify_all();
}

bool CallWatch::disarm() {
  std::lock_guard lock(s_->mu);
  s_->armed = false;
  if (s_->fired) PyThreadState_SetAsyncExc(s_->thread_id, nullptr);  // a TimeoutError not raised yet
  return s_->fired;
}

void CallWatch::loop() {
  std::unique_lock lock(s_->mu);
  while (!s_->stop) {
    if (!s_->armed) {
      s_->cv.wait(lock);
      continue;
    }
    const uint64_t generation = s_->generation;
    if (s_->cv.wait_until(lock, s_->deadline, [&] { return s_->stop || !s_->armed || s_->generation != generation; }))
      continue;
    s_->fired = true;
    std::thread(interrupt, s_, generation).detach();
    const auto grace = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(grace_s_));
    if (s_->cv.wait_for(lock, grace, [&] { return s_->stop || !s_->armed || s_->generation != generation; }))
      continue;
    // Not interruptible: end the run rather than hang (the message names the call and the limit).
    std::fprintf(stderr, "error: %s\n", s_->message.c_str());
    temp_files::unlink_all();
    ::_exit(1);
  }
}

}  // namespace tranche::geo

#endif
