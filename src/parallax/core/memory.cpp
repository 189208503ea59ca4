#include "parallax/core/memory.h"

#include <malloc.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <new>
#include <utility>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/core/parallel.h"

namespace parallax {

double peakResidentMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
}

double peakResidentBytes() {
  rusage children{};
  getrusage(RUSAGE_CHILDREN, &children);
  return std::max(peakResidentMiB(), double(children.ru_maxrss) / 1024.0) * 1024.0 * 1024.0;
}

double residentBytes() {
  std::ifstream statm("/proc/self/statm");
  unsigned long long pages = 0, resident = 0;
  if (!(statm >> pages >> resident)) return 0;
  return double(resident) * double(sysconf(_SC_PAGE_SIZE));
}

namespace {

constexpr size_t kHugePage = size_t(2) << 20;

size_t roundedToHugePages(size_t bytes) {
  return (bytes + kHugePage - 1) / kHugePage * kHugePage;
}

// Large blocks freed while a KeepFreedBlocks lives, kept for the next allocation of the same
// rounded size. At most kKeptBytes are kept (the oldest go first), so the peak rises by no more
// than that; releaseFreeMemory() and the last KeepFreedBlocks empty it. Never destroyed: blocks
// may be freed during static destruction.
class KeptBlocks {
 public:
  static KeptBlocks& instance() {
    static KeptBlocks* kept = new KeptBlocks;
    return *kept;
  }
  void* take(size_t rounded) {
    const std::lock_guard lock(mutex_);
    for (size_t k = blocks_.size(); k-- > 0;)
      if (blocks_[k].second == rounded) {
        void* block = blocks_[k].first;
        blocks_.erase(blocks_.begin() + std::ptrdiff_t(k));
        bytes_ -= rounded;
        return block;
      }
    return nullptr;
  }
  void keep(void* block, size_t rounded) {
    const std::lock_guard lock(mutex_);
    if (scopes_ == 0 || rounded > kKeptBytes) return std::free(block);
    while (bytes_ + rounded > kKeptBytes) {
      std::free(blocks_.front().first);
      bytes_ -= blocks_.front().second;
      blocks_.erase(blocks_.begin());
    }
    blocks_.push_back({block, rounded});
    bytes_ += rounded;
  }
  void release() {
    const std::lock_guard lock(mutex_);
    releaseLocked();
  }
  size_t bytes() {
    const std::lock_guard lock(mutex_);
    return bytes_;
  }
  void open() {
    const std::lock_guard lock(mutex_);
    ++scopes_;
  }
  void close() {
    const std::lock_guard lock(mutex_);
    if (--scopes_ == 0) releaseLocked();
  }

 private:
  void releaseLocked() {
    for (const auto& [block, rounded] : blocks_) std::free(block);
    blocks_.clear();
    bytes_ = 0;
  }
  static constexpr size_t kKeptBytes = size_t(64) << 20;
  int scopes_ = 0;
  std::mutex mutex_;
  std::vector<std::pair<void*, size_t>> blocks_;
  size_t bytes_ = 0;
};

}  // namespace

void* allocateBlock(size_t bytes) {
  if (bytes < kLargeBlockBytes) return ::operator new(bytes);
  const size_t rounded = roundedToHugePages(bytes);
  if (void* kept = KeptBlocks::instance().take(rounded)) return kept;
  void* block = std::aligned_alloc(kHugePage, rounded);
  if (!block) throw std::bad_alloc();
  // Advice only: where transparent huge pages are off (or the call fails) the block is as good.
  madvise(block, rounded, MADV_HUGEPAGE);
  return block;
}

void freeBlock(void* block, size_t bytes) {
  if (bytes < kLargeBlockBytes)
    ::operator delete(block);
  else
    KeptBlocks::instance().keep(block, roundedToHugePages(bytes));
}

size_t keptBlockBytes() {
  return KeptBlocks::instance().bytes();
}

KeepFreedBlocks::KeepFreedBlocks() {
  KeptBlocks::instance().open();
}
KeepFreedBlocks::~KeepFreedBlocks() {
  KeptBlocks::instance().close();
}

void releaseFreeMemory() {
  KeptBlocks::instance().release();
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

uint64_t physicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  uint64_t bytes = pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) : 0;
  // A container's limit (cgroup v2), when it is lower: "max" or a number of bytes.
  std::ifstream cgroup("/sys/fs/cgroup/memory.max");
  unsigned long long limit = 0;
  if (cgroup >> limit && limit > 0 && (bytes == 0 || limit < bytes)) bytes = limit;
  return bytes;
}

double defaultMemoryLimitBytes(uint64_t physicalBytes) {
  return physicalBytes == 0 ? 4.0 * kGiB : 0.75 * double(physicalBytes);
}

double imageBytes(double width, double height, double bytesPerPixel, double count) {
  return width * height * bytesPerPixel * count;
}

std::string formatGiB(double bytes) {
  const double gib = bytes / kGiB;
  char text[64];
  if (gib >= 9.5)
    std::snprintf(text, sizeof text, "%.0f GiB", gib);
  else
    std::snprintf(text, sizeof text, "%.2g GiB", gib);
  return text;
}

void checkMemory(double bytes, double limitBytes, const std::string& subject,
                 const std::string& what, const std::string& advice) {
  if (bytes <= limitBytes) return;
  throw InputError(subject, "",
                   "needs about " + formatGiB(bytes) + " for " + what + " (limit " +
                       formatGiB(limitBytes) + "); " + advice);
}

double streamingPassSeconds(double bytes, int threads) {
  constexpr int64_t kBlockWords = (1 << 20) / sizeof(uint64_t);
  const int64_t blocks = std::max<int64_t>(1, int64_t(bytes / (kBlockWords * sizeof(uint64_t))));
  std::vector<uint64_t> words(size_t(blocks * kBlockWords));
  for (size_t i = 0; i < words.size(); ++i) words[i] = i;  // resident before the clock
  double fastest = 0, checksum = 0;
  for (int repeat = 0; repeat < 3; ++repeat) {
    const auto start = std::chrono::steady_clock::now();
    checksum += parallelSum(blocks, threads, 1, [&](int64_t block) {
      uint64_t sum = 0;
      const uint64_t* first = words.data() + block * kBlockWords;
      for (int64_t i = 0; i < kBlockWords; ++i) sum += first[i];
      return double(sum);
    });
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    fastest = repeat == 0 ? seconds : std::min(fastest, seconds);
  }
  if (checksum < 0) std::printf("%g\n", checksum);  // keeps the reads
  return fastest * bytes / (double(words.size()) * sizeof(uint64_t));
}

}  // namespace parallax
