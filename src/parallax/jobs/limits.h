// The limits every request is held to before any work starts (docs/inputs.md): memory (the
// front end's max_memory, default 3/4 of physical memory) and time (max_time, default one day,
// estimated at an optimistic rate), and the renderer's 2^31-pixel index.
#pragma once

#include <cstdint>
#include <exception>
#include <string>
#include <utility>

namespace parallax::jobs {

// Process-wide: the front end sets them once (the CLI's global --max-memory / --max-time and
// the commands' own; Python's set_limits). 0: the default.
struct Limits {
  double maxMemoryGiB = 0;
  double maxSeconds = 0;
  // The CLI's --estimate, Python's estimate_memory: the command stops at its estimate
  // (checkPeakMemory throws EstimateOnly), before its work allocates or writes anything.
  bool estimateOnly = false;
};
Limits& limits();

// The memory limit in bytes.
double memoryLimitBytes();
// Hands the limits to the importer's isolated readers (importer/assimp_importer.h,
// setImporterLimits): the memory budget is memoryLimitBytes(), the CPU budget the default importer
// budget or max_time if that is smaller. Called before every scene load.
void applyImporterLimits();
// Refuses pictures of more than 2^31 pixels (the renderer's pixel index is an int); call it
// after the memory estimate, which refuses them first where memory is smaller.
void checkPixelCount(double pixels, const std::string& subject);
// Refuses (InputError naming `subject`) when what the process holds now plus `bytes` exceeds
// memoryLimitBytes(): an early refusal of a part, before the inputs are loaded.
void checkMemoryEstimate(double bytes, const std::string& subject, const std::string& what,
                         const std::string& advice);

// A command's whole estimate of its peak resident memory (docs/inputs.md, "Memory").
struct MemoryEstimate {
  double bytes = 0;  // the peak resident set size the process will reach
  std::string what;  // what the work holds at its peak ("the layers (1920x1080 image, ...)")
};
// Thrown by checkPeakMemory under limits().estimateOnly: the command stops there.
class EstimateOnly : public std::exception {
 public:
  explicit EstimateOnly(MemoryEstimate estimate) : estimate_(std::move(estimate)) {}
  const MemoryEstimate& estimate() const { return estimate_; }
  const char* what() const noexcept override { return "estimate only"; }

 private:
  MemoryEstimate estimate_;
};
// The process's peak once `workBytes` more are allocated: what it holds now (residentBytes())
// plus the work, or the peak so far when loading the inputs went higher.
double peakEstimate(double workBytes);
// The command's final estimate, made once its inputs are loaded and before its work allocates:
// refuses when peakEstimate(workBytes) is over the limit (the message gives the estimate),
// remembers it (lastEstimate(), for the records), and under limits().estimateOnly throws
// EstimateOnly.
void checkPeakMemory(double workBytes, const std::string& subject, const std::string& what,
                     const std::string& advice);
// The last checkPeakMemory's estimate (bytes 0 before any).
const MemoryEstimate& lastEstimate();
// The time estimate: `samples` camera samples (pixel x sample, each at least one ray) on
// `threads` threads (0: all) at kSamplesPerSecondPerThread, an optimistic rate (the fastest
// bench figure on a simple scene, rounded up), so that only work certain to take longer than
// the time limit is refused. The refusal names the field `field` with the value `value`
// ("--spp 16: needs ...").
inline constexpr double kSamplesPerSecondPerThread = 1e8;
inline constexpr double kDefaultMaxSeconds = 24 * 3600.0;
void checkTimeEstimate(double samples, int threads, const std::string& field,
                       const std::string& value, const std::string& advice);

// "45 s", "12 min", "5 h", "58 days".
std::string formatDuration(double seconds);
// "12.3 M rays/s".
std::string formatRate(double raysPerSecond);
// What a camera ray met of the splats (docs/splats.md, "Speed"): ", 41.2 Gaussians evaluated
// and 9.8 blended a camera ray", or "" when no splat was evaluated.
std::string splatClause(uint64_t evaluated, uint64_t blended, uint64_t cameraRays);

}  // namespace parallax::jobs
