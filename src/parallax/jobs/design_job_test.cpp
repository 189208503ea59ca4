// The design runner (jobs/design_job.h): text and JSON, and its refusals.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "parallax/accel/accelerator.h"
#include "parallax/camera/camera.h"
#include "parallax/camera/display_camera.h"
#include "parallax/core/error.h"
#include "parallax/display/lenticular_presets.h"
#include "parallax/io/display_file.h"
#include "parallax/jobs/design_job.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/jobs_test_support.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/render_job.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/view_job.h"
#include "parallax/render/display_render.h"
#include "parallax/render/display_test_support.h"
#include "parallax/render/quilt.h"

namespace parallax::jobs {
namespace {

TEST(DesignRunner, TextAndJsonSayTheSameDesign) {
  DesignRequest request;
  request.loaded = smallBarrier();
  const DesignReport report = designReport(request, silentReporter());
  EXPECT_NE(report.text.find("views                9"), std::string::npos) << report.text;
  EXPECT_NE(report.json.find("\"views\": 9"), std::string::npos) << report.json;
  request.framing.fit = "depth";  // framing needs a scene
  EXPECT_EQ(fieldOf([&] { designReport(request, silentReporter()); }), "fit");
  request.loaded = portrait();
  request.framing = {};
  request.scene = SceneRequest{};
  EXPECT_EQ(fieldOf([&] { designReport(request, silentReporter()); }), "scene");
}

}  // namespace
}  // namespace parallax::jobs
