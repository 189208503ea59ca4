#include "parallax/jobs/video_output.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "parallax/core/error.h"
#include "parallax/io/image_file.h"

namespace parallax::jobs {
namespace {

namespace fs = std::filesystem;

class VideoOutputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("parallax_video_output_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // Picture k: a bright square on a grey-blue background, 4 pixels further right each frame.
  static Image picture(int width, int height, int k) {
    Image image(width, height, Vec3f(0.05f, 0.1f, 0.2f));
    for (int y = height / 4; y < height / 2; ++y)
      for (int x = 4 * k; x < 4 * k + width / 4 && x < width; ++x)
        image.at(x, y) = Vec3f(0.8f, 0.6f, 0.3f);
    return image;
  }

  fs::path dir_;
};

// Mean absolute difference in 8-bit sRGB codes between a decoded frame and a picture.
double meanCodeError(const VideoFrame& frame, const Image& image) {
  double sum = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const Vec3f p = image.at(x, y);
      const float channels[3] = {p.x, p.y, p.z};
      for (int c = 0; c < 3; ++c)
        sum += std::abs(
            double(frame.rgb[(size_t(y) * size_t(frame.width) + size_t(x)) * 3 + size_t(c)]) -
            double(linearToSrgb8(channels[c])));
    }
  return sum / (3.0 * image.width() * image.height());
}

// writeVideo reads the PNGs (io) in the given order and encodes them all: the decoded video has
// their count, size and order, and says so on one printed line.
TEST_F(VideoOutputTest, WritesThePicturesInOrder) {
  std::vector<std::string> pngs;
  std::vector<Image> pictures;
  for (int k = 0; k < 5; ++k) {
    pictures.push_back(picture(80, 45, k));
    std::string name = "p";
    name += std::to_string(k);
    name += ".png";
    pngs.push_back(path(name));
    writeImage(pngs.back(), pictures.back());
  }
  VideoRequest options;
  options.file = path("out/v.mp4");
  options.quality = 18;
  RecordingReporter reporter;
  writeVideo(pngs, options, reporter);
  ASSERT_EQ(reporter.results.size(), 1u);
  const std::string printed = reporter.results[0];
  EXPECT_NE(printed.find(": 5 frames, 80x45 (coded 80x46), h264, "), std::string::npos) << printed;
  EXPECT_NE(printed.find(std::to_string(fs::file_size(options.file)) + " bytes"), std::string::npos)
      << printed;
  const VideoInfo info = probeVideo(options.file, [&](int k, const VideoFrame& f) {
    // Its own picture is much nearer than the next one (the square moved 4 pixels).
    const double own = meanCodeError(f, pictures[size_t(k)]);
    EXPECT_LT(own, 2.0) << "frame " << k;
    if (k + 1 < 5) {
      EXPECT_GT(meanCodeError(f, pictures[size_t(k + 1)]), 2 * own + 1);
    }
  });
  EXPECT_EQ(info.frames, 5);
  EXPECT_EQ(info.width, 80);
  EXPECT_EQ(info.height, 46);
}

TEST_F(VideoOutputTest, RefusesPicturesItCannotUse) {
  writeImage(path("a.png"), picture(32, 32, 0));
  writeImage(path("b.png"), picture(32, 30, 0));
  VideoRequest options;
  options.file = path("v.webm");
  try {
    writeVideo({path("a.png"), path("b.png")}, options);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path("b.png"));  // the picture of another size is named
  }
  EXPECT_THROW(writeVideo({path("a.png"), path("missing.png")}, options), InputError);
  try {
    writeVideo({}, options);
    ADD_FAILURE() << "no error";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.field(), "video");
  }
  options.codec = "h264";
  try {
    writeVideo({path("a.png")}, options);
    ADD_FAILURE() << "no error";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.field(), "video_codec");
  }
  EXPECT_FALSE(fs::exists(path("v.webm")));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 2);
}

}  // namespace
}  // namespace parallax::jobs
