// Work that may not end, run in a child process with a wall-clock limit.
//
// OpenCASCADE's general fuse asks whether to stop only between its stages;
// one intersection of two B-spline faces can run for minutes. Run in a child
// (fork), it can be ended at its limit like any process, and the parent goes
// on with the next route: nothing it computed is lost and no thread is left
// running. The child shares the parent's memory as it was at the fork (copy
// on write) and hands its result back through a file. Kernel-free.
#pragma once

#include <functional>
#include <string>

namespace sizemesh {

enum class ChildOutcome { Done, Failed, TimedOut, NoChild };

// Runs `work(path, threads)` in a child process that must write its result
// to `path` and return true, within `seconds`; the parent then reads `path`
// (removed by the caller). NoChild: fork failed (the caller may run the work
// itself). `threads` is true when the parent's oneTBB workers were ended
// before the fork, so the child may start its own (a fork copies only the
// calling thread: workers left running would be waited for forever).
ChildOutcome run_in_child(const std::function<bool(const std::string& path, bool threads)>& work, double seconds,
                          const std::string& path);

// A scratch file name unique to this process and call.
std::string child_result_path();

}  // namespace sizemesh
