#include "parallax/jobs/limits.h"

#include <algorithm>
#include <climits>
#include <cstdio>
#include <thread>

#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/importer/assimp_importer.h"

namespace parallax::jobs {

Limits& limits() {
  static Limits processLimits;
  return processLimits;
}

double memoryLimitBytes() {
  const double giB = limits().maxMemoryGiB;
  return giB > 0 ? giB * kGiB : defaultMemoryLimitBytes(physicalMemoryBytes());
}

void applyImporterLimits() {
  ImporterLimits importer;
  importer.memoryBytes = memoryLimitBytes();
  importer.cpuSeconds = limits().maxSeconds > 0
                            ? std::min(limits().maxSeconds, kDefaultImporterCpuSeconds)
                            : kDefaultImporterCpuSeconds;
  setImporterLimits(importer);
}

void checkPixelCount(double pixels, const std::string& subject) {
  if (pixels > double(INT_MAX))
    throw InputError(subject, "",
                     "more than 2^31 pixels, the most the renderer can index; use a smaller size");
}

void checkMemoryEstimate(double bytes, const std::string& subject, const std::string& what,
                         const std::string& advice) {
  checkMemory(residentBytes() + bytes, memoryLimitBytes(), subject, what,
              advice + ", or raise {max_memory}");
}

namespace {
MemoryEstimate& estimateRecord() {
  static MemoryEstimate last;
  return last;
}
}  // namespace

double peakEstimate(double workBytes) {
  releaseFreeMemory();
  return std::max(peakResidentBytes(), residentBytes() + workBytes);
}

void checkPeakMemory(double workBytes, const std::string& subject, const std::string& what,
                     const std::string& advice) {
  const double bytes = peakEstimate(workBytes);
  checkMemory(bytes, memoryLimitBytes(), subject, what, advice + ", or raise {max_memory}");
  estimateRecord() = {bytes, what};
  if (limits().estimateOnly) throw EstimateOnly(estimateRecord());
}

const MemoryEstimate& lastEstimate() {
  return estimateRecord();
}

void checkTimeEstimate(double samples, int threads, const std::string& field,
                       const std::string& value, const std::string& advice) {
  const double cores = std::max(1u, std::thread::hardware_concurrency());
  const double used = threads > 0 ? std::min(double(threads), cores) : cores;
  const double seconds = samples / (kSamplesPerSecondPerThread * used);
  const double limit = limits().maxSeconds > 0 ? limits().maxSeconds : kDefaultMaxSeconds;
  if (seconds <= limit) return;
  char text[256];
  std::snprintf(text, sizeof text,
                "needs %.3g samples, at least %s at %.0f M samples/s on %.0f threads (limit %s); ",
                samples, formatDuration(seconds).c_str(), kSamplesPerSecondPerThread / 1e6, used,
                formatDuration(limit).c_str());
  throw RequestError(field, text + advice + ", or raise {max_time}", value);
}

std::string formatDuration(double seconds) {
  char text[64];
  if (seconds < 120)
    std::snprintf(text, sizeof text, "%.0f s", seconds);
  else if (seconds < 7200)
    std::snprintf(text, sizeof text, "%.0f min", seconds / 60);
  else if (seconds < 3 * 86400)
    std::snprintf(text, sizeof text, "%.0f h", seconds / 3600);
  else
    std::snprintf(text, sizeof text, "%.3g days", seconds / 86400);
  return text;
}

std::string splatClause(uint64_t evaluated, uint64_t blended, uint64_t cameraRays) {
  if (evaluated == 0 || cameraRays == 0) return "";
  char text[96];
  std::snprintf(text, sizeof text, ", %.1f Gaussians evaluated and %.1f blended a camera ray",
                double(evaluated) / double(cameraRays), double(blended) / double(cameraRays));
  return text;
}

std::string formatRate(double raysPerSecond) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f M rays/s", raysPerSecond / 1e6);
  return text;
}

}  // namespace parallax::jobs
