#include "parallax/core/memory.h"

#include <malloc.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <new>

#include "parallax/core/error.h"

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

void* allocateBlock(size_t bytes) {
  if (bytes < kLargeBlockBytes) return ::operator new(bytes);
  constexpr size_t kHugePage = size_t(2) << 20;
  const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
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
    std::free(block);
}

void releaseFreeMemory() {
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

}  // namespace parallax
