// RGB-D files: a 16-bit grey depth PNG keeps its 16 bits (written by encodePngGrey16, read back
// by readImageSamples), the loader's scene matches the analytic unprojection, and bad input is
// refused naming the file.
#include "parallax/io/rgbd_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/io/image_file.h"
#include "parallax/io/png_encoder.h"

namespace parallax {
namespace {

namespace fs = std::filesystem;

class RgbdFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("parallax_rgbd_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // A 16-bit depth PNG of the codes, width x height.
  std::string writeDepth16(const std::string& name, const std::vector<uint16_t>& codes, int width,
                           int height) const {
    writeFileAtomically(path(name), encodePngGrey16(codes.data(), width, height));
    return path(name);
  }
  std::string writeColour(const std::string& name, int width, int height) const {
    Image image(width, height);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        image.at(x, y) = {float(x) / float(width), float(y) / float(height), 0.5f};
    writeImage(path(name), image);
    return path(name);
  }

  // The message of the InputError `f` throws (a failure if it throws none).
  template <typename F>
  std::string errorOf(F f) {
    try {
      f();
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no InputError";
    return "";
  }

  fs::path dir_;
};

TEST_F(RgbdFileTest, SixteenBitGreyPngKeepsEveryCode) {
  const int w = 7, h = 3;
  std::vector<uint16_t> codes(size_t(w * h));
  // Codes whose low bytes differ from their high bytes, and the extremes.
  for (size_t i = 0; i < codes.size(); ++i) codes[i] = uint16_t((i * 3119u + 1u) % 65536u);
  codes[0] = 0;
  codes[1] = 65535;
  codes[2] = 256;
  codes[3] = 255;
  const std::string file = writeDepth16("depth.png", codes, w, h);
  const ImageSamples s = readImageSamples(file);
  ASSERT_EQ(s.width, w);
  ASSERT_EQ(s.height, h);
  EXPECT_EQ(s.channels, 1);
  EXPECT_EQ(s.bitsPerSample, 16);
  for (size_t i = 0; i < codes.size(); ++i)
    EXPECT_EQ(std::lround(double(s.samples[i]) * 65535.0), long(codes[i])) << i;
}

TEST_F(RgbdFileTest, EightBitGreyIsReadWithoutTheTransferFunction) {
  // An 8-bit grey PNG of code 128 (the sRGB PNG writer's grey picture is one channel): the
  // depth is 128 / 255, not the sRGB-decoded 0.216.
  Image grey(4, 4, Vec3f(srgb8ToLinear(128)));
  writeImage(path("grey.png"), grey);
  const ImageSamples s = readImageSamples(path("grey.png"));
  EXPECT_EQ(s.channels, 1);
  EXPECT_EQ(s.bitsPerSample, 8);
  EXPECT_FLOAT_EQ(s.samples[5], 128.0f / 255.0f);
}

TEST_F(RgbdFileTest, SceneFollowsTheSixteenBitDepth) {
  const int w = 5, h = 3;
  // Neighbouring codes 1 apart stay apart: 8 bits would merge them.
  std::vector<uint16_t> codes(size_t(w * h), 30000);
  codes[size_t(1 * w + 2)] = 30001;  // the centre pixel
  const std::string depth = writeDepth16("d.png", codes, w, h);
  const std::string colour = writeColour("c.png", w, h);
  RgbdOptions o;  // disparity, 1:3, 50 degrees
  const Scene scene = loadRgbdScene(colour, depth, o);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const auto zOf = [&](double code) {
    const double v = code / 65535.0;
    return 1.0 / (v / 1.0 + (1.0 - v) / 3.0);
  };
  const TriangleMesh& mesh = scene.meshes[0];
  const Vec3f centre = mesh.positions[size_t(1 * w + 2)];
  EXPECT_NEAR(centre.x, 0.0, 1e-6);
  EXPECT_NEAR(centre.y, 0.0, 1e-6);
  EXPECT_NEAR(-centre.z, zOf(30001), 1e-6);
  EXPECT_NEAR(-mesh.positions[0].z, zOf(30000), 1e-6);
  EXPECT_LT(-centre.z, -mesh.positions[0].z);  // brighter is nearer
  EXPECT_TRUE(scene.warnings.empty());
  // The colour image is the texture, linear as read.
  EXPECT_EQ(scene.images.at(0).pixels(), readImage(colour).pixels());
}

TEST_F(RgbdFileTest, GreyDepthSavedAsRgbIsAcceptedColouredIsRefused) {
  const int w = 4, h = 4;
  const std::string colour = writeColour("c.png", w, h);
  Image grey(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) grey.at(x, y) = Vec3f(srgb8ToLinear(uint8_t(40 * x + 10 * y)));
  writeFileAtomically(path("rgb_grey.png"), pngBytes(grey, /*greyAsOneChannel=*/false));
  EXPECT_EQ(readImageSamples(path("rgb_grey.png")).channels, 3);
  const Scene scene = loadRgbdScene(colour, path("rgb_grey.png"), {});
  // Pixel (1, 2): code 60 -> v = 60 / 255.
  const double v = 60.0 / 255.0;
  EXPECT_NEAR(-scene.meshes[0].positions[size_t(2 * w + 1)].z, 1.0 / (v + (1.0 - v) / 3.0), 1e-5);

  grey.at(2, 1) = {0.2f, 0.5f, 0.2f};
  writeFileAtomically(path("coloured.png"), pngBytes(grey, false));
  const std::string message = errorOf([&] { loadRgbdScene(colour, path("coloured.png"), {}); });
  EXPECT_NE(message.find(path("coloured.png")), std::string::npos) << message;
  EXPECT_NE(message.find("greyscale"), std::string::npos) << message;
  EXPECT_NE(message.find("(2, 1)"), std::string::npos) << message;
}

TEST_F(RgbdFileTest, RefusesMissingFilesAndDifferentSizesNamingThem) {
  const std::string colour = writeColour("c.png", 6, 4);
  const std::string depth = writeDepth16("d.png", std::vector<uint16_t>(5 * 4, 100), 5, 4);
  std::string message = errorOf([&] { loadRgbdScene(colour, path("none.png"), {}); });
  EXPECT_NE(message.find(path("none.png")), std::string::npos) << message;
  message = errorOf([&] { loadRgbdScene(path("nothing.png"), depth, {}); });
  EXPECT_NE(message.find(path("nothing.png")), std::string::npos) << message;
  message = errorOf([&] { loadRgbdScene(colour, depth, {}); });
  EXPECT_NE(message.find(depth), std::string::npos) << message;
  EXPECT_NE(message.find("5x4"), std::string::npos) << message;
  EXPECT_NE(message.find("6x4"), std::string::npos) << message;
}

TEST_F(RgbdFileTest, ConstantDepthWarnsAndTooLargeARefusalComesBeforeTheMesh) {
  const std::string colour = writeColour("c.png", 8, 8);
  const std::string depth = writeDepth16("d.png", std::vector<uint16_t>(64, 5000), 8, 8);
  const Scene flat = loadRgbdScene(colour, depth, {});
  ASSERT_EQ(flat.warnings.size(), 1u);
  EXPECT_NE(flat.warnings[0].find("constant"), std::string::npos);
  // A limit below the estimate: refused naming the depth map and the estimate's subject.
  const std::string message = errorOf([&] { loadRgbdScene(colour, depth, {}, 100.0); });
  EXPECT_NE(message.find(depth), std::string::npos) << message;
  EXPECT_NE(message.find("8x8"), std::string::npos) << message;
}

}  // namespace
}  // namespace parallax
