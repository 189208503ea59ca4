// The view runner (jobs/view_job.h) against the library's own pinhole render.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "parallax/accel/accelerator.h"
#include "parallax/camera/camera.h"
#include "parallax/jobs/design_job.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/jobs_test_support.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/render_job.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/view_job.h"
#include "parallax/render/render.h"

namespace parallax::jobs {
namespace {

TEST(ViewRunner, APinholeViewIsTheLibrarysRender) {
  const Scene scene = defaultScene();
  ViewRequest request;
  request.width = 64, request.height = 36;
  request.sampling.spp = 1;
  const Image view = viewInMemory(request, scene, silentReporter());
  const CameraSpec spec = scene.camera ? *scene.camera : frameScene(scene);
  const PinholeCamera camera(spec.eye, spec.lookAt, spec.up, spec.fovDegrees, 64, 36);
  const Accelerator accelerator(scene);
  RenderSettings settings;
  settings.samplesPerPixel = 1;
  EXPECT_EQ(view.pixels(), render(scene, accelerator, camera, settings).pixels());
  request.fov = 180.0f;
  EXPECT_EQ(fieldOf([&] { viewInMemory(request, scene, silentReporter()); }), "fov");
  request.fov.reset();
  request.displayEye = Vec3d{0, 0, -10};
  request.display.loaded = smallBarrier();
  EXPECT_EQ(fieldOf([&] { viewInMemory(request, scene, silentReporter()); }), "display_eye");
}

}  // namespace
}  // namespace parallax::jobs
