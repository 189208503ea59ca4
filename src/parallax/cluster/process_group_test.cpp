#include "parallax/cluster/process_group.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "parallax/core/error.h"

namespace parallax::cluster {
namespace {

TEST(ProcessGroup, AloneWithoutASession) {
  ProcessGroup& group = world();
  EXPECT_EQ(group.rank(), 0);
  EXPECT_EQ(group.size(), 1);
  EXPECT_TRUE(group.isRoot());
  EXPECT_NO_THROW(group.checkpoint());
}

TEST(ProcessGroup, SingleProcessAgreesWithItself) {
  const auto group = makeSingleProcessGroup();
  EXPECT_FALSE(group->agree(std::nullopt).has_value());
  const std::optional<Failure> failure = group->agree(Failure{0, 2, "scene.json: missing"});
  ASSERT_TRUE(failure.has_value());
  EXPECT_EQ(failure->exitCode, 2);
  EXPECT_EQ(failure->message, "scene.json: missing");
}

TEST(ProcessGroup, SingleProcessMergeAndSumsKeepValues) {
  const auto group = makeSingleProcessGroup();
  std::vector<uint8_t> bytes{1, 0, 255, 7};
  group->mergeToRoot(bytes);
  EXPECT_EQ(bytes, (std::vector<uint8_t>{1, 0, 255, 7}));
  std::vector<uint64_t> counts{3, 1ull << 40};
  group->sumOnAll(counts);
  EXPECT_EQ(counts, (std::vector<uint64_t>{3, 1ull << 40}));
  EXPECT_EQ(group->maxOnAll(2.5), 2.5);
}

TEST(ProcessGroup, PeerFailedCarriesTheFailure) {
  const PeerFailed e(Failure{3, 2, "x.obj: bad"});
  EXPECT_EQ(e.failure().rank, 3);
  EXPECT_EQ(e.failure().exitCode, 2);
  EXPECT_NE(std::string(e.what()).find("rank 3"), std::string::npos);
}

TEST(ProcessGroup, TestFailureOnlyOnTheNamedRank) {
  const auto group = makeSingleProcessGroup();
  unsetenv("PARALLAX_TEST_FAIL_RANK");
  EXPECT_NO_THROW(failIfAskedForTest(*group));
  setenv("PARALLAX_TEST_FAIL_RANK", "1", 1);
  EXPECT_NO_THROW(failIfAskedForTest(*group));  // this process is rank 0
  setenv("PARALLAX_TEST_FAIL_RANK", "0", 1);
  EXPECT_THROW(failIfAskedForTest(*group), InputError);
  unsetenv("PARALLAX_TEST_FAIL_RANK");
}

TEST(ProcessGroup, MpirunIsDetectedFromItsEnvironment) {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"}) unsetenv(name);
  EXPECT_FALSE(launchedByMpirun());
  setenv("OMPI_COMM_WORLD_SIZE", "2", 1);
  EXPECT_TRUE(launchedByMpirun());
  unsetenv("OMPI_COMM_WORLD_SIZE");
}

}  // namespace
}  // namespace parallax::cluster
