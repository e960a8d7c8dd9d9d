// The time limit of a fill-angle script's calls (--script-timeout): a watchdog thread that, when a
// call runs past its deadline, raises TimeoutError inside the script (PyThreadState_SetAsyncExc,
// from a helper thread that takes the GIL), so a loop in Python stops with a clear error. A call
// that cannot be interrupted that way (stuck in C code: time.sleep, a huge integer power) holds
// out; `grace` seconds later the watchdog prints its message, removes the run's temporary files
// and ends the process with exit status 1, rather than let the run hang.
// Only built with Python (TRANCHE_HAVE_PYTHON); used by python_script.cpp.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace tranche::geo {

class CallWatch {
 public:
  CallWatch(double timeout_s, double grace_s = 2);
  ~CallWatch();
  CallWatch(const CallWatch&) = delete;
  CallWatch& operator=(const CallWatch&) = delete;

  // Starts timing a call on this thread (which holds the GIL). `message` is what the process
  // prints if it must be ended.
  void arm(std::string message);
  // Ends the call (the GIL still held); true when it ran past the deadline. A TimeoutError the
  // watchdog sent that is still pending is cancelled.
  bool disarm();
  double timeout_s() const { return timeout_s_; }

  struct Shared;  // what the watchdog and its helpers share (they may outlive a call)

 private:
  void loop();

  double timeout_s_, grace_s_;
  std::shared_ptr<Shared> s_;
  std::thread thread_;
};

}  // namespace tranche::geo
