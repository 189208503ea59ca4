#include "parallax/io/image_file.h"

#include <gtest/gtest.h>
#include <stb_image.h>
#include <stb_image_write.h>
#include <unistd.h>

#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "parallax/core/error.h"

namespace parallax {
namespace {

namespace fs = std::filesystem;

class ImageFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // Unique per test and process: CTest runs the tests of this executable in parallel.
    dir_ = fs::temp_directory_path() /
           ("parallax_image_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void writeBytes(const std::string& name, const std::string& bytes) const {
    std::ofstream(path(name), std::ios::binary) << bytes;
  }
  std::string readBytes(const std::string& name) const {
    std::ifstream in(path(name), std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::vector<std::string> folderEntries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path dir_;
};

std::string floatBytes(float v, bool littleEndian) {
  const auto bits = std::bit_cast<uint32_t>(v);
  std::string out;
  for (int i = 0; i < 4; ++i) out += char((bits >> (8 * (littleEndian ? i : 3 - i))) & 0xFF);
  return out;
}

// ---- An independent minimal PNG encoder (stored deflate blocks), for files stb cannot write.
uint32_t crc32(const std::string& bytes) {  // ISO 3309 / PNG spec, bit by bit
  uint32_t crc = 0xFFFFFFFFu;
  for (unsigned char b : bytes) {
    crc ^= b;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}
std::string bigEndian32(uint32_t v) {
  return {char(v >> 24), char((v >> 16) & 0xFF), char((v >> 8) & 0xFF), char(v & 0xFF)};
}
std::string pngChunk(const std::string& type, const std::string& data) {
  return bigEndian32(uint32_t(data.size())) + type + data + bigEndian32(crc32(type + data));
}
std::string storedPng(int width, int height, int bitDepth, int colorType, const std::string& rows) {
  std::string ihdr = bigEndian32(uint32_t(width)) + bigEndian32(uint32_t(height));
  ihdr += {char(bitDepth), char(colorType), 0, 0, 0};
  uint32_t a = 1, b = 0;  // Adler-32 (RFC 1950)
  for (unsigned char c : rows) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  const auto len = uint16_t(rows.size());
  std::string zlib = {0x78,
                      0x01,
                      0x01,
                      char(len & 0xFF),
                      char(len >> 8),
                      char(~len & 0xFF),
                      char((~len >> 8) & 0xFF)};
  zlib += rows + bigEndian32((b << 16) | a);
  return std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", ihdr) + pngChunk("IDAT", zlib) +
         pngChunk("IEND", "");
}

TEST_F(ImageFileTest, PngRoundTripKeepsEvery8BitCode) {
  Image image(256, 2);
  for (int x = 0; x < 256; ++x) {
    image.at(x, 0) = {srgb8ToLinear(uint8_t(x)), srgb8ToLinear(uint8_t(255 - x)),
                      srgb8ToLinear(uint8_t((x * 7) % 256))};
    image.at(x, 1) = Vec3f(srgb8ToLinear(uint8_t((x * 13) % 256)));
  }
  writeImage(path("codes.png"), image);
  const Image back = readImage(path("codes.png"));
  ASSERT_EQ(back.width(), 256);
  ASSERT_EQ(back.height(), 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 256; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(back.at(x, y)[c], image.at(x, y)[c]) << x << "," << y;
}

TEST_F(ImageFileTest, PngHoldsHandComputedSrgbCodes) {
  // Codes from IEC 61966-2-1 evaluated by hand (double precision, then rounded):
  // 0.5 -> 187.516, 0.18 -> 117.646, 0.001 -> 3.295, 0.05 -> 63.189, 0.75 -> 224.610.
  const float linear[] = {0.0f, 1.0f, 0.5f, 0.18f, 0.001f, 0.05f, 0.75f, 2.0f, -1.0f};
  const int expected[] = {0, 255, 188, 118, 3, 63, 225, 255, 0};
  Image image(9, 1);
  for (int x = 0; x < 9; ++x) image.at(x, 0) = {linear[x], linear[8 - x], 0.5f};
  writeImage(path("known.png"), image);
  // Decode with stb directly, bypassing readImage's linearisation.
  int w = 0, h = 0, channels = 0;
  stbi_uc* codes = stbi_load(path("known.png").c_str(), &w, &h, &channels, 0);
  ASSERT_NE(codes, nullptr);
  ASSERT_EQ(w, 9);
  ASSERT_EQ(h, 1);
  ASSERT_EQ(channels, 3);
  for (int x = 0; x < 9; ++x) {
    EXPECT_EQ(codes[3 * x + 0], expected[x]) << "x=" << x;
    EXPECT_EQ(codes[3 * x + 1], expected[8 - x]) << "x=" << x;
    EXPECT_EQ(codes[3 * x + 2], 188);
  }
  stbi_image_free(codes);
}

TEST_F(ImageFileTest, GreyPicturesAreWrittenAsOneChannelAndReadBackTheSame) {
  Image grey(256, 1), colour(2, 1);
  for (int x = 0; x < 256; ++x) grey.at(x, 0) = Vec3f(srgb8ToLinear(uint8_t(x)));
  colour.at(0, 0) = Vec3f(0.5f);
  colour.at(1, 0) = {0.5f, 0.5f, 0.51f};  // one channel off: stays RGB
  writeImage(path("grey.png"), grey);
  writeImage(path("colour.png"), colour);
  int w = 0, h = 0, channels = 0;
  ASSERT_TRUE(stbi_info(path("grey.png").c_str(), &w, &h, &channels));
  EXPECT_EQ(channels, 1);
  ASSERT_TRUE(stbi_info(path("colour.png").c_str(), &w, &h, &channels));
  EXPECT_EQ(channels, 3);
  const Image back = readImage(path("grey.png"));
  for (int x = 0; x < 256; ++x) EXPECT_EQ(back.at(x, 0), grey.at(x, 0)) << x;
}

TEST_F(ImageFileTest, ReadsGreyAlphaPngByDroppingAlpha) {
  const unsigned char greyAlpha[] = {0, 255, 128, 0, 255, 10};  // three pixels, 1 row
  ASSERT_TRUE(stbi_write_png(path("ga.png").c_str(), 3, 1, 2, greyAlpha, 6));
  const Image image = readImage(path("ga.png"));
  ASSERT_EQ(image.width(), 3);
  for (int x = 0; x < 3; ++x)
    EXPECT_EQ(image.at(x, 0), Vec3f(srgb8ToLinear(greyAlpha[2 * x]))) << x;
}

TEST_F(ImageFileTest, Reads16BitPngFromAnIndependentEncoder) {
  // 2x2 grey+alpha, 16 bits: rows top to bottom, each with filter byte 0.
  const std::string rows = std::string("\0\x80\x00\xff\xff\xff\xff\x00\x00", 9) +
                           std::string("\0\x03\xe8\x12\x34\x00\x00\xff\xff", 9);
  writeBytes("deep.png", storedPng(2, 2, 16, 4, rows));
  const Image image = readImage(path("deep.png"));
  ASSERT_EQ(image.width(), 2);
  ASSERT_EQ(image.height(), 2);
  // Hand-computed sRGB decodes of code/65535: 32768 -> 0.214048, 65535 -> 1, 1000 -> 0.001181.
  EXPECT_NEAR(image.at(0, 0).y, 0.214048f, 2e-6f);
  EXPECT_NEAR(image.at(1, 0).x, 1.0f, 1e-6f);
  EXPECT_NEAR(image.at(0, 1).z, 0.00118104f, 1e-7f);
  EXPECT_EQ(image.at(1, 1), Vec3f(0.0f));
}

TEST_F(ImageFileTest, PfmRoundTripIsBitExact) {
  Image image(3, 2);
  const float values[] = {0.0f,  -0.0f,   1.0f,    -2.5f,  1e-40f, 3.4e38f, 0.1f,    1e-3f, 7.0f,
                          65504, 1.0e10f, -1e-20f, 0.333f, 42.0f,  0.5f,    1.0e-7f, 9.9f,  -7.0f};
  for (int i = 0; i < 6; ++i)
    image.at(i % 3, i / 3) = {values[3 * i], values[3 * i + 1], values[3 * i + 2]};
  writeImage(path("exact.pfm"), image);
  const Image back = readImage(path("exact.pfm"));
  ASSERT_EQ(back.width(), 3);
  ASSERT_EQ(back.height(), 2);
  EXPECT_EQ(std::memcmp(back.pixels().data(), image.pixels().data(), 6 * sizeof(Vec3f)), 0);
}

TEST_F(ImageFileTest, PfmIsWrittenLittleEndianBottomRowFirst) {
  Image image(1, 2);
  image.at(0, 0) = {1.0f, 2.0f, 3.0f};  // top
  image.at(0, 1) = {4.0f, 5.0f, 6.0f};  // bottom
  writeImage(path("layout.pfm"), image);
  std::string expected = "PF\n1 2\n-1\n";
  for (float v : {4.0f, 5.0f, 6.0f, 1.0f, 2.0f, 3.0f}) expected += floatBytes(v, true);
  EXPECT_EQ(readBytes("layout.pfm"), expected);
}

TEST_F(ImageFileTest, ReadsBigEndianColourAndLittleEndianGreyPfm) {
  std::string big = "PF\n2 1\n1.0\n";
  for (float v : {0.25f, 0.5f, 0.75f, 8.0f, -1.0f, 1e-30f}) big += floatBytes(v, false);
  writeBytes("big.pfm", big);
  const Image colour = readImage(path("big.pfm"));
  ASSERT_EQ(colour.width(), 2);
  EXPECT_EQ(colour.at(0, 0), Vec3f(0.25f, 0.5f, 0.75f));
  EXPECT_EQ(colour.at(1, 0), Vec3f(8.0f, -1.0f, 1e-30f));

  std::string grey = "Pf 1 3 -0.5 ";  // spaces are whitespace too
  for (float v : {10.0f, 20.0f, 30.0f}) grey += floatBytes(v, true);
  writeBytes("grey.pfm", grey);
  const Image g = readImage(path("grey.pfm"));
  ASSERT_EQ(g.height(), 3);
  EXPECT_EQ(g.at(0, 2), Vec3f(10.0f));  // first row in the file is the bottom
  EXPECT_EQ(g.at(0, 0), Vec3f(30.0f));
}

TEST_F(ImageFileTest, ReadsRadianceHdrAsLinear) {
  // One flat (not run-length encoded) scanline of two RGBE pixels: 128*2^(129-136) = 1.0 and
  // 64*2^(131-136) = 2.0.
  std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 2\n";
  hdr += std::string("\x80\x80\x80\x81\x40\x40\x40\x83", 8);
  writeBytes("tiny.hdr", hdr);
  const Image image = readImage(path("tiny.hdr"));
  ASSERT_EQ(image.width(), 2);
  EXPECT_NEAR(image.at(0, 0).x, 1.0f, 1e-6f);
  EXPECT_NEAR(image.at(1, 0).z, 2.0f, 1e-6f);
}

TEST_F(ImageFileTest, BadFilesThrowInputErrorNamingTheFile) {
  auto expectError = [&](const std::string& name, const std::string& needle) {
    try {
      readImage(path(name));
      ADD_FAILURE() << name << " was read";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path(name));
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expectError("missing.png", "file not found");
  writeBytes("garbage.png", "this is not an image");
  expectError("garbage.png", "not a readable image");
  writeBytes("short.pfm", "PF\n4 4\n-1\n" + floatBytes(1.0f, true));
  expectError("short.pfm", "truncated PFM");
  writeBytes("zero.pfm", "PF\n1 1\n0\n" + std::string(12, '\0'));
  expectError("zero.pfm", "scale must be non-zero");
  writeBytes("header.pfm", "PF\n1 x\n-1\n");
  expectError("header.pfm", "malformed PFM header");
}

TEST_F(ImageFileTest, UnknownWriteExtensionIsAnInputError) {
  EXPECT_THROW(writeImage(path("picture.tiff"), Image(1, 1)), InputError);
  EXPECT_TRUE(folderEntries().empty());
}

TEST_F(ImageFileTest, AtomicWriteCreatesFoldersReplacesAndLeavesNoTemporary) {
  const std::string target = path("a/b/out.txt");
  writeFileAtomically(target, "first");
  writeFileAtomically(target, "second, longer");
  EXPECT_EQ(readBytes("a/b/out.txt"), "second, longer");
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir_ / "a/b"))
    names.push_back(entry.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"out.txt"});
}

TEST_F(ImageFileTest, FailedAtomicWriteLeavesNoPartialTarget) {
  // The folder the target should go in is a file: nothing can be created.
  writeBytes("blocker", "keep me");
  EXPECT_THROW(writeFileAtomically(path("blocker/out.png"), "data"), std::runtime_error);
  EXPECT_EQ(readBytes("blocker"), "keep me");
  // The target is an existing folder: the rename fails and the temporary must go away.
  fs::create_directories(dir_ / "occupied" / "inner");
  EXPECT_THROW(writeFileAtomically(path("occupied"), "data"), std::runtime_error);
  EXPECT_TRUE(fs::is_directory(dir_ / "occupied" / "inner"));
  EXPECT_EQ(folderEntries(), (std::vector<std::string>{"blocker", "occupied"}));
  // writeImage reports the same failure.
  EXPECT_THROW(writeImage(path("blocker/x.pfm"), Image(1, 1)), std::runtime_error);
  EXPECT_EQ(folderEntries(), (std::vector<std::string>{"blocker", "occupied"}));
}

}  // namespace
}  // namespace parallax
