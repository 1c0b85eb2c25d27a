// The preparation's budget of work (cad/deadline.h): it counts CPU seconds
// of the thread that made it and the work added for it, not wall time, so a
// thread that waits spends nothing of it, and a loaded machine takes the
// same routes through the union as an idle one.
#include <catch2/catch.hpp>

#include <chrono>
#include <thread>

#include "cad/deadline.h"

using namespace sizemesh;

TEST_CASE("a budget of work: waiting spends none of it, working and adding work spend it") {
  WorkBudget b(1.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  CHECK(b.spent() < 0.05);
  CHECK_FALSE(b.passed());
  // Work on this thread: about 0.2 s of CPU (bounded by work, not by time).
  const ThreadClock clock;
  const double start = clock.now();
  volatile double x = 0;
  while (clock.now() - start < 0.2) x = x + 1;
  CHECK(b.spent() >= 0.2);
  CHECK(b.remaining() <= 0.8);
  b.add(0.5);  // a fuse in a child process
  CHECK(b.spent() >= 0.7);
  b.add(0.5);
  CHECK(b.passed());
  CHECK(b.remaining() == 0);
  // Work on another thread is not this thread's.
  WorkBudget c(1.0);
  std::thread other([] {
    const ThreadClock own;
    const double s = own.now();
    volatile double y = 0;
    while (own.now() - s < 0.2) y = y + 1;
  });
  other.join();
  CHECK(c.spent() < 0.05);
}
