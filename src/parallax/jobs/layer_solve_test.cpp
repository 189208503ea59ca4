// Content-adaptive layers through the runner (jobs/render_parts.h, solveLayers): the solver
// lowers its objective from the slits' start, and the record holds what simulate reads back.
#include <gtest/gtest.h>

#include <string>

#include "parallax/jobs/jobs_test_support.h"
#include "parallax/jobs/render_job.h"

namespace parallax::jobs {
namespace {

// `method`'s layers on the small barrier, one sample a pixel, one training eye a view.
RenderRequest smallLayersRequest(const std::string& method) {
  RenderRequest request;
  request.display.loaded = smallBarrier();
  request.sampling.spp = 1;
  request.layers.method = method;
  request.layers.trainEyes = 1;
  return request;
}

TEST(LayerSolve, NmfFramesLowerTheObjectiveAndAreRecorded) {
  const Scene scene = defaultScene();
  RenderRequest request = smallLayersRequest("nmf");
  request.layers.rank = 2;
  request.layers.iterations = 3;
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
    const RenderRequest request = smallLayersRequest(method);
    RecordingReporter reporter;
    const RenderResult result = renderInMemory(request, scene, reporter);
    ASSERT_EQ(reporter.results.size(), 1u);
    EXPECT_EQ(reporter.results[0].rfind(std::string(method) + ": 1 frame(s), 7 iterations", 0), 0u)
        << reporter.results[0];
  }
}

// --train-distances sets the training eyes: K per view at each distance (the small barrier's
// views times K times the distances), recorded with the layers.
TEST(LayerSolve, TrainingEyesSitAtTheDistancesAsked) {
  const Scene scene = defaultScene();
  RenderRequest request = smallLayersRequest("optimized-image");
  request.layers.iterations = 1;
  const auto eyes = [&](const std::string& distances, const std::string& recorded) {
    request.layers.trainDistances = distances;
    RecordingReporter reporter;
    const RenderResult result = renderInMemory(request, scene, reporter);
    EXPECT_NE(result.record.find(recorded), std::string::npos) << result.record;
    const size_t at = result.record.find("\"training_eyes\": ");
    EXPECT_NE(at, std::string::npos);
    return std::stoi(result.record.substr(at + 17));
  };
  const int three =
      eyes("0.8,1,1.25", "\"training_distances\": [\n      0.8,\n      1.0,\n      1.25");
  const int two = eyes("0.85,1.2", "\"training_distances\": [\n      0.85,\n      1.2");
  const int one = eyes("1", "\"training_distances\": [\n      1.0");
  EXPECT_GT(one, 0);
  EXPECT_EQ(two, 2 * one);
  EXPECT_EQ(three, 3 * one);
}

}  // namespace
}  // namespace parallax::jobs
