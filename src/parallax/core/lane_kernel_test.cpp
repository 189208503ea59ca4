#include "parallax/core/lane_kernel.h"

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace parallax {
namespace {

// The CPU's feature flags as the kernel reports them: a truth independent of GCC's cpuid code.
std::set<std::string> cpuFlags() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line))
    if (line.rfind("flags", 0) == 0) {
      std::istringstream words(line.substr(line.find(':') + 1));
      std::set<std::string> flags;
      for (std::string word; words >> word;) flags.insert(word);
      return flags;
    }
  return {};
}

bool hasAll(const std::set<std::string>& flags, std::initializer_list<const char*> wanted) {
  for (const char* flag : wanted)
    if (!flags.count(flag)) return false;
  return true;
}

TEST(LaneKernel, ReportsTheWidestLevelTheCpuHas) {
  const std::set<std::string> flags = cpuFlags();
  if (flags.empty()) GTEST_SKIP() << "no /proc/cpuinfo flags on this system";
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__AVX512F__)
  // The x86-64 psABI's levels: v3 adds AVX, AVX2, BMI1/2, F16C, FMA, LZCNT, MOVBE to v2's
  // SSE4.2 and POPCNT; v4 adds AVX-512 F, BW, CD, DQ and VL.
  // LZCNT (v3) is left out: Linux lists it as "abm", which some hypervisors' CPU models hide
  // from /proc/cpuinfo while CPUID, which GCC's dispatcher reads, reports it (seen on a CI
  // machine with AVX-512 whose flags lacked "abm").
  const bool v3 = hasAll(flags, {"avx", "avx2", "bmi1", "bmi2", "f16c", "fma", "movbe", "sse4_2",
                                 "popcnt", "ssse3", "cx16"});
  const bool v4 = v3 && hasAll(flags, {"avx512f", "avx512bw", "avx512cd", "avx512dq", "avx512vl"});
  EXPECT_STREQ(laneKernelIsa(), v4 ? "x86-64-v4" : v3 ? "x86-64-v3" : "x86-64");
#else
  EXPECT_STREQ(laneKernelIsa(), "native");
#endif
}

}  // namespace
}  // namespace parallax
