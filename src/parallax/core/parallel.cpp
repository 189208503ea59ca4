#include "parallax/core/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <memory>
#include <thread>
#include <vector>

namespace parallax {

namespace {
// The cores this process may use, when shareCoresAmong set them (0: all of them).
int sharedCores = 0;
}  // namespace

void shareCoresAmong(int processes) {
  if (processes <= 1) return;
  const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
  sharedCores = std::max(1, cores / processes);
  // oneTBB's own limit: no arena of this process runs more workers than its share.
  static std::unique_ptr<tbb::global_control> limit;
  limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                size_t(sharedCores));
}

// More workers than cores only queue (oneTBB warns and ignores the excess): asking for more is
// asking for every core.
int workerCount(int threads) {
  const int cores = sharedCores > 0 ? sharedCores : tbb::this_task_arena::max_concurrency();
  return threads > 0 ? std::min(threads, cores) : cores;
}

void parallelFor(int64_t count, int threads, int64_t grain,
                 const std::function<void(int64_t, int64_t)>& body) {
  if (count <= 0) return;
  grain = std::max<int64_t>(1, grain);
  // One chunk, or one worker: no pool at all (the caller's thread, the caller's stack).
  if (count <= grain || threads == 1) {
    for (int64_t begin = 0; begin < count; begin += grain)
      body(begin, std::min(count, begin + grain));
    return;
  }
  // simple_partitioner: chunks of at most `grain` items, as promised (the default partitioner
  // may hand a worker several grains at once, which callers that size their buffers by the
  // grain must not see).
  const auto run = [&] {
    tbb::parallel_for(
        tbb::blocked_range<int64_t>(0, count, size_t(grain)),
        [&](const tbb::blocked_range<int64_t>& range) { body(range.begin(), range.end()); },
        tbb::simple_partitioner());
  };
  if (threads <= 0 || workerCount(threads) == workerCount(0)) return run();
  tbb::task_arena arena(workerCount(threads));
  arena.execute(run);
}

double parallelSum(int64_t count, int threads, int64_t grain,
                   const std::function<double(int64_t)>& term) {
  std::vector<double> terms(size_t(std::max<int64_t>(0, count)));
  parallelFor(count, threads, grain, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) terms[size_t(i)] = term(i);
  });
  double sum = 0;
  for (double t : terms) sum += t;
  return sum;
}

void parallelInvoke(int threads, const std::function<void()>& first,
                    const std::function<void()>& second) {
  if (threads == 1) {
    first();
    second();
    return;
  }
  const auto run = [&] { tbb::parallel_invoke(first, second); };
  if (threads <= 0 || workerCount(threads) == workerCount(0)) return run();
  tbb::task_arena arena(workerCount(threads));
  arena.execute(run);
}

}  // namespace parallax
