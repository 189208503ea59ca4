// A frame split by bands of rows (RenderSettings::bandParts, docs/distributed.md): the parts
// render only their own bands, leave every other pixel all-zero bits, and OR-ed together make
// the one-process picture bit for bit, with adaptive sampling too.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>

#include "parallax/render/render.h"

namespace parallax {
namespace {

uint32_t bitsOf(float value) {
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

void expectPartsMakeTheWhole(const RenderSettings& settings, int parts) {
  const Scene scene = defaultScene();
  const Accelerator accel(scene);
  const CameraSpec& c = *scene.camera;
  // 53 rows: the last band is 5 rows short of 16.
  const PinholeCamera camera(c.eye, c.lookAt, c.up, c.fovDegrees, 70, 53);
  RenderStats wholeStats;
  const Image whole = render(scene, accel, camera, settings, &wholeStats);
  std::vector<uint32_t> merged(size_t(whole.width()) * whole.height() * 3, 0);
  uint64_t cameraRays = 0;
  for (int part = 0; part < parts; ++part) {
    RenderSettings share = settings;
    share.bandParts = parts;
    share.bandPart = part;
    RenderStats stats;
    const Image image = render(scene, accel, camera, share, &stats);
    cameraRays += stats.cameraRays;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x)
        for (int k = 0; k < 3; ++k) {
          const uint32_t bits = bitsOf(image.at(x, y)[k]);
          const bool mine = (y / 16) % parts == part;
          if (!mine) {
            EXPECT_EQ(bits, 0u) << "part " << part << " wrote row " << y;
          }
          merged[(size_t(y) * image.width() + x) * 3 + k] |= bits;
        }
  }
  for (int y = 0; y < whole.height(); ++y)
    for (int x = 0; x < whole.width(); ++x)
      for (int k = 0; k < 3; ++k)
        ASSERT_EQ(merged[(size_t(y) * whole.width() + x) * 3 + k], bitsOf(whole.at(x, y)[k]))
            << parts << " parts, pixel " << x << "," << y;
  EXPECT_EQ(cameraRays, wholeStats.cameraRays);
}

TEST(BandSplit, PartsMakeTheWholePicture) {
  RenderSettings settings;
  settings.samplesPerPixel = 4;
  for (int parts : {1, 2, 3, 5}) expectPartsMakeTheWhole(settings, parts);
}

TEST(BandSplit, AdaptiveSamplingSplitsToo) {
  RenderSettings settings;
  settings.samplesPerPixel = 16;
  settings.adaptive = true;
  for (int parts : {2, 3}) expectPartsMakeTheWhole(settings, parts);
}

TEST(BandSplit, MorePartsThanBandsLeavesSomeEmpty) {
  const Scene scene = defaultScene();
  const Accelerator accel(scene);
  const CameraSpec& c = *scene.camera;
  const PinholeCamera camera(c.eye, c.lookAt, c.up, c.fovDegrees, 20, 20);  // 2 bands
  RenderSettings share;
  share.bandParts = 4;
  share.bandPart = 3;
  RenderStats stats;
  const Image image = render(scene, accel, camera, share, &stats);
  EXPECT_EQ(stats.cameraRays, 0u);
  for (const Vec3f& p : image.pixels()) EXPECT_EQ(bitsOf(p.x) | bitsOf(p.y) | bitsOf(p.z), 0u);
}

}  // namespace
}  // namespace parallax
