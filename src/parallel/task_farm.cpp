#include "imunoise/parallel/task_farm.hpp"

#include <cstring>

namespace imunoise::parallel {
namespace {

constexpr int kTaskTag = 31;
constexpr int kResultTag = 32;

// A task is its index as 8 bytes; an empty message tells the worker to stop. A result is the
// index followed by the work's bytes.
Bytes index_bytes(std::size_t index) {
  Bytes bytes(8);
  const auto i = static_cast<std::uint64_t>(index);
  std::memcpy(bytes.data(), &i, 8);
  return bytes;
}

std::size_t index_of(const Bytes& bytes) {
  std::uint64_t i = 0;
  std::memcpy(&i, bytes.data(), 8);
  return static_cast<std::size_t>(i);
}

void serve(Ranks& ranks, const std::function<Bytes(std::size_t)>& work) {
  for (;;) {
    const Bytes task = ranks.receive(0, kTaskTag);
    if (task.size() != 8) return;
    const std::size_t index = index_of(task);
    Bytes result = index_bytes(index);
    const Bytes done = work(index);
    result.insert(result.end(), done.begin(), done.end());
    ranks.send(0, kResultTag, result);
  }
}

void hand_out(Ranks& ranks, std::size_t n_tasks, const std::function<bool(std::size_t, const Bytes&)>& on_result) {
  std::size_t next = 0;
  int busy = 0;
  bool go_on = true;
  for (int r = 1; r < ranks.size(); ++r) {
    if (next < n_tasks) {
      ranks.send(r, kTaskTag, index_bytes(next++));
      ++busy;
    } else {
      ranks.send(r, kTaskTag, {});
    }
  }
  while (busy > 0) {
    int from = 0;
    const Bytes result = ranks.receive(-1, kResultTag, &from);
    --busy;
    const std::size_t index = index_of(result);
    go_on = on_result(index, Bytes(result.begin() + 8, result.end())) && go_on;
    if (go_on && next < n_tasks) {
      ranks.send(from, kTaskTag, index_bytes(next++));
      ++busy;
    } else {
      ranks.send(from, kTaskTag, {});
    }
  }
}

}  // namespace

void run_task_farm(Ranks& ranks, std::size_t n_tasks, const std::function<Bytes(std::size_t)>& work,
                   const std::function<bool(std::size_t, const Bytes&)>& on_result) {
  if (ranks.size() == 1) {
    for (std::size_t i = 0; i < n_tasks; ++i) {
      if (!on_result(i, work(i))) return;
    }
    return;
  }
  if (ranks.rank() == 0) {
    hand_out(ranks, n_tasks, on_result);
  } else {
    serve(ranks, work);
  }
}

}  // namespace imunoise::parallel
