#include "core/child_process.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <oneapi/tbb/global_control.h>

#include <atomic>
#include <new>
#include <chrono>
#include <filesystem>
#include <thread>

namespace sizemesh {

std::string child_result_path() {
  static std::atomic<int> counter{0};
  std::error_code ec;
  const auto dir = std::filesystem::temp_directory_path(ec);
  return (dir / ("sizemesh-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".child")).string();
}

ChildOutcome run_in_child(const std::function<bool(const std::string& path, bool threads)>& work, double seconds,
                          const std::string& path) {
  // oneTBB ends its workers only when nothing else holds the scheduler (no
  // live task arena, no other user in the process); otherwise the child
  // works on one thread.
  tbb::task_scheduler_handle scheduler{tbb::attach{}};
  const bool threads = tbb::finalize(scheduler, std::nothrow);
  const pid_t pid = ::fork();
  if (pid < 0) return ChildOutcome::NoChild;
  if (pid == 0) {
    bool ok = false;
    try {
      ok = work(path, threads);
    } catch (...) {
      ok = false;
    }
    ::_exit(ok ? 0 : 1);  // no destructors, no atexit handlers of the parent's
  }
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  for (auto pause = std::chrono::microseconds(200);; pause = std::min(pause * 2, std::chrono::microseconds(20000))) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0) return ChildOutcome::Failed;
    if (std::chrono::steady_clock::now() >= end) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return ChildOutcome::TimedOut;
    }
    std::this_thread::sleep_for(pause);
  }
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? ChildOutcome::Done : ChildOutcome::Failed;
}

}  // namespace sizemesh
