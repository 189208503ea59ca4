// The limits (jobs/limits.h): a refusal names the field and its value.
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

}  // namespace
}  // namespace parallax::jobs
