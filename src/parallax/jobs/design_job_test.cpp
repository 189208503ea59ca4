// The design runner (jobs/design_job.h): text and JSON, and its refusals.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "parallax/jobs/design_job.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/jobs_test_support.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/render_job.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/scene_request.h"
#include "parallax/jobs/view_job.h"

namespace parallax::jobs {
namespace {

TEST(DesignRunner, TextAndJsonSayTheSameDesign) {
  DesignRequest request;
  request.display.loaded = smallBarrier();
  const DesignReport report = designReport(request, silentReporter());
  EXPECT_NE(report.text.find("views                9"), std::string::npos) << report.text;
  EXPECT_NE(report.json.find("\"views\": 9"), std::string::npos) << report.json;
  request.framing.fit = "depth";  // framing needs a scene
  EXPECT_EQ(fieldOf([&] { designReport(request, silentReporter()); }), "fit");
}

// design --scene on a lenticular panel: the lens's depth of field, and the scene framed into it
// as render frames it (a bare scene, no width given: the depth fit).
TEST(DesignRunner, ALenticularPanelReportsTheScenesFraming) {
  DesignRequest request;
  request.display.loaded = portrait();
  const DesignReport plain = designReport(request, silentReporter());
  EXPECT_NE(plain.text.find("depth of field       +-12.8 mm around the panel"), std::string::npos)
      << plain.text;
  EXPECT_NE(plain.json.find("\"depth_of_field_mm\": 12.79"), std::string::npos) << plain.json;
  Scene bare = defaultScene();
  bare.display.fit = bare.bounds();
  bare.display.content = bare.bounds();
  request.scene = SceneRequest{};
  const DesignReport framed = designReport(request, silentReporter(), &bare);
  EXPECT_NE(framed.text.find("depth (fit depth)"), std::string::npos) << framed.text;
  EXPECT_EQ(framed.text.find("warning:"), std::string::npos) << framed.text;
  EXPECT_NE(framed.json.find("\"within_budget\": true"), std::string::npos) << framed.json;
  request.framing.fit = "window";
  const DesignReport window = designReport(request, silentReporter(), &bare);
  EXPECT_NE(window.text.find("warning: the content spans"), std::string::npos) << window.text;
  EXPECT_NE(window.text.find("the display is sharp within ±13 mm (the lens's depth of field)"),
            std::string::npos)
      << window.text;
}

}  // namespace
}  // namespace parallax::jobs
