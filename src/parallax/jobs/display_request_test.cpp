// The display request (jobs/display_request.h): where a description comes from (loaded, a made
// model, the path, the command's default), how messages name it, and the camera's choices it
// carries, each against the reader and the factory it stands for.
#include "parallax/jobs/display_request.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "parallax/display/flat_monitor_test_support.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/jobs_test_support.h"

namespace parallax::jobs {
namespace {

TEST(DisplayRequest, DescribesFromWhatItWasGiven) {
  DisplayRequest none;
  // No path: the command's default, "" the built-in barrier.
  EXPECT_EQ(none.describe(silentReporter()).barrier.imagePanel.width,
            defaultDisplaySpec().imagePanel.width);
  EXPECT_EQ(none.describe(silentReporter(), "lkg:portrait").kind, DisplayKind::Lenticular);
  DisplayRequest file;
  file.path = kSmallDisplayFile;
  EXPECT_EQ(file.describe(silentReporter()).barrier.imagePanel.width,
            loadDisplayDescription(kSmallDisplayFile).barrier.imagePanel.width);
  EXPECT_EQ(file.describe(silentReporter(), "lkg:portrait").kind, DisplayKind::Barrier);
  // A description in hand wins over the path, and names it by its source.
  DisplayRequest loaded = DisplayRequest::of(portrait());
  loaded.path = kSmallDisplayFile;
  EXPECT_EQ(loaded.describe(silentReporter()).kind, DisplayKind::Lenticular);
  EXPECT_EQ(DisplayRequest::of(portrait()).path, portrait().source());
  EXPECT_EQ(DisplayRequest::of(smallBarrier()).path, "");  // the built-in's source names no file
  // A model made in code is read from nowhere: a description of kind Other.
  DisplayRequest made;
  made.madeInCode = [](const DisplayCameraRequest&) {
    return std::make_unique<FlatMonitor>(8, 4, 100.0, Vec3d{0, 0, 500});
  };
  EXPECT_EQ(made.describe(silentReporter()).kind, DisplayKind::Other);
  EXPECT_EQ(buildDisplay(made, made.describe(silentReporter()))->kind(), DisplayKind::Other);
  // A missing file is refused naming it.
  DisplayRequest missing;
  missing.path = "/nonexistent/display.json";
  try {
    missing.describe(silentReporter());
    ADD_FAILURE() << "a missing display file was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), missing.path);
  }
}

TEST(DisplayRequest, NamesAndCarriesTheCamerasChoices) {
  DisplayRequest r;
  EXPECT_EQ(r.named(), "<built-in display>");
  EXPECT_EQ(r.named("<built-in>"), "<built-in>");
  r.path = "panel.json";
  EXPECT_EQ(r.named(), "panel.json");
  r.subpixels = true;
  r.distance = 700;
  r.lens = {2.5, "parallel"};
  ViewFilter filter;
  filter.widthViews = 1.5;
  const DisplayCameraRequest camera = r.camera(filter);
  EXPECT_TRUE(camera.subpixels);
  EXPECT_EQ(camera.viewDistanceMm, 700);
  EXPECT_EQ(camera.filter.widthViews, 1.5);
  EXPECT_EQ(camera.lens.spot, 2.5);
  EXPECT_EQ(camera.lens.bundles, "parallel");
  EXPECT_TRUE(camera.lens.given());
  EXPECT_FALSE(LensReadingRequest{}.given());
  // The factory reads the choices as the request spells them: a barrier refuses a distance.
  EXPECT_EQ(fieldOf([&] { buildDisplay(r, smallBarrier()); }), "distance");
  r.distance = 0;
  EXPECT_EQ(fieldOf([&] { buildDisplay(r, smallBarrier()); }), "lens_spot");
  r.lens = {};
  EXPECT_EQ(buildDisplay(r, smallBarrier())->film().columns, 3 * 90);  // one ray a subpixel
}

}  // namespace
}  // namespace parallax::jobs
