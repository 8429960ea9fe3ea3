// run_parts (<raykernel/parallel.hpp>), the one thread pool of the library, the Python module and the CLI:
// every part once, the lowest failing part's exception after every thread joined, the thread cap, and — in a
// child process whose address space is too small for the stacks asked for — no std::terminate when the
// system refuses threads (a regression: `render --threads 500` under `ulimit -v 4000000` aborted).
#include <raykernel/batch.hpp>
#include <raykernel/parallel.hpp>

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace raykernel {
namespace {

TEST(RunParts, EveryPartRunsExactlyOnce) {
  for (const std::size_t parts : {std::size_t{0}, std::size_t{1}, std::size_t{7}, std::size_t{1000}}) {
    for (const unsigned threads : {0u, 1u, 3u, 64u}) {
      std::vector<std::atomic<int>> runs(parts);
      const unsigned ran = run_parts(parts, threads, [&](std::size_t k) { ++runs[k]; });
      for (std::size_t k = 0; k < parts; ++k) EXPECT_EQ(runs[k].load(), 1) << "part " << k << " of " << parts;
      EXPECT_GE(ran, 1u);
      EXPECT_LE(ran, std::max<std::size_t>(parts, 1));
    }
  }
}

TEST(RunParts, RethrowsTheLowestFailingPartAfterEveryThreadJoined) {
  std::atomic<int> running{0};
  try {
    run_parts(64, 4, [&](std::size_t k) {
      ++running;
      if (k == 5 || k == 9) throw std::runtime_error("part " + std::to_string(k));
      std::this_thread::yield();
      --running;
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    // Parts 5 and 9 may both have run (on different threads); 5 is the lowest.
    const std::string what = e.what();
    EXPECT_TRUE(what == "part 5" || what == "part 9") << what;
  }
  EXPECT_LE(running.load(), 2) << "every part that did not throw has finished";
  // With one thread, parts run in order: the first failure is the lowest, and later parts never start.
  std::vector<int> order;
  EXPECT_THROW(run_parts(10, 1, [&](std::size_t k) {
                 order.push_back(static_cast<int>(k));
                 if (k == 3) throw std::logic_error("3");
               }),
               std::logic_error);
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3}));
}

TEST(RunParts, AskingForMoreThanMaxThreadsGetsMaxThreads) {
  EXPECT_EQ(thread_count(100000), max_threads);
  EXPECT_EQ(thread_count(max_threads + 1), max_threads);
  EXPECT_EQ(thread_count(3), 3u);
  EXPECT_GE(thread_count(0), 1u);
}

// Limits the address space to its current size plus `room` bytes (thread stacks of 8 MiB each).
bool limit_address_space(rlim_t room) {
  std::ifstream statm("/proc/self/statm");
  std::size_t pages = 0;
  statm >> pages;
  const rlim_t limit = static_cast<rlim_t>(pages) * static_cast<rlim_t>(sysconf(_SC_PAGESIZE)) + room;
  // Only the soft limits: the second call may need a larger one than the first (the first run's thread stacks
  // and malloc arenas stay mapped, more or fewer by timing), and a soft limit may rise up to the hard limit.
  rlimit stack{}, address_space{};
  if (getrlimit(RLIMIT_STACK, &stack) != 0 || getrlimit(RLIMIT_AS, &address_space) != 0) return false;
  stack.rlim_cur = rlim_t{8} << 20;
  if (stack.rlim_max != RLIM_INFINITY && stack.rlim_max < stack.rlim_cur) stack.rlim_cur = stack.rlim_max;
  address_space.rlim_cur = limit;
  if (address_space.rlim_max != RLIM_INFINITY && address_space.rlim_max < limit) return false;
  return pages > 0 && setrlimit(RLIMIT_STACK, &stack) == 0 && setrlimit(RLIMIT_AS, &address_space) == 0;
}

// The child's exit status: 0 when run_parts, asked for max_threads threads with room for about 20 stacks,
// ran every part on fewer threads, and the batch API (the same pool) answered 20 parts' worth of queries on
// the threads it got, the same answers as on one thread; 3 when the limit refused no thread (the test would
// prove nothing); 1 when a part was lost or an answer differs; 4 when the limit could not be set.
// std::terminate would be SIGABRT.
int child_under_address_space_limit() {
  // The batch: 20 parts of 2^14 queries (ray i from (i, 0, 0) along z, plane z = 1: hit at t = 1), answered
  // on one thread before the limit.
  const std::size_t n = std::size_t{20} << 14;
  std::vector<double> ox(n), zero(n, 0.0), one(n, 1.0);
  for (std::size_t i = 0; i < n; ++i) ox[i] = static_cast<double>(i);
  const RayBatch rays{ox, zero, zero, zero, zero, one};
  const PlaneBatch planes{zero, zero, one, zero, zero, one};
  std::vector<Relation> relation_one(n), relation_many(n);
  std::vector<double> t_one(n), t_many(n);
  intersect_batch(rays, planes, {relation_one, t_one}, {.threads = 1});

  if (!limit_address_space(rlim_t{160} << 20)) return 4;
  std::vector<std::atomic<int>> runs(10000);
  const unsigned ran = run_parts(runs.size(), max_threads, [&](std::size_t k) { ++runs[k]; });
  for (const std::atomic<int>& r : runs)
    if (r.load() != 1) return 1;
  if (ran >= max_threads) return 3;
  if (!limit_address_space(rlim_t{40} << 20)) return 4;  // room for about 5 of the batch's 20 threads
  intersect_batch(rays, planes, {relation_many, t_many}, {.threads = 20});
  return relation_one == relation_many && t_one == t_many ? 0 : 1;
}

TEST(RunParts, ThreadsTheSystemRefusesAreNoErrorAndNeverTerminate) {
  std::fflush(nullptr);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) _exit(child_under_address_space_limit());
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "the child died of signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  EXPECT_EQ(WEXITSTATUS(status), 0) << "3: no thread was refused, 1: a part was lost, 4: setrlimit failed";
}

}  // namespace
}  // namespace raykernel
