#pragma once
// Minimal fork-join over independent work items. Each item writes only its own output slot,
// so results never depend on how many threads ran or in which order they took items.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace imunoise::detail {

inline unsigned resolve_threads(unsigned requested) {
  if (requested != 0) return requested;
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware == 0 ? 1 : hardware;
}

/// Calls fn(i) for every i in [0, n_items), on up to `threads` threads (0 = all cores).
template <class Fn>
void parallel_for(std::size_t n_items, unsigned threads, Fn&& fn) {
  const std::size_t workers = std::min<std::size_t>(resolve_threads(threads), n_items);
  if (workers <= 1) {
    for (std::size_t i = 0; i < n_items; ++i) fn(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t i = next.fetch_add(1); i < n_items; i = next.fetch_add(1)) fn(i);
  };
  std::vector<std::jthread> pool;
  pool.reserve(workers - 1);
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
}

}  // namespace imunoise::detail
