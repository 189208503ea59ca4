// The limits (jobs/limits.h): a refusal names the field and its value.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <string>

#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/jobs/design_job.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/jobs_test_support.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/render_job.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/view_job.h"

namespace parallax::jobs {
namespace {

TEST(Limits, TheTimeEstimateNamesTheFieldAndItsValue) {
  const Limits saved = limits();
  limits().maxSeconds = 1;
  SamplingRequest sampling;
  sampling.spp = 1 << 20;
  try {
    sampling.checkWork(4096, 4096);
    ADD_FAILURE() << "no refusal";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.field(), "spp");
    EXPECT_EQ(e.value(), std::to_string(1 << 20));
    EXPECT_NE(e.message().find("{max_time}"), std::string::npos) << e.message();
  }
  limits() = saved;
  EXPECT_NO_THROW(sampling.checkWork(16, 16));
}

// The whole estimate is what the process holds now plus the work: a work of 64 MiB on top of
// this test process's resident memory, measured independently from /proc/self/status.
TEST(Limits, ThePeakEstimateIsTheResidentMemoryPlusTheWork) {
  std::ifstream status("/proc/self/status");
  std::string line;
  double residentKiB = 0;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0) residentKiB = std::stod(line.substr(6));
  ASSERT_GT(residentKiB, 0);
  const double work = 64.0 * 1024 * 1024;
  const double estimate = peakEstimate(work);
  EXPECT_GE(estimate, work);
  // Within 8 MiB of the resident size read here (the heap trim only lowers it).
  EXPECT_LE(estimate - work, residentKiB * 1024 + 8.0 * 1024 * 1024);
}

TEST(Limits, AnEstimateOnlyRunStopsAtTheWholeEstimate) {
  const Limits saved = limits();
  limits().estimateOnly = true;
  try {
    checkPeakMemory(1e8, "--size 1x1", "the film", "use a smaller size");
    ADD_FAILURE() << "no stop";
  } catch (const EstimateOnly& e) {
    EXPECT_GE(e.estimate().bytes, 1e8);
    EXPECT_EQ(e.estimate().what, "the film");
  }
  limits() = saved;
  EXPECT_EQ(lastEstimate().what, "the film");
  // Over the limit: refused with the whole estimate in the message (the work plus what the
  // process holds already: about 0.01 GiB in a Release build, more under the sanitizers).
  limits().maxMemoryGiB = 0.5;
  const double heldGiB = peakEstimate(0) / kGiB;
  try {
    checkPeakMemory(kGiB, "--size 1x1", "the film", "use a smaller size");
    ADD_FAILURE() << "no refusal";
  } catch (const InputError& e) {
    const std::string message = e.what();
    const std::string before = "needs about ";
    const std::size_t at = message.find(before);
    ASSERT_NE(at, std::string::npos) << message;
    std::size_t length = 0;
    const double gib = std::stod(message.substr(at + before.size()), &length);
    EXPECT_EQ(message.substr(at + before.size() + length, 18), " GiB for the film ") << message;
    EXPECT_GE(gib, 1.0) << message;
    EXPECT_LE(gib, 1.0 + heldGiB + 0.1) << message;
    EXPECT_NE(message.find("(limit 0.5 GiB)"), std::string::npos) << message;
  }
  limits() = saved;
}

}  // namespace
}  // namespace parallax::jobs
