// A wall-clock budget for OpenCASCADE's long algorithms (the general fuse,
// sewing): their progress scopes ask the indicator whether to stop, and this
// one says yes once the budget is spent, so an attempt is abandoned for the
// next route instead of running for minutes. OpenCASCADE side: geometry/ only.
#pragma once

#include <Message_ProgressIndicator.hxx>
#include <Message_ProgressRange.hxx>

#include <algorithm>
#include <chrono>

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

// Says "stop" to the algorithm it is passed to once `end` has passed; shows nothing.
class DeadlineIndicator : public Message_ProgressIndicator {
 public:
  explicit DeadlineIndicator(Deadline::Clock::time_point end) : end_(end) {}
  Standard_Boolean UserBreak() override { return Deadline::Clock::now() >= end_; }
  void Show(const Message_ProgressScope&, const Standard_Boolean) override {}

 private:
  Deadline::Clock::time_point end_;
};

}  // namespace sizemesh
