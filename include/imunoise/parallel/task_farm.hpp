#pragma once
// Independent tasks of unequal cost (one file each) over the ranks: rank 0 hands the task
// indexes out one at a time to ranks 1..P-1 as they become free, so a long task does not hold
// up a queue of short ones, and gives each result to its caller. On one rank, rank 0 does
// every task itself in order.
#include <cstddef>
#include <functional>

#include "imunoise/parallel/ranks.hpp"

namespace imunoise::parallel {

/// `work(i)` computes task i's result (on a worker rank, or on rank 0 when alone);
/// `on_result(i, bytes)` receives it on rank 0, in completion order, and returns false to stop
/// handing out new tasks (those already running still report). Returns on every rank when all
/// handed-out tasks have reported; workers are told to stop with an empty task message.
void run_task_farm(Ranks& ranks, std::size_t n_tasks, const std::function<Bytes(std::size_t)>& work,
                   const std::function<bool(std::size_t, const Bytes&)>& on_result);

}  // namespace imunoise::parallel
