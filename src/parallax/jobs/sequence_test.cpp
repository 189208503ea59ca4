#include "parallax/jobs/sequence.h"

#include <gtest/gtest.h>

#include "parallax/core/error.h"

namespace parallax::jobs {
namespace {

// The N parts of a range cover it once, in order, each within one frame of the others' length.
TEST(Chunk, PartsCoverTheFramesOnceAndEvenly) {
  for (const auto& [first, last] : {std::pair{1, 120}, {5, 17}, {3, 3}, {1, 7}}) {
    for (int n = 1; n <= 12; ++n) {
      int next = first, shortest = 1 << 30, longest = 0;
      for (int k = 1; k <= n; ++k) {
        int a = first, b = last;
        narrowToChunk(std::to_string(k) + "/" + std::to_string(n), a, b);
        EXPECT_EQ(a, next) << first << ":" << last << " part " << k << "/" << n;
        EXPECT_GE(b, a - 1);
        shortest = std::min(shortest, b - a + 1);
        longest = std::max(longest, b - a + 1);
        next = b + 1;
      }
      EXPECT_EQ(next, last + 1);
      EXPECT_LE(longest - shortest, 1);
    }
  }
}

TEST(Chunk, RefusesWhatIsNotKOfN) {
  for (const char* bad : {"", "3", "0/4", "5/4", "1/0", "a/2", "1/-2", "1:2", "2/"}) {
    int a = 1, b = 10;
    EXPECT_THROW(narrowToChunk(bad, a, b), InputError) << bad;
  }
}

}  // namespace
}  // namespace parallax::jobs
