#include "parallax/jobs/interlace_job.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/display/lenticular.h"
#include "parallax/display/lenticular_presets.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/jobs_test_support.h"
#include "parallax/jobs/requests.h"

namespace parallax::jobs {
namespace {

// Camera k's colour: its own on every pixel.
Vec3f cameraColour(int k, int count) {
  const float t = float(k) / float(count - 1);
  return {t, 1.0f - t, 0.25f + 0.5f * t};
}

std::vector<Image> constantViews(int count, int width, int height) {
  std::vector<Image> views;
  for (int k = 0; k < count; ++k) views.emplace_back(width, height, cameraColour(k, count));
  return views;
}

InterlaceRequest smallRequest() {
  InterlaceRequest r;
  r.display.path = kSmallDisplayFile;
  return r;
}

// Expects `call` to throw a RequestError naming `field`.
template <class Call>
void expectRefusal(Call call, const std::string& field) {
  try {
    call();
    ADD_FAILURE() << "no refusal naming " << field;
  } catch (const RequestError& e) {
    EXPECT_EQ(e.field(), field) << e.what();
  }
}

// Direct mapping of N constant views: every image-layer pixel has the colour of the camera
// whose design view the display shows there (camera k feeds the k-th eye from the left).
TEST(InterlaceInMemory, EachPixelTakesItsOwnViewsColour) {
  const InterlaceRequest r = smallRequest();
  const BuiltDisplay display = makeDisplay(loadDisplay(kSmallDisplayFile, silentReporter()));
  const DisplayDesign& design = *display->barrierDesign();
  const int count = interlacedViewCount(design);
  ASSERT_EQ(count, 9);
  const InterlaceResult result =
      interlaceInMemory(r, constantViews(count, 320, 180), {}, silentReporter());
  ASSERT_EQ(result.image.width(), 320);
  ASSERT_EQ(result.image.height(), 180);
  const std::vector<int> designView = designViewsLeftToRight(design);
  std::vector<int> cameraOfView(designView.size());
  for (size_t k = 0; k < designView.size(); ++k) cameraOfView[designView[k]] = int(k);
  std::vector<int> seen(count, 0);
  for (int y = 0; y < 180; y += 17)
    for (int x = 0; x < 320; ++x) {
      const int camera = cameraOfView[display->viewIndex(x, y)];
      ++seen[camera];
      const Vec3f expected = cameraColour(camera, count), got = result.image.at(x, y);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], expected[c], 1e-6) << x << "," << y;
    }
  for (int k = 0; k < count; ++k) EXPECT_GT(seen[k], 0) << "camera " << k;
  // The mask beside it, and the record's cameras.
  EXPECT_EQ(result.mask.width(), 320);
  EXPECT_NE(result.record.find("\"cameras\""), std::string::npos);
  EXPECT_NE(result.record.find("\"design\""), std::string::npos);
}

// The quilt of the same views (tiles from the bottom-left) gives the same layers.
TEST(InterlaceInMemory, AQuiltIsItsViews) {
  InterlaceRequest r = smallRequest();
  const std::vector<Image> views = constantViews(9, 32, 18);
  const Image fromViews = interlaceInMemory(r, views, {}, silentReporter()).image;
  r.quiltLayout = QuiltLayout{3, 3, 0.0};
  const Image fromQuilt =
      interlaceInMemory(r, {}, assembleQuilt(views, 3, 3), silentReporter()).image;
  EXPECT_EQ(fromViews.pixels(), fromQuilt.pixels());
}

// Eight views on a nine-view barrier: resampled across views, and said so.
TEST(InterlaceInMemory, OtherCountsAreResampledWithANote) {
  InterlaceRequest r = smallRequest();
  r.viewResampling = "nearest";
  RecordingReporter reporter;
  const InterlaceResult result = interlaceInMemory(r, constantViews(8, 320, 180), {}, reporter);
  ASSERT_EQ(reporter.notes.size(), 1u);
  EXPECT_NE(reporter.notes[0].find("8 views given, the display takes 9 views"), std::string::npos);
  EXPECT_NE(result.record.find("\"view_resampling\": \"nearest\""), std::string::npos);
  // Nearest: every pixel is one of the cameras' colours.
  for (int x = 0; x < 320; ++x) {
    bool found = false;
    for (int k = 0; k < 8; ++k) found = found || result.image.at(x, 90) == cameraColour(k, 8);
    ASSERT_TRUE(found) << x;
  }
}

// A lenticular panel blends the two views around f N - 1/2 (f the subpixel's view fraction):
// with view k grey k / (N - 1), each subpixel is that position over N - 1.
// A Portrait shrunk eightfold, and `count` flat views, view k grey k / (count - 1).
struct SmallPanel {
  InterlaceRequest request;
  LenticularDesign design;
  std::vector<Image> views;
};
SmallPanel smallPanel(int count) {
  DisplayDescription description = loadDisplay("lkg:portrait", silentReporter());
  LenticularCalibration& calibration = description.lenticular;
  calibration.screenW /= 8, calibration.screenH /= 8;
  SmallPanel panel;
  panel.request.display.loaded = description;
  panel.design = designLenticular(calibration);
  for (int k = 0; k < count; ++k) panel.views.emplace_back(16, 16, Vec3f(float(k) / (count - 1)));
  return panel;
}

TEST(InterlaceInMemory, ALenticularSubpixelBlendsTheViewsAroundItsFraction) {
  const int count = 12;
  const auto [r, design, views] = smallPanel(count);
  const InterlaceResult result = interlaceInMemory(r, views, {}, silentReporter());
  EXPECT_TRUE(result.mask.empty());
  ASSERT_EQ(result.image.width(), design.calibration.screenW);
  for (int y = 0; y < result.image.height(); y += 7)
    for (int x = 0; x < result.image.width(); x += 3)
      for (int c = 0; c < 3; ++c) {
        const double at =
            std::clamp(viewFraction(design, x, y, c) * count - 0.5, 0.0, double(count - 1));
        ASSERT_NEAR(result.image.at(x, y)[c], at / (count - 1), 1e-5) << x << "," << y;
      }
}

// view_resampling nearest on a lenticular panel: each subpixel shows the one view whose window
// holds its view fraction (brute force: floor(f N)), not the blend; the record says which.
TEST(InterlaceInMemory, ALenticularSubpixelTakesTheNearestViewWhenAsked) {
  const int count = 12;
  auto [r, design, views] = smallPanel(count);
  const InterlaceResult linear = interlaceInMemory(r, views, {}, silentReporter());
  r.viewResampling = "nearest";
  const InterlaceResult nearest = interlaceInMemory(r, views, {}, silentReporter());
  EXPECT_NE(nearest.image.pixels(), linear.image.pixels());
  EXPECT_NE(nearest.record.find("\"view_resampling\": \"nearest\""), std::string::npos);
  for (int y = 0; y < nearest.image.height(); ++y)
    for (int x = 0; x < nearest.image.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        const int view =
            std::clamp(int(std::floor(viewFraction(design, x, y, c) * count)), 0, count - 1);
        ASSERT_FLOAT_EQ(nearest.image.at(x, y)[c], float(view) / (count - 1)) << x << "," << y;
      }
}

TEST(InterlaceRequestChecks, NameTheirFields) {
  const std::vector<Image> views = constantViews(9, 32, 18);
  InterlaceRequest r = smallRequest();
  r.viewResampling = "cubic";
  expectRefusal([&] { interlaceInMemory(r, views, {}, silentReporter()); }, "view_resampling");
  r = smallRequest();
  expectRefusal([&] { interlaceInMemory(r, {}, {}, silentReporter()); }, "views");
  expectRefusal([&] { interlaceInMemory(r, views, views[0], silentReporter()); }, "quilt");
  expectRefusal([&] { interlaceInMemory(r, {}, views[0], silentReporter()); }, "quilt_layout");
  r.quiltLayout = QuiltLayout{0, 3, 0.0};
  expectRefusal([&] { interlaceInMemory(r, {}, views[0], silentReporter()); }, "quilt_layout");
  r.quiltLayout = QuiltLayout{3, 3, 0.0};
  expectRefusal([&] { interlaceInMemory(r, views, {}, silentReporter()); }, "quilt_layout");
  InterlaceRequest lenticular;
  lenticular.display.path = "lkg:portrait";
  lenticular.display.subpixels = true;
  expectRefusal([&] { interlaceInMemory(lenticular, views, {}, silentReporter()); }, "subpixels");
  // Views of another size are named by their place.
  std::vector<Image> mixed = views;
  mixed[4] = Image(16, 18);
  r = smallRequest();
  try {
    interlaceInMemory(r, mixed, {}, silentReporter());
    ADD_FAILURE() << "views of two sizes";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "views[4]");
  }
}

TEST(LenticularSimulateRequest, RefusesAnEyeBehindThePanelAndABarrier) {
  LenticularSimulateRequest r;
  r.display.path = "lkg:portrait";
  r.eye = Vec3d{0, 0, -5};
  const LenticularCalibration portrait = *lenticularPreset("portrait");
  const Image panel(portrait.screenW, portrait.screenH);
  expectRefusal([&] { lenticularViewInMemory(r, panel, silentReporter()); }, "eye");
  r.display.path = kSmallDisplayFile;
  r.eye.reset();
  EXPECT_THROW(lenticularViewInMemory(r, panel, silentReporter()), InputError);
}

}  // namespace
}  // namespace parallax::jobs
