#include "parallax/io/png_encoder.h"

#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <zlib.h>

#include <cstring>
#include <memory>
#include <random>
#include <vector>

namespace parallax {
namespace {

uint32_t bigEndian(const std::string& bytes, size_t at) {
  return uint32_t(uint8_t(bytes[at])) << 24 | uint32_t(uint8_t(bytes[at + 1])) << 16 |
         uint32_t(uint8_t(bytes[at + 2])) << 8 | uint32_t(uint8_t(bytes[at + 3]));
}

// A picture with flat runs, gradients and noise: every PNG filter wins somewhere.
std::vector<uint8_t> picture(int width, int height, int channels, unsigned seed) {
  std::mt19937 random(seed);
  std::vector<uint8_t> codes(size_t(width) * size_t(height) * size_t(channels));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c) {
        const size_t i = (size_t(y) * size_t(width) + size_t(x)) * size_t(channels) + size_t(c);
        codes[i] = x < width / 3       ? uint8_t(40 * c)
                   : x < 2 * width / 3 ? uint8_t(x + 3 * y + 50 * c)
                                       : uint8_t(random());
      }
  return codes;
}

// Every chunk's CRC, and the IDAT chunks' data joined (the zlib stream).
std::string checkChunks(const std::string& png, std::vector<std::string>& types) {
  EXPECT_EQ(png.compare(0, 8, "\x89PNG\r\n\x1a\n"), 0);
  std::string idat;
  for (size_t at = 8; at + 12 <= png.size();) {
    const uint32_t length = bigEndian(png, at);
    const std::string type = png.substr(at + 4, 4);
    const uLong crc =
        crc32(0L, reinterpret_cast<const Bytef*>(png.data() + at + 4), uInt(4 + length));
    EXPECT_EQ(bigEndian(png, at + 8 + length), uint32_t(crc)) << type;
    if (type == "IDAT") idat += png.substr(at + 8, length);
    types.push_back(type);
    at += 12 + length;
  }
  return idat;
}

TEST(PngEncoder, AnIndependentDecoderReadsBackEveryCode) {
  struct Case {
    int width, height, channels;
  };
  // One pixel; one column of many bands; a row wider than a band; grey and RGB.
  for (const Case& c : {Case{1, 1, 3}, Case{1, 3000, 1}, Case{400000, 2, 3}, Case{641, 1203, 3},
                        Case{1920, 1080, 1}}) {
    const std::vector<uint8_t> codes = picture(c.width, c.height, c.channels, 7);
    const std::string png = encodePng(codes.data(), c.width, c.height, c.channels);
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> decoded(
        stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(png.data()), int(png.size()), &width,
                              &height, &channels, 0),
        stbi_image_free);
    ASSERT_TRUE(decoded) << c.width << "x" << c.height << ": " << stbi_failure_reason();
    ASSERT_EQ(width, c.width);
    ASSERT_EQ(height, c.height);
    ASSERT_EQ(channels, c.channels);
    EXPECT_EQ(std::memcmp(decoded.get(), codes.data(), codes.size()), 0)
        << c.width << "x" << c.height;

    // zlib's own decoder accepts the joined stream whole (its Adler-32 included) and finds
    // one filter byte per row before the row's bytes.
    std::vector<std::string> types;
    const std::string idat = checkChunks(png, types);
    EXPECT_EQ(types.front(), "IHDR");
    EXPECT_EQ(types.back(), "IEND");
    std::vector<uint8_t> raw(size_t(c.height) * (size_t(c.width) * size_t(c.channels) + 1) + 1);
    uLongf rawSize = uLongf(raw.size());
    ASSERT_EQ(uncompress(raw.data(), &rawSize, reinterpret_cast<const Bytef*>(idat.data()),
                         uLong(idat.size())),
              Z_OK);
    EXPECT_EQ(rawSize, raw.size() - 1);
  }
}

TEST(PngEncoder, SameBytesForAnyThreadCount) {
  const std::vector<uint8_t> codes = picture(700, 2500, 3, 11);  // several bands
  const std::string one = encodePng(codes.data(), 700, 2500, 3, {2, 1});
  for (int threads : {2, 3, 0}) EXPECT_EQ(encodePng(codes.data(), 700, 2500, 3, {2, threads}), one);
  // A higher level is slower and no larger.
  EXPECT_LE(encodePng(codes.data(), 700, 2500, 3, {9, 0}).size(), one.size());
}

TEST(PngEncoder, RefusesWhatItCannotWrite) {
  const uint8_t code = 0;
  EXPECT_THROW(encodePng(&code, 0, 1, 1), std::invalid_argument);
  EXPECT_THROW(encodePng(&code, 1, 1, 2), std::invalid_argument);
}

}  // namespace
}  // namespace parallax
