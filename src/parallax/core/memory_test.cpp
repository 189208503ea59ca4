#include "parallax/core/memory.h"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>

namespace parallax {
namespace {

TEST(Memory, PeakGrowsWhenWeTouch64MiB) {
  const double before = peakResidentMiB();
  const size_t bytes = size_t(64) << 20;
  auto block = std::make_unique<char[]>(bytes);
  std::memset(block.get(), 1, bytes);  // touch every page so it becomes resident
  const double after = peakResidentMiB();
  EXPECT_GT(before, 0.0);
  EXPECT_GE(after, before + 60.0) << "before " << before << " after " << after;
  EXPECT_EQ(block[bytes - 1], 1);
}

}  // namespace
}  // namespace parallax
