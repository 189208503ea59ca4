#include "parallax/core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace parallax {
namespace {

TEST(Parallel, EveryItemOnceInChunksOfAtMostTheGrain) {
  for (int threads : {0, 1, 2, 3}) {
    for (int64_t count : {0, 1, 7, 64, 1000}) {
      std::vector<std::atomic<int>> seen(static_cast<size_t>(count));
      std::atomic<bool> oversized{false};
      parallelFor(count, threads, 7, [&](int64_t begin, int64_t end) {
        if (end - begin > 7 || end <= begin) oversized = true;
        for (int64_t i = begin; i < end; ++i) ++seen[size_t(i)];
      });
      EXPECT_FALSE(oversized) << threads << " threads, " << count << " items";
      for (int64_t i = 0; i < count; ++i) ASSERT_EQ(seen[size_t(i)], 1) << i;
    }
  }
}

// Terms whose floating-point sum depends on the order: the parallel sum must be the serial
// sum in index order, bit for bit, for every thread count and grain.
TEST(Parallel, SumAddsTheTermsInIndexOrder) {
  const auto term = [](int64_t i) {
    return (i % 3 == 0 ? 1e16 : 1.0) * (i % 2 ? -1.0 : 1.0) + 0.1 * double(i);
  };
  for (int64_t count : {0, 1, 5, 1000}) {
    double serial = 0;
    for (int64_t i = 0; i < count; ++i) serial += term(i);
    for (int threads : {0, 1, 2, 3})
      for (int64_t grain : {1, 7, 64})
        EXPECT_EQ(parallelSum(count, threads, grain, term), serial)
            << count << " terms, " << threads << " threads, grain " << grain;
  }
}

// Two tasks that each wait (up to 10 s) for the other to start: both see the other only if
// they run at the same time; run one after the other, the first gives up and says so.
template <class Run>
int tasksThatMetTheOther(const Run& run) {
  std::atomic<int> arrived{0}, met{0};
  const auto task = [&] {
    ++arrived;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (arrived < 2 && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
    met += arrived == 2;
  };
  run(task);
  return met;
}

TEST(Parallel, UsesMoreThanOneWorkerWhenAsked) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one core";
  EXPECT_EQ(tasksThatMetTheOther(
                [](const auto& task) { parallelFor(2, 2, 1, [&](int64_t, int64_t) { task(); }); }),
            2);
  EXPECT_EQ(tasksThatMetTheOther([](const auto& task) { parallelInvoke(2, task, task); }), 2);
}

TEST(Parallel, RethrowsAChunksException) {
  EXPECT_THROW(parallelFor(100, 2, 1,
                           [](int64_t begin, int64_t) {
                             if (begin == 57) throw std::runtime_error("chunk 57");
                           }),
               std::runtime_error);
  const auto nothing = [] {};
  const auto throwSecond = [] { throw std::runtime_error("second"); };
  EXPECT_THROW(parallelInvoke(2, nothing, throwSecond), std::runtime_error);
}

TEST(Parallel, WorkerCount) {
  const int cores = workerCount(0);
  EXPECT_GE(cores, 1);
  EXPECT_EQ(workerCount(1), 1);
  EXPECT_EQ(workerCount(cores + 5), cores);
}

// Last in the file: it limits the whole process (CTest runs every test in a process of its own).
TEST(Parallel, RanksOnOneMachineShareItsCores) {
  const int cores = int(std::thread::hardware_concurrency());
  if (cores < 2) GTEST_SKIP() << "one core";
  shareCoresAmong(1);  // one process: nothing changes
  EXPECT_EQ(workerCount(0), cores);
  shareCoresAmong(cores);  // as many ranks as cores: one worker each, even for "every core"
  EXPECT_EQ(workerCount(0), 1);
  EXPECT_EQ(workerCount(2), 1);
  // Every chunk on the one thread: many short chunks would otherwise spread over the workers.
  std::mutex mutex;
  std::set<std::thread::id> threads;
  parallelFor(256, 0, 1, [&](int64_t, int64_t) {
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    const std::lock_guard<std::mutex> lock(mutex);
    threads.insert(std::this_thread::get_id());
  });
  EXPECT_EQ(threads.size(), 1u);
}

}  // namespace
}  // namespace parallax
