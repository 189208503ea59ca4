// Content-adaptive layers through the runner (jobs/render_parts.h, solveLayers): the solver
// lowers its objective from the slits' start, and the record holds what simulate reads back.
#include <gtest/gtest.h>

#include <string>

#include "parallax/jobs/jobs_test_support.h"
#include "parallax/jobs/render_job.h"

namespace parallax::jobs {
namespace {

TEST(LayerSolve, NmfFramesLowerTheObjectiveAndAreRecorded) {
  const Scene scene = defaultScene();
  RenderRequest request;
  request.loaded = smallBarrier();
  request.sampling.spp = 1;
  request.layers.method = "nmf";
  request.layers.rank = 2;
  request.layers.iterations = 3;
  request.layers.trainEyes = 1;
  RecordingReporter reporter;
  const RenderResult result = renderInMemory(request, scene, reporter);
  ASSERT_EQ(result.frames.size(), 2u);
  for (const LayerFrame& frame : result.frames) {
    EXPECT_EQ(frame.image.width(), 90);
    EXPECT_EQ(frame.mask.width(), 90);
  }
  ASSERT_EQ(reporter.results.size(), 1u);  // the solver's line
  EXPECT_EQ(reporter.results[0].rfind("nmf: 2 frame(s), 3 iterations", 0), 0u)
      << reporter.results[0];
  // The objective falls (the record's first and last).
  const auto number = [&](const std::string& key) {
    const size_t at = result.record.find("\"" + key + "\": ");
    EXPECT_NE(at, std::string::npos) << key;
    return std::stod(result.record.substr(at + key.size() + 4));
  };
  EXPECT_LT(number("objective_last"), number("objective_first"));
  // nmf's default brightness: 1.05 max(2, rank) times the slits'.
  EXPECT_DOUBLE_EQ(number("brightness_gain"), 2.1);
}

// Without --iterations both solvers run kDefaultLayerIterations.
TEST(LayerSolve, BothSolversRunTheDefaultIterations) {
  for (const char* method : {"optimized-image", "nmf"}) {
    const Scene scene = defaultScene();
    RenderRequest request;
    request.loaded = smallBarrier();
    request.sampling.spp = 1;
    request.layers.method = method;
    request.layers.trainEyes = 1;
    RecordingReporter reporter;
    const RenderResult result = renderInMemory(request, scene, reporter);
    ASSERT_EQ(reporter.results.size(), 1u);
    EXPECT_EQ(reporter.results[0].rfind(std::string(method) + ": 1 frame(s), 7 iterations", 0), 0u)
        << reporter.results[0];
  }
}

}  // namespace
}  // namespace parallax::jobs
