// Quilts and the direct mapping of camera views. Truths: names and tile positions worked out by
// hand from the convention (docs/quilts.md), the display's own geometry (viewIndex, the ray of
// a pixel, viewPosition), and renderDirectMapping as a second code path.
#include "parallax/render/quilt.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "parallax/core/error.h"
#include "parallax/display/display_model.h"
#include "parallax/display/lenticular_test_support.h"
#include "parallax/render/display_render.h"
#include "parallax/render/display_test_support.h"

namespace parallax {
namespace {

Image solid(int width, int height, float value) {
  return Image(width, height, Vec3f(value));
}

DisplaySpec smallDisplay(LayerOrder order) {
  return smallDisplaySpec(180, 60, order);
}

TEST(QuiltName, ParsesTheLayout) {
  QuiltLayout a = parseQuiltName("scene_qs5x9a1.7778.png");
  EXPECT_EQ(a.columns, 5);
  EXPECT_EQ(a.rows, 9);
  EXPECT_DOUBLE_EQ(a.aspect, 1.7778);
  a = parseQuiltName("/renders/v1.2/shot_qs8x6a0.75.jpg");
  EXPECT_EQ(a.columns, 8);
  EXPECT_EQ(a.rows, 6);
  EXPECT_DOUBLE_EQ(a.aspect, 0.75);
  a = parseQuiltName("old_qs2x2a1_qs11x6a2.pfm");  // the last _qs counts
  EXPECT_EQ(a.columns, 11);
  EXPECT_EQ(a.rows, 6);
  EXPECT_DOUBLE_EQ(a.aspect, 2.0);
}

// Names as Looking Glass's tools write them: `a` is the display's aspect with as many decimals
// as the tool prints (its WebXR library writes screenW / screenH in full), or no aspect at all
// (its own example quilts, "..._qs8x6.webp").
TEST(QuiltName, ReadsNamesAsLookingGlassWritesThem) {
  QuiltLayout a = parseQuiltName("quilt_qs7x7a1.7778.png");
  EXPECT_EQ(a.columns, 7);
  EXPECT_EQ(a.rows, 7);
  EXPECT_DOUBLE_EQ(a.aspect, 1.7778);
  a = parseQuiltName("hologram_qs7x7a1.7777777777777777.png");
  EXPECT_DOUBLE_EQ(a.aspect, 16.0 / 9.0);
  for (const char* name : {"x_qs5x9a1.8.png", "x_qs5x9a1.78.png", "x_qs5x9a1.778.png"}) {
    a = parseQuiltName(name);
    EXPECT_EQ(a.columns * a.rows, 45) << name;
    EXPECT_NEAR(a.aspect, 1.78, 0.021) << name;
  }
  a = parseQuiltName("Space_Nap_qs8x6.webp");
  EXPECT_EQ(a.columns, 8);
  EXPECT_EQ(a.rows, 6);
  EXPECT_EQ(a.aspect, 0.0);                                                   // left to the display
  EXPECT_EQ(quiltFileName("Space_Nap", a, ".webp"), "Space_Nap_qs8x6.webp");  // and written back
  // Square tiles (a 16" Gen3's 7x7 on 5999 x 5999) under a 16:9 name are taken as they are.
  const std::vector<Image> views = splitQuilt(Image(70, 70), a, "x");
  EXPECT_EQ(splitQuilt(Image(70, 70), parseQuiltName("quilt_qs7x7a1.7778.png"), "q").size(), 49u);
  EXPECT_EQ(views.size(), 48u);
}

// Every layout parallax writes reads back to the same layout and the display's aspect (to the
// four decimals written).
TEST(QuiltName, EveryWrittenLayoutRoundTrips) {
  for (const double aspect : {16.0 / 9.0, 0.75, 9.0 / 16.0, 1.0, 3.0, 1536.0 / 2048.0, 1.6})
    for (const auto& [columns, rows] : {std::pair{7, 7}, {8, 6}, {11, 6}, {5, 9}, {9, 1}}) {
      const QuiltLayout layout{columns, rows, aspect};
      const QuiltLayout back = parseQuiltName("dir.v2/quilt" + quiltFileName("", layout, ".png"));
      EXPECT_EQ(back.columns, columns);
      EXPECT_EQ(back.rows, rows);
      EXPECT_NEAR(back.aspect, aspect, 5e-5);
    }
}

// A quilt video's name carries its layout as Looking Glass Studio imports it.
TEST(QuiltName, VideoNamesCarryTheLayout) {
  const QuiltLayout layout{7, 7, 16.0 / 9.0};
  EXPECT_EQ(quiltVideoPath("out/turn.mp4", layout), "out/turn_qs7x7a1.7778.mp4");
  EXPECT_EQ(quiltVideoPath("turn.webm", layout), "turn_qs7x7a1.7778.webm");
  EXPECT_EQ(quiltVideoPath("out/turn_qs7x7a1.7778.mp4", layout), "out/turn_qs7x7a1.7778.mp4");
  EXPECT_EQ(quiltVideoPath("out/turn_qs7x7a1.78.mp4", layout), "out/turn_qs7x7a1.78.mp4");
  EXPECT_EQ(quiltVideoPath("out/turn_qs7x7.mp4", layout), "out/turn_qs7x7a1.7778.mp4");
  EXPECT_EQ(quiltVideoPath("out/my_qsfoo.mkv", layout), "out/my_qsfoo_qs7x7a1.7778.mkv");
  const QuiltLayout back = parseQuiltName(quiltVideoPath("out/turn.mp4", layout));
  EXPECT_EQ(back.columns, 7);
  EXPECT_NEAR(back.aspect, layout.aspect, 5e-5);
  EXPECT_THROW(quiltVideoPath("out/turn_qs8x6a0.75.mp4", layout), std::invalid_argument);
  EXPECT_THROW(quiltVideoPath("out/turn_qs7x7a0.75.mp4", layout), std::invalid_argument);
}

TEST(QuiltName, RejectsMalformedNamesNamingTheFile) {
  for (const char* name :
       {"scene.png", "scene_qs5x9a.png", "scene_qs0x9a1.png", "scene_qs5x0.png",
        "scene_qs5by9a1.png", "scene_qs5x9a1.7778_final.png", "scene_qs5x9a0.png",
        "scene_qs5x9a-1.png", "scene_qs5x99999999999a1.png", "scene_qsx9a1.png"}) {
    try {
      parseQuiltName(name);
      ADD_FAILURE() << name << " was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), name);
      EXPECT_NE(std::string(e.what()).find("_qs"), std::string::npos) << e.what();
    }
  }
}

TEST(QuiltName, WrittenNamesReadBack) {
  EXPECT_EQ(formatQuiltAspect(1.0), "1");
  EXPECT_EQ(formatQuiltAspect(0.75), "0.75");
  EXPECT_EQ(formatQuiltAspect(1920.0 / 1080.0), "1.7778");
  const QuiltLayout layout{3, 3, 1920.0 / 1080.0};
  const std::string name = quiltFileName("quilt", layout, ".png");
  EXPECT_EQ(name, "quilt_qs3x3a1.7778.png");
  const QuiltLayout back = parseQuiltName(name);
  EXPECT_EQ(back.columns, 3);
  EXPECT_EQ(back.rows, 3);
  EXPECT_NEAR(back.aspect, layout.aspect, 5e-5);
}

TEST(ColumnsByRows, ParsesAndRejects) {
  int c = 0, r = 0;
  EXPECT_TRUE(parseColumnsByRows("5x9", c, r));
  EXPECT_EQ(c, 5);
  EXPECT_EQ(r, 9);
  for (const char* bad : {"", "5", "5x", "x9", "5x9x2", "0x3", "3x0", "-3x3", "3 x3", "3x3 "})
    EXPECT_FALSE(parseColumnsByRows(bad, c, r)) << bad;
}

TEST(Quilt, TilesStartAtTheBottomLeft) {
  // 3 x 2 tiles of 4 x 3: view k is a solid k. By the convention, the bottom row (image rows
  // 3-5) holds views 0, 1, 2 from left to right and the top row (rows 0-2) views 3, 4, 5.
  std::vector<Image> views;
  for (int k = 0; k < 6; ++k) views.push_back(solid(4, 3, float(k)));
  const Image quilt = assembleQuilt(views, 3, 2);
  ASSERT_EQ(quilt.width(), 12);
  ASSERT_EQ(quilt.height(), 6);
  EXPECT_EQ(quilt.at(0, 5).x, 0.0f);   // bottom-left
  EXPECT_EQ(quilt.at(5, 4).x, 1.0f);   // bottom row, second tile
  EXPECT_EQ(quilt.at(11, 3).x, 2.0f);  // bottom-right
  EXPECT_EQ(quilt.at(0, 2).x, 3.0f);   // top row starts on the left
  EXPECT_EQ(quilt.at(7, 0).x, 4.0f);
  EXPECT_EQ(quilt.at(11, 0).x, 5.0f);  // top-right: the last view
  const std::vector<Image> back = splitQuilt(quilt, {3, 2, 0.0}, "q");
  ASSERT_EQ(back.size(), 6u);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(back[size_t(k)].pixels(), views[size_t(k)].pixels()) << k;
}

TEST(Quilt, RoundTripKeepsEveryPixel) {
  std::vector<Image> views;
  for (int k = 0; k < 12; ++k) {
    Image v(5, 4);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 5; ++x) v.at(x, y) = Vec3f(float(k), float(x), float(y));
    views.push_back(v);
  }
  const Image quilt = assembleQuilt(views, 4, 3);
  const std::vector<Image> back = splitQuilt(quilt, {4, 3, 1.25}, "q");
  ASSERT_EQ(back.size(), views.size());
  for (size_t k = 0; k < views.size(); ++k) EXPECT_EQ(back[k].pixels(), views[k].pixels()) << k;
}

TEST(Quilt, PaddingAtTheTopAndRightIsIgnored) {
  // 13 x 7 pixels in 3 x 2 tiles: tiles of 4 x 3 from the bottom-left; column 12 and row 0
  // are padding.
  Image quilt(13, 7, Vec3f(-1.0f));
  for (int y = 1; y < 7; ++y)
    for (int x = 0; x < 12; ++x) quilt.at(x, y) = Vec3f(float(x / 4 + 3 * ((6 - y) / 3)));
  const std::vector<Image> views = splitQuilt(quilt, {3, 2, 0.0}, "q");
  ASSERT_EQ(views.size(), 6u);
  for (int k = 0; k < 6; ++k) {
    ASSERT_EQ(views[size_t(k)].width(), 4);
    ASSERT_EQ(views[size_t(k)].height(), 3);
    EXPECT_EQ(views[size_t(k)].pixels(), solid(4, 3, float(k)).pixels()) << k;
  }
}

// The name's aspect is the display's, so tiles of any shape are taken; only a quilt with fewer
// pixels than tiles is refused.
TEST(Quilt, TilesOfAnyShapeAreTaken) {
  const Image quilt(12, 6);  // 3 x 2 tiles of 4 x 3: aspect 1.333
  EXPECT_EQ(splitQuilt(quilt, {3, 2, 1.3333}, "q_qs3x2a1.3333.png").size(), 6u);
  const std::vector<Image> swapped = splitQuilt(quilt, {2, 3, 1.3333}, "q_qs2x3a1.3333.png");
  ASSERT_EQ(swapped.size(), 6u);
  EXPECT_EQ(swapped[0].width(), 6);
  EXPECT_EQ(swapped[0].height(), 2);
  try {
    splitQuilt(Image(2, 2), {3, 1, 0.0}, "q");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "q");
  }
}

TEST(Interlace, ViewCountIsRoundedViewsOrThreeTimesWithSubpixels) {
  const DisplaySpec s = smallDisplay(LayerOrder::BarrierBack);
  EXPECT_EQ(interlacedViewCount(designDisplay(s)), 9);
  BarrierCameraSettings subpixels;
  subpixels.subpixelRays = true;
  EXPECT_EQ(interlacedViewCount(designDisplay(s, subpixels)), 27);
  EXPECT_THROW(
      interlaceCameraViews(designDisplay(s, subpixels), std::vector<Image>(9, solid(180, 60, 0))),
      std::invalid_argument);
}

TEST(Interlace, BarrierBackCountsViewsLeftToRightAndBarrierFrontRightToLeft) {
  // Barrier-back: the backlight aperture sits behind the group centre, so a pixel left of the
  // centre sends its light to the left: view 0 (the group's leftmost column) is seen from the
  // left. Barrier-front: the aperture is in front, a left pixel is seen from the right.
  const std::vector<int> back =
      designViewsLeftToRight(designDisplay(smallDisplay(LayerOrder::BarrierBack)));
  const std::vector<int> front =
      designViewsLeftToRight(designDisplay(smallDisplay(LayerOrder::BarrierFront)));
  ASSERT_EQ(back.size(), 9u);
  ASSERT_EQ(front.size(), 9u);
  for (int k = 0; k < 9; ++k) {
    EXPECT_EQ(back[size_t(k)], k);
    EXPECT_EQ(front[size_t(k)], 8 - k);
  }
}

TEST(Interlace, SolidViewsGoToTheirViewIndexAndLeftmostEye) {
  for (const LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
    const DisplayDesign d = designDisplay(smallDisplay(order));
    const std::unique_ptr<DisplayModel> rays = makeBarrierDisplay(d);
    std::vector<Image> cameras;  // camera k (k-th from the left) shows a solid k
    for (int k = 0; k < 9; ++k) cameras.push_back(solid(180, 60, float(k)));
    const Image image = interlaceCameraViews(d, cameras);
    for (int y = 0; y < 60; y += 11)
      for (int x = 0; x < 180; ++x) {
        const int camera = int(image.at(x, y).x);
        const int view = rays->viewIndex(x, y);
        // Barrier-back: the colour is the view index itself; barrier-front: mirrored.
        EXPECT_EQ(camera, order == LayerOrder::BarrierBack ? view : 8 - view) << x << "," << y;
        // The pixel's central display ray leaves toward the eye of its camera: camera k's
        // picture is seen from the k-th eye from the left (spaced S / 9 = 55 mm apart).
        const DisplayRay ray = rays->ray(x + 0.5, y + 0.5, 0.5, 0.5);
        EXPECT_NEAR(ray.origin.x, rays->viewPosition(view).x, 0.5);
        EXPECT_NEAR(ray.origin.x, quiltEyePosition(d, camera, 9).x, 0.5) << x << "," << y;
      }
    // The leftmost camera is seen from the leftmost design eye.
    double leftmost = 1e9;
    int leftmostView = -1;
    for (int v = 0; v < 9; ++v)
      if (rays->viewPosition(v).x < leftmost) leftmost = rays->viewPosition(v).x, leftmostView = v;
    for (int x = 0; x < 180; ++x)
      if (rays->viewIndex(x, 30) == leftmostView) {
        EXPECT_EQ(image.at(x, 30).x, 0.0f) << x;
      }
  }
}

TEST(Interlace, SubpixelChannelsComeFromTheirOwnCameras) {
  BarrierCameraSettings subpixels;
  subpixels.subpixelRays = true;
  const DisplayDesign d = designDisplay(smallDisplay(LayerOrder::BarrierBack), subpixels);
  const std::unique_ptr<DisplayModel> rays = makeBarrierDisplay(d);
  std::vector<Image> cameras;
  for (int k = 0; k < 27; ++k) cameras.push_back(solid(180, 60, float(k)));
  const Image image = interlaceCameraViews(d, cameras);
  const std::vector<int> order = designViewsLeftToRight(d);
  for (int x = 0; x < 180; ++x)
    for (int i = 0; i < 3; ++i) {
      const int column = 3 * x + i, view = rays->viewIndex(column, 20);
      const int camera = int(std::find(order.begin(), order.end(), view) - order.begin());
      EXPECT_EQ(image.at(x, 20)[rays->channelOfColumn(column)], float(camera)) << column;
    }
}

TEST(Interlace, ViewsOfAnotherSizeAreResampled) {
  const DisplayDesign d = designDisplay(smallDisplay(LayerOrder::BarrierBack));
  std::vector<Image> full, half;
  for (int k = 0; k < 9; ++k) {
    full.push_back(solid(180, 60, float(k)));
    half.push_back(solid(90, 30, float(k)));
  }
  EXPECT_EQ(interlaceCameraViews(d, half).pixels(), interlaceCameraViews(d, full).pixels());
}

TEST(Interlace, QuiltOfTheDisplaysViewsIsTheDirectMapping) {
  // Two code paths: renderDirectMapping renders design view v from viewPosition(v); here the
  // views are rendered from eyes spread evenly over S, tiled into a quilt, cut out again and
  // interlaced by camera order.
  Scene scene = defaultScene();
  scene.display.width = 1.5f;  // the 49.4 mm display frames the box
  const Accelerator accel(scene);
  for (const LayerOrder order : {LayerOrder::BarrierBack, LayerOrder::BarrierFront}) {
    const DisplayDesign d = designDisplay(smallDisplay(order));
    const std::unique_ptr<DisplayModel> rays = makeBarrierDisplay(d);
    const std::vector<int> designView = designViewsLeftToRight(d);
    for (int k = 0; k < 9; ++k)
      EXPECT_NEAR(quiltEyePosition(d, k, 9).x, rays->viewPosition(designView[size_t(k)]).x, 1e-9);

    const std::vector<Image> views = renderQuiltViews(scene, accel, d, {}, 9, 180, 60);
    const Image quilt = assembleQuilt(views, 3, 3);
    const QuiltLayout layout = parseQuiltName(quiltFileName("quilt", {3, 3, 3.0}, ".png"));
    const Image image = interlaceCameraViews(d, splitQuilt(quilt, layout, "quilt"));
    const Image direct = renderDirectMapping(scene, accel, d, {}).image;
    ASSERT_EQ(image.pixels().size(), direct.pixels().size());
    int close = 0;
    for (size_t i = 0; i < image.pixels().size(); ++i)
      close += length(image.pixels()[i] - direct.pixels()[i]) <= 1e-3f;
    EXPECT_GE(close, int(image.pixels().size()) * 99 / 100);
    // And the picture is not trivially uniform: views differ from one another.
    EXPECT_NE(views[0].pixels(), views[8].pixels());
  }
}

// The player's table (QuiltInterlacer, from 8-bit quilt codes to 8-bit panel codes) against
// interlaceQuiltLenticular on the quilt's decoded views (splitQuilt) encoded to 8 bits: within
// one code everywhere, both resamplings, a quilt whose tiles are not the panel's shape and a
// thread count of 1 and of every core alike.
TEST(QuiltInterlacer, IsTheInterlacerOnCodes) {
  const LenticularDesign d = smallLenticularDesign(40);  // 180 x 40 pixels
  const QuiltLayout layout{4, 3, 0};
  const int quiltW = 4 * 37, quiltH = 3 * 23;
  std::vector<uint8_t> codes(size_t(quiltW) * quiltH * 3);
  uint32_t state = 12345;
  for (uint8_t& code : codes) {
    state = state * 1664525u + 1013904223u;
    code = uint8_t(state >> 24);
  }
  Image quilt(quiltW, quiltH);
  for (size_t i = 0; i < quilt.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) quilt.pixels()[i][c] = srgb8ToLinear(codes[3 * i + size_t(c)]);
  const std::vector<Image> views = splitQuilt(quilt, layout, "quilt");
  for (const ViewResampling resampling : {ViewResampling::Linear, ViewResampling::Nearest}) {
    const Image truth = interlaceQuiltLenticular(d, views, resampling);
    const QuiltInterlacer table(d, layout, quiltW, quiltH, resampling);
    ASSERT_EQ(table.panelWidth(), truth.width());
    ASSERT_EQ(table.panelHeight(), truth.height());
    std::vector<uint8_t> panel(size_t(truth.width()) * truth.height() * 3), serial(panel.size());
    table.interlace(codes.data(), panel.data());
    table.interlace(codes.data(), serial.data(), 1);
    EXPECT_EQ(panel, serial);
    int off = 0;
    for (size_t i = 0; i < truth.pixels().size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const int expected = linearToSrgb8(truth.pixels()[i][c]);
        const int got = panel[3 * i + size_t(c)];
        ASSERT_LE(std::abs(got - expected), 1) << i << " " << c;
        off += got != expected;
      }
    EXPECT_LT(off, int(panel.size()) / 100);  // a rounding's difference, rarely
  }
}

}  // namespace
}  // namespace parallax

namespace parallax {
namespace {

Image flat(int width, int height, float value) {
  Image image(width, height);
  for (Vec3f& p : image.pixels()) p = Vec3f(value);
  return image;
}

// Views carrying their own index: view k of `count` sits (k + 1/2) / count of the way across,
// so linear resampling gives the camera position there, j = (k + 1/2) m / count - 1/2, clamped,
// and nearest its rounding.
TEST(ResampleViews, BlendsTheTwoViewsAroundEachNeededOne) {
  std::vector<Image> cameras;
  for (int j = 0; j < 48; ++j) cameras.push_back(flat(4, 3, float(j)));
  const std::vector<Image> linear = resampleViews(cameras, 9, ViewResampling::Linear);
  const std::vector<Image> nearest = resampleViews(cameras, 9, ViewResampling::Nearest);
  ASSERT_EQ(linear.size(), 9u);
  for (int k = 0; k < 9; ++k) {
    const double position = std::clamp((k + 0.5) * 48 / 9 - 0.5, 0.0, 47.0);
    EXPECT_NEAR(linear[size_t(k)].at(2, 1).x, position, 1e-4) << k;
    EXPECT_EQ(nearest[size_t(k)].at(2, 1).x, float(std::lround(position))) << k;
  }
  // More views than cameras: the ends hold the end cameras.
  const std::vector<Image> up =
      resampleViews({flat(2, 2, 0), flat(2, 2, 1)}, 4, ViewResampling::Linear);
  EXPECT_FLOAT_EQ(up[0].at(0, 0).x, 0.0f);
  EXPECT_FLOAT_EQ(up[1].at(0, 0).x, 0.25f);
  EXPECT_FLOAT_EQ(up[2].at(0, 0).x, 0.75f);
  EXPECT_FLOAT_EQ(up[3].at(0, 0).x, 1.0f);
}

// Quilt views rendered straight into their tiles are the views rendered one by one and tiled
// (a second code path), for any display kind.
TEST(RenderQuilt, TilesAreTheViewsRenderedOneByOne) {
  const DisplayDesign d = designDisplay(smallDisplay(LayerOrder::BarrierBack));
  Scene scene = defaultScene();
  scene.display.width = 0.75f;
  const Accelerator accel(scene);
  const QuiltLayout layout{3, 2, 0};
  const Image quilt = renderQuilt(scene, accel, *makeBarrierDisplay(d), {}, layout, 30, 20);
  const std::vector<Image> views = renderQuiltViews(scene, accel, d, {}, 6, 30, 20);
  const Image tiled = assembleQuilt(views, 3, 2);
  ASSERT_EQ(quilt.width(), tiled.width());
  for (size_t i = 0; i < quilt.pixels().size(); ++i)
    ASSERT_EQ(quilt.pixels()[i], tiled.pixels()[i]) << i;
}

// Looking Glass's mapping, written out: a subpixel of view fraction f takes views f N - 1/2
// lies between, blended; flat views make it analytic.
TEST(InterlaceQuiltLenticular, EachSubpixelBlendsTheViewsAroundItsFraction) {
  const LenticularDesign d = smallLenticularDesign(40);  // 180 x 40 pixels
  std::vector<Image> views;
  for (int j = 0; j < 10; ++j) views.push_back(flat(30, 20, float(j) / 9.0f));
  const Image panel = interlaceQuiltLenticular(d, views);
  ASSERT_EQ(panel.width(), 180);
  for (int y = 0; y < 40; y += 3)
    for (int x = 0; x < 180; x += 7)
      for (int ch = 0; ch < 3; ++ch) {
        const double position = std::clamp(viewFraction(d, x, y, ch) * 10 - 0.5, 0.0, 9.0);
        EXPECT_NEAR(panel.at(x, y)[ch], position / 9.0, 1e-5) << x << "," << y << "," << ch;
      }
}

// Nearest, brute force: each subpixel shows the one view whose window [i / N, (i + 1) / N) holds
// its view fraction, floor(f N), as Looking Glass's unblended shader mode picks it; and that
// differs from the linear blend wherever f is off a view's centre.
TEST(InterlaceQuiltLenticular, NearestShowsTheViewWhoseWindowHoldsTheFraction) {
  const LenticularDesign d = smallLenticularDesign(40);
  const int n = 10;
  std::vector<Image> views;
  for (int j = 0; j < n; ++j) views.push_back(flat(30, 20, float(j + 1)));
  const Image nearest = interlaceQuiltLenticular(d, views, ViewResampling::Nearest);
  const Image linear = interlaceQuiltLenticular(d, views, ViewResampling::Linear);
  EXPECT_EQ(linear.pixels(), interlaceQuiltLenticular(d, views).pixels());  // the default
  int differ = 0, subpixels = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 180; ++x)
      for (int ch = 0; ch < 3; ++ch) {
        const int view = std::clamp(int(std::floor(viewFraction(d, x, y, ch) * n)), 0, n - 1);
        ASSERT_EQ(nearest.at(x, y)[ch], float(view + 1)) << x << "," << y << "," << ch;
        differ += nearest.at(x, y)[ch] != linear.at(x, y)[ch];
        ++subpixels;
      }
  EXPECT_GT(differ, subpixels / 2);  // only the subpixels at a view's centre agree
}

}  // namespace
}  // namespace parallax
