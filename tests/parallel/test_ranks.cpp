// The message-passing building blocks on thread ranks: the tree merge absorbs every rank's
// data in rank order, the task farm runs each task once and stops handing out on request.
#include <gtest/gtest.h>

#include <algorithm>
#include <mutex>
#include <set>

#include "imunoise/parallel/ranks.hpp"
#include "imunoise/parallel/task_farm.hpp"
#include "parallel/thread_ranks.hpp"

namespace imunoise::test {
namespace {

TEST(TreeMerge, RankZeroAbsorbsEveryRankInOrder) {
  for (int size = 1; size <= 7; ++size) {
    parallel::Bytes at_root;
    const auto errors = run_ranks(size, [&](parallel::Ranks& ranks) {
      parallel::Bytes mine{static_cast<std::uint8_t>(ranks.rank())};
      parallel::tree_merge(
          ranks, [&] { return mine; },
          [&](const parallel::Bytes& theirs) { mine.insert(mine.end(), theirs.begin(), theirs.end()); });
      if (ranks.rank() == 0) at_root = mine;
    });
    for (const auto& e : errors) EXPECT_FALSE(e);
    ASSERT_EQ(at_root.size(), static_cast<std::size_t>(size)) << size << " ranks";
    for (int r = 0; r < size; ++r) EXPECT_EQ(at_root[static_cast<std::size_t>(r)], r) << size << " ranks";
  }
}

TEST(TaskFarm, EveryTaskRunsOnceAndReportsItsResult) {
  constexpr std::size_t kTasks = 11;
  for (int size = 1; size <= 4; ++size) {
    std::vector<int> seen(kTasks, 0);
    std::mutex m;
    std::set<std::size_t> ran;
    const auto errors = run_ranks(size, [&](parallel::Ranks& ranks) {
      parallel::run_task_farm(
          ranks, kTasks,
          [&](std::size_t i) {
            std::lock_guard lock(m);
            EXPECT_TRUE(ran.insert(i).second) << "task " << i << " ran twice";
            return parallel::Bytes{static_cast<std::uint8_t>(3 * i + 1)};
          },
          [&](std::size_t i, const parallel::Bytes& bytes) {
            EXPECT_EQ(ranks.rank(), 0);
            EXPECT_EQ(bytes, parallel::Bytes{static_cast<std::uint8_t>(3 * i + 1)});
            ++seen.at(i);
            return true;
          });
    });
    for (const auto& e : errors) EXPECT_FALSE(e);
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(kTasks)) << size << " ranks";
  }
}

TEST(TaskFarm, StopsHandingOutWhenAskedAndLetsRunningTasksReport) {
  constexpr std::size_t kTasks = 20;
  for (int size = 1; size <= 4; ++size) {
    std::size_t reported = 0;
    const auto errors = run_ranks(size, [&](parallel::Ranks& ranks) {
      parallel::run_task_farm(
          ranks, kTasks, [](std::size_t) { return parallel::Bytes{}; },
          [&](std::size_t, const parallel::Bytes&) {
            ++reported;
            return false;
          });
    });
    for (const auto& e : errors) EXPECT_FALSE(e);
    // One worker per rank is busy when the first result stops the hand-out.
    const std::size_t workers = size == 1 ? 1 : static_cast<std::size_t>(size - 1);
    EXPECT_GE(reported, 1u);
    EXPECT_LE(reported, workers) << size << " ranks";
  }
}

}  // namespace
}  // namespace imunoise::test
