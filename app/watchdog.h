// A hard stop for the command line: OpenCASCADE's general fuse checks its
// stop request only between its stages, and one intersection of two
// B-spline faces can run for minutes. If the preparation outlives its
// budget by far, the process prints one error line and exits 1. The
// command line arms it (`sizemesh batch` runs each model in a process of
// its own); the Python module does not, since it would end its host.
#pragma once

#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace sizemesh {

class Watchdog {
 public:
  // seconds <= 0: no watchdog.
  Watchdog(double seconds, std::string message);
  ~Watchdog();  // disarms it
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

 private:
  std::mutex mutex_;
  std::condition_variable done_;
  bool disarmed_ = false;
  std::thread thread_;
};

}  // namespace sizemesh
