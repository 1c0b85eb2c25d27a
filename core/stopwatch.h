// Wall time since a start: the one timer behind every stage time and every
// part of one (sizing steps, smoothing rounds, curves and faces).
#pragma once

#include <chrono>

namespace sizemesh {

class Stopwatch {
 public:
  // Seconds since the start (or the last lap).
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  // Seconds since the start (or the last lap), and a new start.
  double lap() {
    const double s = seconds();
    start_ = Clock::now();
    return s;
  }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_ = Clock::now();
};

}  // namespace sizemesh
