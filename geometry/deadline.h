// A wall-clock budget for OpenCASCADE's long algorithms (the general fuse,
// sewing): their progress scopes ask the indicator whether to stop, and this
// one says yes once the budget is spent, so an attempt is abandoned for the
// next route instead of running for minutes. OpenCASCADE side: geometry/ only.
#pragma once

#include <Message_ProgressIndicator.hxx>
#include <Message_ProgressRange.hxx>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <string>

namespace sizemesh {

class Deadline {
 public:
  using Clock = std::chrono::steady_clock;
  explicit Deadline(double seconds)
      : end_(Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds))) {}
  double remaining() const { return std::max(0.0, std::chrono::duration<double>(end_ - Clock::now()).count()); }
  bool passed() const { return Clock::now() >= end_; }
  Clock::time_point end() const { return end_; }

 private:
  Clock::time_point end_;
};

// Says "stop" to the algorithm it is passed to once `end` has passed, or
// sooner once the algorithm's own progress shows that it is far from ending
// in time: from a quarter of the budget on, the time so far over the share
// of the work done since the first report projects the whole run, and a
// projection beyond 2.5 times the budget stops it (an attempt that cannot end
// in time is abandoned for the next route while that still has time; the
// margin covers progress that is not even, which is the rule in OpenCASCADE's
// Booleans). Asked from several threads at once; shows nothing.
class DeadlineIndicator : public Message_ProgressIndicator {
 public:
  explicit DeadlineIndicator(Deadline::Clock::time_point end) : start_(Deadline::Clock::now()), end_(end) {}

  Standard_Boolean UserBreak() override {
    if (stopped_) return true;
    const auto now = Deadline::Clock::now();
    const double position = GetPosition();
    double first = first_position_.load();
    if (first < 0) first_position_.compare_exchange_strong(first, position), first = first_position_.load();
    if (now >= end_) return stopped_ = true;
    const double elapsed = seconds(now - start_), budget = seconds(end_ - start_);
    if (elapsed < 0.25 * budget || position <= first) return false;
    const double projected = elapsed * (1 - first) / (position - first);
    if (projected <= 2.5 * budget) return false;
    if (bool no = false; projecting_.compare_exchange_strong(no, true)) projected_ = projected, done_ = position, at_ = elapsed;
    return stopped_ = true;
  }
  void Show(const Message_ProgressScope&, const Standard_Boolean) override {}

  // Why it said stop, as a verb phrase ("did not end within 12 s"), or empty.
  std::string why() const {
    if (!stopped_) return "";
    char line[160];
    if (projected_ > 0)
      std::snprintf(line, sizeof line, "was stopped %.0f%% through after %.1f s, on course for about %.0f s of its %.1f s",
                    100 * done_, at_, projected_, seconds(end_ - start_));
    else
      std::snprintf(line, sizeof line, "did not end within %.1f s", seconds(end_ - start_));
    return line;
  }

 private:
  static double seconds(Deadline::Clock::duration d) { return std::chrono::duration<double>(d).count(); }
  Deadline::Clock::time_point start_, end_;
  std::atomic<double> first_position_{-1.0};
  std::atomic<bool> stopped_{false}, projecting_{false};
  double projected_ = 0, done_ = 0, at_ = 0;  // written once, by the first thread to project past the budget
};

}  // namespace sizemesh
