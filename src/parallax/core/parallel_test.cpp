#include "parallax/core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
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

TEST(Parallel, UsesMoreThanOneWorkerWhenAsked) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one core";
  // Two chunks that each wait for the other: they finish only if they run at the same time.
  std::atomic<int> arrived{0};
  parallelFor(2, 2, 1, [&](int64_t, int64_t) {
    ++arrived;
    for (int spin = 0; arrived < 2 && spin < 200000000; ++spin) std::this_thread::yield();
  });
  EXPECT_EQ(arrived, 2);
  std::atomic<int> invoked{0};
  const auto meet = [&] {
    ++invoked;
    for (int spin = 0; invoked < 2 && spin < 200000000; ++spin) std::this_thread::yield();
  };
  parallelInvoke(2, meet, meet);
  EXPECT_EQ(invoked, 2);
}

TEST(Parallel, RethrowsAChunksException) {
  EXPECT_THROW(parallelFor(100, 2, 1,
                           [](int64_t begin, int64_t) {
                             if (begin == 57) throw std::runtime_error("chunk 57");
                           }),
               std::runtime_error);
  EXPECT_THROW(parallelInvoke(
                   2, [] {}, [] { throw std::runtime_error("second"); }),
               std::runtime_error);
}

TEST(Parallel, WorkerCount) {
  EXPECT_EQ(workerCount(3), 3);
  EXPECT_GE(workerCount(0), 1);
}

}  // namespace
}  // namespace parallax
