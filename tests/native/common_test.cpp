#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

#include "common/thread_team.h"

using tvf::ThreadTeam;

// Every task runs exactly once, whether there are fewer parts than threads, as many, or more (the caller
// then runs the rest itself), and the caller sees what the tasks wrote.
TEST(ThreadTeam, RunsEachTaskOnceAndWaitsForAll) {
  ThreadTeam& team = ThreadTeam::shared();
  for (int parts = 1; parts <= ThreadTeam::kHelpers + 3; ++parts)
    for (int round = 0; round < 50; ++round) {
      std::vector<int> ran(parts, 0);
      team.run(parts, [&](int k) { ++ran[k]; });
      for (int k = 0; k < parts; ++k) ASSERT_EQ(ran[k], 1) << parts << " parts, task " << k;
    }
}

TEST(ThreadTeam, TasksRunOnHelperThreadsWhereThereAreAny) {
  std::vector<std::thread::id> ids(ThreadTeam::kHelpers + 1);
  ThreadTeam::shared().run(static_cast<int>(ids.size()), [&](int k) { ids[k] = std::this_thread::get_id(); });
  EXPECT_EQ(ids[0], std::this_thread::get_id());
  for (size_t k = 1; k < ids.size(); ++k) {
    EXPECT_NE(ids[k], std::this_thread::get_id()) << "task " << k;
    for (size_t j = 0; j < k; ++j) EXPECT_NE(ids[k], ids[j]) << "tasks " << j << " and " << k;
  }
}

// Two callers at once: the one that finds the helpers busy runs its tasks itself; both get all their tasks
// done and neither waits for the other's.
TEST(ThreadTeam, ConcurrentCallersBothFinish) {
  std::atomic<int> total{0};
  const auto caller = [&] {
    for (int round = 0; round < 200; ++round)
      ThreadTeam::shared().run(3, [&](int) { total.fetch_add(1, std::memory_order_relaxed); });
  };
  std::thread other(caller);
  caller();
  other.join();
  EXPECT_EQ(total.load(), 2 * 200 * 3);
}
