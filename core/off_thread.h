// Work handed to threads made for it, never run on the calling thread.
//
// OpenCASCADE's maps of shapes are hashed by the address of each shape's
// data, so the order they iterate in follows the order of the heap's
// allocations. Work whose shapes stay (the preparation's) is done on one
// thread; work only measured (trial sewings, validity checks) can run in
// parallel, provided it never runs on that thread: its heap then sees the
// same allocations on every run whatever the timing, and so does the mesh
// that follows. oneTBB's parallel_for may run tasks on the calling thread.
#pragma once

#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace sizemesh {

// f(0) .. f(n-1) on threads made for them, as many at once as the task
// arena allows (--threads), never on the calling thread; the first exception
// thrown is thrown again here once all have ended.
template <class F>
void off_this_thread(size_t n, const F& f) {
  const size_t k = std::min<size_t>(n, static_cast<size_t>(std::max(1, tbb::this_task_arena::max_concurrency())));
  std::atomic<size_t> next{0};
  std::mutex guard;
  std::exception_ptr failure;
  std::vector<std::thread> pool;
  for (size_t t = 0; t < k; ++t)
    pool.emplace_back([&] {
      for (size_t i; (i = next++) < n;) {
        try {
          f(i);
        } catch (...) {
          const std::lock_guard<std::mutex> lock(guard);
          if (!failure) failure = std::current_exception();
        }
      }
    });
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace sizemesh
