#include "parallax/video/video_writer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "parallax/core/error.h"

namespace parallax {
namespace {

namespace fs = std::filesystem;

class VideoWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // Unique per test and process: CTest runs the tests of this executable in parallel.
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    for (char& c : name)
      if (c == '/') c = '_';
    dir_ = fs::temp_directory_path() /
           ("parallax_video_test_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::vector<std::string> folderEntries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  static std::string readBytes(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }

  fs::path dir_;
};

// Frame k of a test sequence, as 8-bit RGB codes: smooth colour gradients with a soft bright
// blob moving right and down by 3 and 2 pixels a frame, so each frame differs from the next.
std::vector<uint8_t> testFrame(int width, int height, int k) {
  std::vector<uint8_t> rgb(size_t(width) * size_t(height) * 3);
  const double cx = 8 + 3.0 * k, cy = 6 + 2.0 * k, r = 0.18 * std::min(width, height) + 3;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double blob = std::exp(-((x - cx) * (x - cx) + (y - cy) * (y - cy)) / (2 * r * r));
      const double v[3] = {40 + 150.0 * x / width + 60 * blob, 60 + 120.0 * y / height + 70 * blob,
                           180 - 100.0 * x / width + 40 * blob};
      for (int c = 0; c < 3; ++c)
        rgb[(size_t(y) * size_t(width) + size_t(x)) * 3 + size_t(c)] =
            uint8_t(std::lround(std::clamp(v[c], 0.0, 255.0)));
    }
  return rgb;
}

// PSNR in dB of the top-left width x height of a decoded frame against the input's codes
// (10 log10(255^2 / MSE) over all three channels).
double psnr8(const std::vector<uint8_t>& input, int width, int height, const VideoFrame& decoded) {
  double sum = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double a = input[(size_t(y) * size_t(width) + size_t(x)) * 3 + size_t(c)];
        const double b =
            decoded.rgb[(size_t(y) * size_t(decoded.width) + size_t(x)) * 3 + size_t(c)];
        sum += (a - b) * (a - b);
      }
  const double mse = sum / (3.0 * width * height);
  return mse == 0 ? 99.0 : 10 * std::log10(255.0 * 255.0 / mse);
}

struct Case {
  const char* codec;
  const char* file;
  int width, height;
};
void PrintTo(const Case& c, std::ostream* os) {
  *os << c.codec << " " << c.file << " " << c.width << "x" << c.height;
}

class VideoRoundTrip : public VideoWriterTest, public ::testing::WithParamInterface<Case> {};

// At quality 18 every decoded frame is within 35 dB PSNR of its input (smooth content; H.264
// at CRF 18 is usually called visually lossless, about 40-45 dB on such pictures), has the
// coded size (odd sides one more), and the frames come back in their order: frame k is nearer
// its own input than its neighbours' inputs.
TEST_P(VideoRoundTrip, DecodesEveryFrameNearItsInput) {
  const Case& c = GetParam();
  constexpr int kFrames = 12;
  VideoOptions options;
  options.codec = c.codec;
  options.quality = 18;
  options.fps = 30;
  std::vector<std::vector<uint8_t>> inputs;
  VideoWriter writer;
  writer.open(path(c.file), c.width, c.height, options);
  EXPECT_EQ(writer.codec(), c.codec);
  EXPECT_EQ(writer.codedWidth(), c.width + c.width % 2);
  EXPECT_EQ(writer.codedHeight(), c.height + c.height % 2);
  for (int k = 0; k < kFrames; ++k) {
    inputs.push_back(testFrame(c.width, c.height, k));
    writer.addFrame8(inputs.back().data(), c.width, c.height);
  }
  writer.finish();
  EXPECT_EQ(folderEntries(), std::vector<std::string>{c.file});  // no temporary file left

  std::vector<double> own, worstNeighbour;
  const VideoInfo info = probeVideo(path(c.file), [&](int k, const VideoFrame& f) {
    ASSERT_LT(k, kFrames);
    ASSERT_EQ(f.width, writer.codedWidth());
    own.push_back(psnr8(inputs[size_t(k)], c.width, c.height, f));
    double neighbour = 0;
    for (int n : {k - 1, k + 1})
      if (n >= 0 && n < kFrames)
        neighbour = std::max(neighbour, psnr8(inputs[size_t(n)], c.width, c.height, f));
    worstNeighbour.push_back(neighbour);
    // The padding repeats the last column and row: the extra column is near the last one.
    if (f.width > c.width) {
      const size_t last = size_t(c.width - 1) * 3, extra = size_t(c.width) * 3;
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(f.rgb[last + size_t(ch)], f.rgb[extra + size_t(ch)], 12) << "frame " << k;
    }
  });
  EXPECT_EQ(info.frames, kFrames);
  EXPECT_EQ(info.width, c.width + c.width % 2);
  EXPECT_EQ(info.height, c.height + c.height % 2);
  EXPECT_EQ(info.codec, c.codec);
  EXPECT_NEAR(info.fps, 30.0, 1e-9);
  ASSERT_EQ(own.size(), size_t(kFrames));
  for (int k = 0; k < kFrames; ++k) {
    EXPECT_GT(own[size_t(k)], 35.0) << "frame " << k;
    EXPECT_GT(own[size_t(k)], worstNeighbour[size_t(k)] + 3.0) << "frame " << k;
  }
}

// The same frames and options give the same bytes (fixed encoder threads, no times or versions
// in the file), and so the same decoded frames.
TEST_P(VideoRoundTrip, SameFramesGiveSameBytes) {
  const Case& c = GetParam();
  VideoOptions options;
  options.codec = c.codec;
  for (const char* name : {"a", "b"}) {
    VideoWriter writer;
    writer.open(path(std::string(name) + fs::path(c.file).extension().string()), c.width, c.height,
                options);
    for (int k = 0; k < 6; ++k)
      writer.addFrame8(testFrame(c.width, c.height, k).data(), c.width, c.height);
    writer.finish();
  }
  const std::string ext = fs::path(c.file).extension().string();
  const std::string a = readBytes(path("a" + ext)), b = readBytes(path("b" + ext));
  EXPECT_GT(a.size(), 100u);
  EXPECT_TRUE(a == b) << "the two encodes differ (" << a.size() << " and " << b.size() << " bytes)";
}

INSTANTIATE_TEST_SUITE_P(
    Codecs, VideoRoundTrip,
    ::testing::Values(Case{"h264", "even.mp4", 64, 48}, Case{"h264", "odd.mp4", 65, 37},
                      Case{"h265", "even.mp4", 64, 48}, Case{"h265", "odd.mp4", 65, 37},
                      Case{"vp9", "even.webm", 64, 48}, Case{"vp9", "odd.webm", 65, 37},
                      Case{"h264", "any.mkv", 64, 48}, Case{"vp9", "any.mkv", 65, 37}),
    [](const auto& p) {
      return std::string(p.param.codec) + "_" + fs::path(p.param.file).stem().string() + "_" +
             fs::path(p.param.file).extension().string().substr(1);
    });

// addFrame takes linear light and encodes the sRGB codes image/image.h makes; decodeVideoFrame
// gives linear light back: the round trip is near in the sRGB codes.
TEST_F(VideoWriterTest, LinearImagesRoundTripThroughSrgb) {
  const int w = 48, h = 32;
  std::vector<Image> images;
  for (int k = 0; k < 4; ++k) {
    const std::vector<uint8_t> codes = testFrame(w, h, k);
    Image image(w, h);
    for (size_t i = 0; i < image.pixels().size(); ++i)
      image.pixels()[i] = Vec3f(srgb8ToLinear(codes[3 * i]), srgb8ToLinear(codes[3 * i + 1]),
                                srgb8ToLinear(codes[3 * i + 2]));
    images.push_back(image);
  }
  VideoWriter writer;
  writer.open(path("linear.mp4"), w, h, {"h264", 18, 30});
  for (const Image& image : images) writer.addFrame(image);
  writer.finish();
  const Image decoded = decodeVideoFrame(path("linear.mp4"), 2);
  ASSERT_EQ(decoded.width(), w);
  ASSERT_EQ(decoded.height(), h);
  double sum = 0;
  for (size_t i = 0; i < decoded.pixels().size(); ++i) {
    const Vec3f a = images[2].pixels()[i], b = decoded.pixels()[i];
    for (const auto& [p, q] : {std::pair{a.x, b.x}, {a.y, b.y}, {a.z, b.z}}) {
      const double d = double(linearToSrgb8(p)) - double(linearToSrgb8(q));
      sum += d * d;
    }
  }
  EXPECT_GT(10 * std::log10(255.0 * 255.0 / (sum / (3.0 * w * h))), 35.0);
  EXPECT_THROW(decodeVideoFrame(path("linear.mp4"), 4), InputError);
}

// "auto" picks by the extension, and H.265 for MP4 above 4096 a side.
TEST_F(VideoWriterTest, AutoCodecFollowsContainerAndSize) {
  const VideoOptions automatic;
  EXPECT_EQ(resolveVideoCodec("a.mp4", automatic, 1920, 1080), "h264");
  EXPECT_EQ(resolveVideoCodec("a.mp4", automatic, 4096, 4096), "h264");
  EXPECT_EQ(resolveVideoCodec("a.MP4", automatic, 4097, 100), "h265");
  EXPECT_EQ(resolveVideoCodec("a.mp4", automatic, 100, 8192), "h265");
  EXPECT_EQ(resolveVideoCodec("a.webm", automatic, 8192, 8192), "vp9");
  EXPECT_EQ(resolveVideoCodec("a.mkv", automatic, 640, 480), "h264");
  VideoWriter writer;
  writer.open(path("auto.webm"), 32, 32);
  writer.addFrame8(testFrame(32, 32, 0).data(), 32, 32);
  writer.finish();
  EXPECT_EQ(probeVideo(path("auto.webm")).codec, "vp9");
}

// The frame rate is stored as a fraction and read back.
TEST_F(VideoWriterTest, FrameRateIsKept) {
  for (const double fps : {24.0, 30000.0 / 1001.0, 60.0}) {
    for (const char* file : {"rate.mp4", "rate.webm"}) {
      VideoWriter writer;
      writer.open(path(file), 32, 32, {"auto", 30, fps});
      for (int k = 0; k < 5; ++k) writer.addFrame8(testFrame(32, 32, k).data(), 32, 32);
      writer.finish();
      const VideoInfo info = probeVideo(path(file));
      EXPECT_EQ(info.frames, 5) << file;
      EXPECT_NEAR(info.fps, fps, 1e-3) << file << " at " << fps;
    }
  }
}

// Which request field (or, for a file it reads, which file) an error names.
std::string optionOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const RequestError& e) {
    return e.field();
  } catch (const InputError& e) {
    return e.file();
  }
  return "(no error)";
}

TEST_F(VideoWriterTest, BadInputsNameTheirOption) {
  const std::vector<uint8_t> frame = testFrame(32, 32, 0);
  VideoWriter writer;
  EXPECT_EQ(optionOf([&] { writer.open(path("x.avi"), 32, 32); }), "video");
  try {
    writer.open(path("x.avi"), 32, 32);
  } catch (const RequestError& e) {  // the file's errors carry its path as the value
    EXPECT_EQ(e.value(), path("x.avi"));
    EXPECT_EQ(e.message(), "unknown video extension '.avi': expected .mp4, .webm or .mkv");
  }
  EXPECT_EQ(optionOf([&] { writer.open(path("x"), 32, 32); }), "video");
  fs::create_directories(path("folder.mp4"));
  EXPECT_EQ(optionOf([&] { writer.open(path("folder.mp4"), 32, 32); }), "video");
  EXPECT_EQ(optionOf([&] { writer.open(path("x.mp4"), 0, 32); }), "video");
  // The option a 32x32 open of `file` with `options` blames.
  const auto blamed = [&](const std::string& file, const VideoOptions& options,
                          const VideoFieldNames& names = {}) {
    return optionOf([&] { writer.open(path(file), 32, 32, options, names); });
  };
  EXPECT_EQ(blamed("x.mp4", {"vp9", 23, 30}), "video_codec");
  EXPECT_EQ(blamed("x.webm", {"h264", 23, 30}), "video_codec");
  EXPECT_EQ(blamed("x.mp4", {"mpeg2", 23, 30}), "video_codec");
  EXPECT_EQ(blamed("x.mp4", {"h264", 52, 30}), "video_quality");
  EXPECT_EQ(blamed("x.mp4", {"h264", -1, 30}), "video_quality");
  EXPECT_EQ(blamed("x.webm", {"vp9", 64, 30}), "video_quality");
  EXPECT_NO_THROW(checkVideoOptions(path("x.webm"), {"vp9", 63, 30}));
  EXPECT_EQ(blamed("x.mp4", {"h264", 23, 0}), "fps");
  EXPECT_EQ(blamed("x.mp4", {"h264", 23, NAN}), "fps");
  EXPECT_EQ(blamed("x.mp4", {"h264", 23, 241}), "fps");
  // The caller's names for its options.
  EXPECT_EQ(blamed("x.avi", {}, {"output", "codec", "quality", "rate"}), "output");
  EXPECT_EQ(folderEntries(), std::vector<std::string>{"folder.mp4"});

  // A frame of another size; then finishing without frames.
  writer.open(path("x.mp4"), 32, 32);
  EXPECT_EQ(optionOf([&] { writer.addFrame8(frame.data(), 32, 31); }), "video");
  EXPECT_EQ(optionOf([&] { writer.addFrame(Image(31, 32)); }), "video");
  EXPECT_EQ(optionOf([&] { writer.finish(); }), "video");
  EXPECT_FALSE(writer.isOpen());
  EXPECT_EQ(folderEntries(), std::vector<std::string>{"folder.mp4"});  // no partial file
}

// A writer given up before finish() leaves nothing, not even its temporary file; the file of
// an earlier run stays as it was until a new one is finished.
TEST_F(VideoWriterTest, AbandonedWriterLeavesNoFile) {
  const std::vector<uint8_t> frame = testFrame(32, 32, 0);
  {
    VideoWriter writer;
    writer.open(path("gone.mp4"), 32, 32);
    writer.addFrame8(frame.data(), 32, 32);
    writer.addFrame8(frame.data(), 32, 32);
    ASSERT_EQ(folderEntries().size(), 1u);  // the temporary file
    EXPECT_NE(folderEntries().front(), "gone.mp4");
  }
  EXPECT_TRUE(folderEntries().empty());
  std::ofstream(path("kept.mp4")) << "old";
  {
    VideoWriter writer;
    writer.open(path("kept.mp4"), 32, 32);
    writer.addFrame8(frame.data(), 32, 32);
  }
  EXPECT_EQ(readBytes(path("kept.mp4")), "old");
  EXPECT_EQ(folderEntries(), std::vector<std::string>{"kept.mp4"});
}

// The sizes an encoder refuses are known before any frame: checkVideoSize opens the encoder
// as open() would, and says the same; sizes it takes pass, and no file is made either way.
TEST_F(VideoWriterTest, EncoderSizeLimitsAreKnownBeforeTheFrames) {
  VideoOptions h264;
  h264.codec = "h264";
  VideoOptions h265;
  h265.codec = "h265";
  EXPECT_EQ(optionOf([&] { checkVideoSize(path("wide.mp4"), 20000, 16, h264); }), "video");
  EXPECT_EQ(optionOf([&] { checkVideoSize(path("flat.mp4"), 8192, 16, h265); }), "video");
  EXPECT_EQ(optionOf([&] { checkVideoSize(path("tall.webm"), 16, 16385, {}); }), "video");
  EXPECT_EQ(optionOf([&] { checkVideoSize(path("ok.mp4"), 65, 37, h264); }), "(no error)");
  EXPECT_EQ(optionOf([&] { checkVideoSize(path("ok.webm"), 16, 16384, {}); }), "(no error)");
  EXPECT_TRUE(folderEntries().empty());
  // What checkVideoSize refuses, open() refuses too (no frame needed).
  VideoWriter writer;
  EXPECT_EQ(optionOf([&] { writer.open(path("wide.mp4"), 20000, 16, h264); }), "video");
  EXPECT_EQ(optionOf([&] { writer.open(path("tall.webm"), 16, 16385); }), "video");
  EXPECT_TRUE(folderEntries().empty());
}

// A killed run's FILE.partial-PID goes when the next video of FILE opens.
TEST_F(VideoWriterTest, KilledRunsPartialFilesAreRemoved) {
  std::ofstream(path("x.mp4.partial-999999999")) << "half";
  VideoWriter writer;
  writer.open(path("x.mp4"), 32, 32);
  const std::vector<uint8_t> frame = testFrame(32, 32, 0);
  writer.addFrame8(frame.data(), 32, 32);
  writer.finish();
  EXPECT_EQ(folderEntries(), std::vector<std::string>{"x.mp4"});
}

TEST_F(VideoWriterTest, ProbeRefusesWhatIsNoVideo) {
  std::ofstream(path("text.mp4")) << "not a video at all";
  EXPECT_EQ(optionOf([&] { probeVideo(path("text.mp4")); }), path("text.mp4"));
  EXPECT_EQ(optionOf([&] { probeVideo(path("missing.mp4")); }), path("missing.mp4"));
  EXPECT_EQ(optionOf([&] { probeVideo(dir_.string()); }), dir_.string());
}

}  // namespace
}  // namespace parallax
