// The reporter (jobs/reporter.h): what a runner says reaches the front end in order, and
// printed() formats as printf does, at any length.
#include "parallax/jobs/reporter.h"

#include <gtest/gtest.h>

#include <string>

namespace parallax::jobs {
namespace {

TEST(Reporter, KeepsWhatWasSaidInOrder) {
  RecordingReporter reporter;
  reporter.note("a");
  reporter.result("one");
  reporter.warning("w");
  reporter.result("two");
  EXPECT_EQ(reporter.notes, std::vector<std::string>{"a"});
  EXPECT_EQ(reporter.warnings, std::vector<std::string>{"w"});
  EXPECT_EQ(reporter.results, (std::vector<std::string>{"one", "two"}));
  // Progress is accepted from anyone and says nothing here.
  auto progress = reporter.progress("render");
  progress->callback()(1, 2);
}

TEST(Reporter, PrintedIsPrintf) {
  EXPECT_EQ(printed("%d spp in %.2f s, %s", 16, 1.5, "fast"), "16 spp in 1.50 s, fast");
  EXPECT_EQ(printed("%s", ""), "");
  const std::string long_(5000, 'x');
  EXPECT_EQ(printed("<%s>", long_.c_str()), "<" + long_ + ">");
}

}  // namespace
}  // namespace parallax::jobs
