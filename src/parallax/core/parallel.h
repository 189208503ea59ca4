// Work spread over the cores: the program's one interface to its thread pool (oneTBB, used only
// in parallel.cpp). Every caller computes each item the same way whichever worker runs it, so
// results do not depend on the thread count.
#pragma once

#include <cstdint>
#include <functional>

namespace parallax {

// Calls body(begin, end) on disjoint chunks of at most `grain` items that cover [0, count),
// on `threads` workers (0: every core), and returns when all are done. Chunks run in any order
// and on any worker; an exception thrown by a chunk is rethrown here (the first one).
void parallelFor(int64_t count, int threads, int64_t grain,
                 const std::function<void(int64_t begin, int64_t end)>& body);

// The sum of term(i) over i in [0, count), each term computed on some worker (chunks of `grain`
// items) and the terms added in index order: the same double whatever the thread count.
double parallelSum(int64_t count, int threads, int64_t grain,
                   const std::function<double(int64_t i)>& term);

// Runs the tasks at once, on `threads` workers (0: every core), and returns when all are done.
void parallelInvoke(int threads, const std::function<void()>& first,
                    const std::function<void()>& second);

// The workers a call with `threads` (0: every core) runs on: never more than the cores.
int workerCount(int threads);

// For the life of the process, "every core" means this process's share of the machine's cores
// when `processes` processes run on it at once (ranks of one mpirun on one node): at least one
// worker each, so that N ranks on a node do not run N times as many threads as it has cores.
void shareCoresAmong(int processes);

}  // namespace parallax
