// Size query counters: one cache line per thread, written only by its owner,
// summed when asked.
#include <algorithm>

#include "sizing/size_query_face.h"

namespace sizemesh {

using size_query_detail::kOwnedSlots;

namespace {
int thread_ordinal() {
  static std::atomic<int> next{0};
  thread_local const int id = next.fetch_add(1, std::memory_order_relaxed);
  return id;
}
}  // namespace

void QueryStats::add(const QueryStats& o) {
  queries += o.queries;
  visited += o.visited;
  max_visited = std::max(max_visited, o.max_visited);
  fallbacks += o.fallbacks;
  outside += o.outside;
}

void SizeQuery::count(const QueryStats& one) const {
  const int id = thread_ordinal();
  constexpr auto rel = std::memory_order_relaxed;
  if (id < kOwnedSlots) {
    StatSlot& s = slots_[id];
    s.queries.store(s.queries.load(rel) + one.queries, rel);
    s.visited.store(s.visited.load(rel) + one.visited, rel);
    if (one.max_visited > s.max_visited.load(rel)) s.max_visited.store(one.max_visited, rel);
    if (one.fallbacks) s.fallbacks.store(s.fallbacks.load(rel) + one.fallbacks, rel);
    if (one.outside) s.outside.store(s.outside.load(rel) + one.outside, rel);
    return;
  }
  StatSlot& s = slots_[kOwnedSlots];
  s.queries.fetch_add(one.queries, rel);
  s.visited.fetch_add(one.visited, rel);
  uint64_t m = s.max_visited.load(rel);
  while (one.max_visited > m && !s.max_visited.compare_exchange_weak(m, one.max_visited, rel)) {
  }
  s.fallbacks.fetch_add(one.fallbacks, rel);
  s.outside.fetch_add(one.outside, rel);
}

QueryStats SizeQuery::stats() const {
  QueryStats total;
  constexpr auto rel = std::memory_order_relaxed;
  for (int i = 0; i <= kOwnedSlots; ++i) {
    const StatSlot& s = slots_[i];
    QueryStats one;
    one.queries = s.queries.load(rel);
    one.visited = s.visited.load(rel);
    one.max_visited = s.max_visited.load(rel);
    one.fallbacks = s.fallbacks.load(rel);
    one.outside = s.outside.load(rel);
    total.add(one);
  }
  return total;
}

void SizeQuery::reset_stats() {
  constexpr auto rel = std::memory_order_relaxed;
  for (int i = 0; i <= kOwnedSlots; ++i) {
    StatSlot& s = slots_[i];
    s.queries.store(0, rel);
    s.visited.store(0, rel);
    s.max_visited.store(0, rel);
    s.fallbacks.store(0, rel);
    s.outside.store(0, rel);
  }
}

}  // namespace sizemesh
