#include "parallax/core/memory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>

#include "parallax/core/error.h"

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

TEST(Memory, ImageBytesByHand) {
  // 1920 x 1080 float RGB: 2073600 pixels x 12 bytes.
  EXPECT_DOUBLE_EQ(imageBytes(1920, 1080), 24883200.0);
  // 65536^2 pixels x 12 bytes = 2^32 x 12 = 48 GiB, without int overflow.
  EXPECT_DOUBLE_EQ(imageBytes(65536, 65536), 48.0 * kGiB);
  // Nine 8-bit RGBA views of 100 x 50: 9 x 5000 x 4.
  EXPECT_DOUBLE_EQ(imageBytes(100, 50, kRgba8PixelBytes, 9), 180000.0);
}

TEST(Memory, FormatGiB) {
  EXPECT_EQ(formatGiB(48.0 * kGiB), "48 GiB");
  EXPECT_EQ(formatGiB(18.4 * kGiB), "18 GiB");
  EXPECT_EQ(formatGiB(2.5 * kGiB), "2.5 GiB");
  EXPECT_EQ(formatGiB(0.5 * kGiB), "0.5 GiB");
  EXPECT_EQ(formatGiB(24883200.0), "0.023 GiB");
}

TEST(Memory, DefaultLimitIsThreeQuartersOfPhysical) {
  EXPECT_DOUBLE_EQ(defaultMemoryLimitBytes(uint64_t(24) << 30), 18.0 * kGiB);
  EXPECT_DOUBLE_EQ(defaultMemoryLimitBytes(0), 4.0 * kGiB);
  EXPECT_GT(physicalMemoryBytes(), uint64_t(0));
}

TEST(Memory, CheckRefusesAboveTheLimitWithTheEstimate) {
  EXPECT_NO_THROW(checkMemory(kGiB, 2 * kGiB, "--size 1x1", "the film", "use a smaller size"));
  EXPECT_NO_THROW(checkMemory(2 * kGiB, 2 * kGiB, "--size 1x1", "the film", "x"));
  try {
    checkMemory(imageBytes(65536, 65536), 18.0 * kGiB, "--size 65536x65536", "the film",
                "use a smaller size");
    FAIL() << "no refusal";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "--size 65536x65536: needs about 48 GiB for the film (limit 18 GiB); use a "
                 "smaller size");
    EXPECT_EQ(e.file(), "--size 65536x65536");
  }
}

TEST(Memory, LargeBlocksAreAlignedToHugePagesAndHoldTheirValues) {
  constexpr size_t kHugePage = size_t(2) << 20;
  LargeVector<float> small(100, 1.5f);
  EXPECT_EQ(small.back(), 1.5f);
  // Growing from a small block to a large one keeps the values.
  LargeVector<float> grown(small);
  for (size_t i = 0; grown.size() * sizeof(float) < 3 * kLargeBlockBytes; ++i)
    grown.push_back(float(i));
  EXPECT_EQ(grown[99], 1.5f);
  EXPECT_EQ(grown[100 + 12345], 12345.0f);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(grown.data()) % kHugePage, 0u);
  const LargeVector<uint16_t> large(kLargeBlockBytes / sizeof(uint16_t) + 1, uint16_t(7));
  EXPECT_EQ(reinterpret_cast<uintptr_t>(large.data()) % kHugePage, 0u);
  EXPECT_EQ(large.back(), 7);
}

TEST(Memory, AFreedLargeBlockIsTakenAgainAtItsSizeWhileKept) {
  const size_t count = 3 * kLargeBlockBytes / sizeof(float);
  const size_t blockBytes = count * sizeof(float);  // a multiple of 2 MiB
  {
    const KeepFreedBlocks keep;
    const float* first = nullptr;
    {
      const LargeVector<float> a(count, 2.0f);
      first = a.data();
    }
    // Freed but kept.
    EXPECT_EQ(keptBlockBytes(), blockBytes);
    // Another size does not take it; the same size does, and gets its own values.
    const LargeVector<float> other(2 * count, 1.0f);
    EXPECT_NE(other.data(), first);
    const LargeVector<float> again(count, 3.0f);
    EXPECT_EQ(again.data(), first);
    EXPECT_EQ(again.back(), 3.0f);
    EXPECT_EQ(keptBlockBytes(), 0u);
  }
  // The scope's end gives every kept block back (`other` and `again` were kept at its end).
  EXPECT_EQ(keptBlockBytes(), 0u);
  // Without a scope a freed block goes back at once.
  {
    const LargeVector<float> a(count, 2.0f);
    EXPECT_EQ(a.front(), 2.0f);
  }
  EXPECT_EQ(keptBlockBytes(), 0u);
}

// UninitializedLargeVector leaves only argument-less values unwritten: a value given is
// copied, a type with a constructor still runs it, and the blocks are the large ones.
TEST(Memory, AnUninitializedLargeVectorStillConstructsWhatItIsGiven) {
  UninitializedLargeVector<float> filled(kLargeBlockBytes / sizeof(float), 0.25f);
  EXPECT_EQ(filled.front(), 0.25f);
  EXPECT_EQ(filled.back(), 0.25f);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(filled.data()) % (size_t(2) << 20), 0u);
  struct Counted {
    int value = 7;
  };
  UninitializedLargeVector<Counted> counted(1000);
  EXPECT_EQ(counted[999].value, 7);
  UninitializedLargeVector<float> sized;
  sized.resize(kLargeBlockBytes / sizeof(float));
  std::fill(sized.begin(), sized.end(), 1.0f);
  sized.resize(sized.size() + 1, 2.0f);
  EXPECT_EQ(sized.back(), 2.0f);
  EXPECT_EQ(sized.front(), 1.0f);
}

// The bandwidth figure is a physical one: 64 MiB read at a rate no machine is outside of (0.1 GB/s
// to 10 TB/s).
TEST(Memory, AStreamingPassTakesWhatMemoryBandwidthAllows) {
  const double bytes = 64.0 * (1 << 20);
  const double seconds = streamingPassSeconds(bytes, 0);
  ASSERT_TRUE(std::isfinite(seconds));
  EXPECT_GT(seconds, 0.0);
  EXPECT_GT(bytes / seconds, 1e8);
  EXPECT_LT(bytes / seconds, 1e13);
}

}  // namespace
}  // namespace parallax
