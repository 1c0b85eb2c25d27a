// Budgets for OpenCASCADE's long algorithms: a wall-clock deadline (the
// preparation's), and a progress indicator the general fuse's progress
// scopes ask whether to stop, which says yes once its budget of work is
// spent, so an attempt is abandoned for the next route instead of running
// for minutes. OpenCASCADE side: cad/ only.
#pragma once

#include <Message_ProgressIndicator.hxx>
#include <Message_ProgressRange.hxx>
#include <pthread.h>
#include <time.h>

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

// CPU seconds used by the thread that made it (asked from any thread): the
// work an algorithm has done on the thread that runs it, which a loaded
// machine does not inflate as it does wall time.
class ThreadClock {
 public:
  ThreadClock() { valid_ = pthread_getcpuclockid(pthread_self(), &id_) == 0; }
  double now() const {
    timespec t{};
    if (!valid_ || clock_gettime(id_, &t) != 0)
      return std::chrono::duration<double>(Deadline::Clock::now().time_since_epoch()).count();
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  }

 private:
  clockid_t id_{};
  bool valid_ = false;
};

// f(), its CPU seconds on this thread written to `worked` (returns what f returns).
template <class F>
auto timed(double& worked, const F& f) {
  const ThreadClock clock;
  const double start = clock.now();
  struct Stop {
    const ThreadClock& clock;
    double start;
    double& out;
    ~Stop() { out = clock.now() - start; }
  } stop{clock, start, worked};
  return f();
}

// How many times its budget in wall time an algorithm budgeted in work may
// take on a loaded machine before it is stopped all the same (a loaded
// 2-core machine runs about 3 times slower).
constexpr double kWallPerWork = 3.0;

// The preparation's budget in work: CPU seconds of the thread that made it
// (the one that runs the preparation), plus the work done for it elsewhere
// that every run does alike (add): the fuses in child processes, the
// repair's sewing trials on other threads (not those abandoned when another
// closed first: how far they got depends on timing). So which route each
// component takes depends on the work done, not on how loaded the machine
// is nor on the thread count (a wall-clock budget sent a component down
// another route, and gave another mesh, when a busy machine slowed the
// repair before it). Passed all the same after kWallPerWork times the
// budget in wall time.
class WorkBudget {
 public:
  explicit WorkBudget(double seconds) : budget_(std::max(0.0, seconds)), start_(clock_.now()), wall_(kWallPerWork * budget_) {}
  double spent() const { return clock_.now() - start_ + added_; }
  double remaining() const { return passed() ? 0.0 : std::max(0.0, budget_ - spent()); }
  bool passed() const { return spent() >= budget_ || wall_.passed(); }
  void add(double seconds) { added_ += std::max(0.0, seconds); }

 private:
  ThreadClock clock_;
  double budget_, start_, added_ = 0;
  Deadline wall_;
};

// Says "stop" to the algorithm it is passed to once it has worked `seconds`
// (CPU time of the thread that calls it, so that it does the same work, and
// comes to the same result, on an idle machine and on a loaded one; stopped
// all the same after kWallPerWork times that in wall time), or sooner once
// its own progress shows that it is far from ending in time: from a quarter
// of the budget on, the work so far over the share of the work done since the
// first report projects the whole run, and a projection beyond 2.5 times the
// budget stops it (an attempt that cannot end in time is abandoned for the
// next route while that still has time; the margin covers progress that is
// not even, which is the rule in OpenCASCADE's Booleans). Made on the thread
// that runs the algorithm; asked from several threads at once; shows nothing.
class DeadlineIndicator : public Message_ProgressIndicator {
 public:
  explicit DeadlineIndicator(double seconds)
      : budget_(std::max(0.0, seconds)),
        start_(clock_.now()),
        wall_end_(Deadline::Clock::now() +
                  std::chrono::duration_cast<Deadline::Clock::duration>(std::chrono::duration<double>(kWallPerWork * budget_))) {}

  Standard_Boolean UserBreak() override {
    if (stopped_) return true;
    const double position = GetPosition();
    double first = first_position_.load();
    if (first < 0) first_position_.compare_exchange_strong(first, position), first = first_position_.load();
    const double worked = clock_.now() - start_;
    if (worked >= budget_ || Deadline::Clock::now() >= wall_end_) return stopped_ = true;
    if (worked < 0.25 * budget_ || position <= first) return false;
    const double projected = worked * (1 - first) / (position - first);
    if (projected <= 2.5 * budget_) return false;
    if (bool no = false; projecting_.compare_exchange_strong(no, true)) projected_ = projected, done_ = position, at_ = worked;
    return stopped_ = true;
  }
  void Show(const Message_ProgressScope&, const Standard_Boolean) override {}

  // Why it said stop, as a verb phrase ("did not end within 12 s"), or empty.
  std::string why() const {
    if (!stopped_) return "";
    char line[160];
    if (projected_ > 0)
      std::snprintf(line, sizeof line, "was stopped %.0f%% through after %.1f s, on course for about %.0f s of its %.1f s",
                    100 * done_, at_, projected_, budget_);
    else
      std::snprintf(line, sizeof line, "did not end within %.1f s", budget_);
    return line;
  }

 private:
  ThreadClock clock_;
  double budget_, start_;
  Deadline::Clock::time_point wall_end_;
  std::atomic<double> first_position_{-1.0};
  std::atomic<bool> stopped_{false}, projecting_{false};
  double projected_ = 0, done_ = 0, at_ = 0;  // written once, by the first thread to project past the budget
};

}  // namespace sizemesh
