// Progress of a run on stderr: one line per finished stage with its time and
// a counter of faces meshed, once the run has taken longer than about a
// second (quick runs stay silent). On a terminal the counter updates in
// place; otherwise it prints plain lines (every 10% of the faces). Nothing
// at all when disabled (-q). Also records each stage's wall time.
#pragma once

#include <chrono>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace sizemesh {

class Progress {
 public:
  // seconds: where each finished stage's wall time is appended.
  Progress(bool enabled, std::vector<std::pair<std::string, double>>& seconds);
  // The stage that just ended.
  void lap(const std::string& stage);
  // Faces meshed so far; safe to call from several threads.
  void faces(int done, int total);
  // Whether it prints progress at all (a run's verbosity).
  bool enabled() const { return enabled_; }

 private:
  using Clock = std::chrono::steady_clock;
  double since(Clock::time_point t) const { return std::chrono::duration<double>(Clock::now() - t).count(); }
  bool speaking() const { return enabled_ && since(start_) > kQuietSeconds; }

  static constexpr double kQuietSeconds = 1.0;
  bool enabled_, terminal_;
  std::vector<std::pair<std::string, double>>& seconds_;
  Clock::time_point start_ = Clock::now(), lap_ = start_;
  std::mutex mutex_;
  int last_tenth_ = 0;
  Clock::time_point last_print_ = start_;
  bool counter_shown_ = false;
};

}  // namespace sizemesh
