#include "parallax/io/animation.h"

#include <gtest/gtest.h>
#include <stb_image.h>

#include <memory>
#include <stdexcept>

#include "parallax/core/random.h"
#include "parallax/io/image_file.h"

namespace parallax {
namespace {

// Bit-at-a-time CRC-32 (no table), a second code path to check the chunks against.
uint32_t referenceCrc(std::string_view bytes) {
  uint32_t crc = 0xFFFFFFFFu;
  for (const char byte : bytes) {
    crc ^= uint8_t(byte);
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1)));
  }
  return ~crc;
}

uint32_t bigEndian32(std::string_view bytes, size_t at = 0) {
  return uint32_t(uint8_t(bytes[at])) << 24 | uint32_t(uint8_t(bytes[at + 1])) << 16 |
         uint32_t(uint8_t(bytes[at + 2])) << 8 | uint32_t(uint8_t(bytes[at + 3]));
}
uint32_t bigEndian16(std::string_view bytes, size_t at) {
  return uint32_t(uint8_t(bytes[at])) << 8 | uint32_t(uint8_t(bytes[at + 1]));
}

struct Chunk {
  std::string type;
  std::string data;
};

// Walks the chunks of a PNG file, checking the signature, lengths and every CRC.
std::vector<Chunk> readChunks(const std::string& png) {
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  std::vector<Chunk> chunks;
  size_t at = 8;
  while (at < png.size()) {
    EXPECT_LE(at + 12, png.size());
    if (at + 12 > png.size()) break;
    const uint32_t length = bigEndian32(png, at);
    EXPECT_LE(at + 12 + length, png.size());
    if (at + 12 + length > png.size()) break;
    Chunk chunk{png.substr(at + 4, 4), png.substr(at + 8, length)};
    EXPECT_EQ(bigEndian32(png, at + 8 + length), referenceCrc(chunk.type + chunk.data))
        << "CRC of chunk " << chunks.size() << " (" << chunk.type << ")";
    chunks.push_back(chunk);
    at += 12 + length;
  }
  return chunks;
}

std::string chunkBytes(const std::string& type, const std::string& data) {
  std::string out;
  for (int shift = 24; shift >= 0; shift -= 8) out += char((data.size() >> shift) & 0xFF);
  out += type + data;
  const uint32_t crc = referenceCrc(type + data);
  for (int shift = 24; shift >= 0; shift -= 8) out += char((crc >> shift) & 0xFF);
  return out;
}

// Decodes a PNG with stb_image and compares every code with the frame's sRGB encoding.
void expectDecodesTo(const std::string& png, const Image& frame) {
  int width = 0, height = 0, channels = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(png.data()), int(png.size()), &width,
                            &height, &channels, 3),
      stbi_image_free);
  ASSERT_TRUE(pixels) << stbi_failure_reason();
  ASSERT_EQ(width, frame.width());
  ASSERT_EQ(height, frame.height());
  int mismatches = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        mismatches += pixels.get()[(y * width + x) * 3 + c] != linearToSrgb8(frame.at(x, y)[c]);
  EXPECT_EQ(mismatches, 0);
}

std::vector<Image> testFrames(int count, int width, int height, bool noise) {
  Rng rng(7);
  std::vector<Image> frames;
  for (int i = 0; i < count; ++i) {
    Image frame(width, height);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        frame.at(x, y) = noise ? Vec3f(rng.uniform(), rng.uniform(), rng.uniform())
                               : Vec3f(float(x) / float(width), float(y) / float(height),
                                       float(i) / float(count));
    frames.push_back(frame);
  }
  return frames;
}

TEST(PngCrc32, MatchesKnownValues) {
  EXPECT_EQ(pngCrc32(""), 0u);
  EXPECT_EQ(pngCrc32("IEND"), 0xAE426082u);       // the CRC every PNG ends with
  EXPECT_EQ(pngCrc32("123456789"), 0xCBF43926u);  // the standard CRC-32 check value
  EXPECT_EQ(referenceCrc("IEND"), 0xAE426082u);
  EXPECT_EQ(referenceCrc("123456789"), 0xCBF43926u);
  const std::string bytes = "\x00\xff\x80 any bytes at all \x7f";
  EXPECT_EQ(pngCrc32(bytes), referenceCrc(bytes));
}

TEST(Apng, ChunksAreInSpecOrderWithConsecutiveSequenceNumbers) {
  const std::vector<Image> frames = testFrames(3, 5, 4, false);
  const std::vector<Chunk> chunks = readChunks(encodeApng(frames, 40, 2));
  std::vector<std::string> types;
  for (const Chunk& chunk : chunks) types.push_back(chunk.type);
  EXPECT_EQ(types, (std::vector<std::string>{"IHDR", "acTL", "fcTL", "IDAT", "fcTL", "fdAT", "fcTL",
                                             "fdAT", "IEND"}));
  ASSERT_EQ(chunks.size(), 9u);
  // IHDR: 5 x 4, bit depth 8, colour type 2 (RGB).
  EXPECT_EQ(bigEndian32(chunks[0].data, 0), 5u);
  EXPECT_EQ(bigEndian32(chunks[0].data, 4), 4u);
  EXPECT_EQ(chunks[0].data[8], 8);
  EXPECT_EQ(chunks[0].data[9], 2);
  // acTL: number of frames, number of plays.
  ASSERT_EQ(chunks[1].data.size(), 8u);
  EXPECT_EQ(bigEndian32(chunks[1].data, 0), 3u);
  EXPECT_EQ(bigEndian32(chunks[1].data, 4), 2u);
  uint32_t expectedSequence = 0;
  for (const Chunk& chunk : chunks) {
    if (chunk.type != "fcTL" && chunk.type != "fdAT") continue;
    EXPECT_EQ(bigEndian32(chunk.data), expectedSequence);
    ++expectedSequence;
    if (chunk.type != "fcTL") continue;
    ASSERT_EQ(chunk.data.size(), 26u);
    EXPECT_EQ(bigEndian32(chunk.data, 4), 5u);   // width
    EXPECT_EQ(bigEndian32(chunk.data, 8), 4u);   // height
    EXPECT_EQ(bigEndian32(chunk.data, 12), 0u);  // x offset
    EXPECT_EQ(bigEndian32(chunk.data, 16), 0u);  // y offset
    // delay = num / den seconds = 40 ms
    EXPECT_DOUBLE_EQ(double(bigEndian16(chunk.data, 20)) / bigEndian16(chunk.data, 22), 0.040);
    EXPECT_EQ(chunk.data[24], 0);  // dispose_op NONE
    EXPECT_EQ(chunk.data[25], 0);  // blend_op SOURCE
  }
  EXPECT_EQ(expectedSequence, 5u);
}

TEST(Apng, FirstFrameIsTheDefaultImageForPlainPngDecoders) {
  const std::vector<Image> frames = testFrames(3, 7, 5, false);
  expectDecodesTo(encodeApng(frames, 100), frames[0]);
}

TEST(Apng, EveryFrameDecodesWhenRebuiltAsAPlainPng) {
  // Large noisy frames compress poorly, so each frame's data spans several chunks.
  const std::vector<Image> frames = testFrames(3, 256, 256, true);
  const std::vector<Chunk> chunks = readChunks(encodeApng(frames, 40));
  std::vector<std::string> imageData;  // per frame, the zlib stream
  size_t fdatChunks = 0;
  std::string header;
  for (const Chunk& chunk : chunks) {
    if (chunk.type == "IHDR") header = chunk.data;
    if (chunk.type == "fcTL") imageData.emplace_back();
    if (chunk.type == "IDAT") imageData.back() += chunk.data;
    if (chunk.type == "fdAT") imageData.back() += chunk.data.substr(4), ++fdatChunks;
  }
  ASSERT_EQ(imageData.size(), frames.size());
  EXPECT_GT(fdatChunks, frames.size() - 1);
  for (size_t i = 0; i < frames.size(); ++i) {
    const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + chunkBytes("IHDR", header) +
                            chunkBytes("IDAT", imageData[i]) + chunkBytes("IEND", "");
    SCOPED_TRACE("frame " + std::to_string(i));
    expectDecodesTo(png, frames[i]);
  }
}

TEST(Apng, AGreyFrameAmongColourFramesKeepsTheColourHeader) {
  // A black frame is grey; alone it would be written with one channel, which the colour
  // frames' header does not describe. Every frame is written as RGB, and decodes as itself.
  std::vector<Image> frames = testFrames(3, 6, 4, false);
  frames[1] = Image(6, 4);  // black
  const std::string apng = encodeApng(frames, 40);
  expectDecodesTo(apng, frames[0]);
  std::vector<std::string> pngs;
  for (const Image& frame : frames) pngs.push_back(pngBytes(frame, false));
  EXPECT_EQ(encodeApngFromPngs(pngs, 40), apng);
  // Frames encoded with different headers are refused.
  pngs[1] = pngBytes(frames[1]);  // one channel
  EXPECT_THROW(encodeApngFromPngs(pngs, 40), std::invalid_argument);
}

TEST(Apng, RejectsBadArguments) {
  const std::vector<Image> frames = testFrames(2, 4, 4, false);
  EXPECT_THROW(encodeApng({}, 40), std::invalid_argument);
  EXPECT_THROW(encodeApng({Image(4, 4), Image(4, 5)}, 40), std::invalid_argument);
  EXPECT_THROW(encodeApng(frames, -1), std::invalid_argument);
  EXPECT_THROW(encodeApng(frames, 65536), std::invalid_argument);
  EXPECT_THROW(encodeApng(frames, 40, -1), std::invalid_argument);
}

TEST(PngBytes, DecodesToTheImagesSrgbCodes) {
  const Image image = testFrames(1, 9, 3, true)[0];
  expectDecodesTo(pngBytes(image), image);
  EXPECT_THROW(pngBytes(Image()), std::invalid_argument);
}

}  // namespace
}  // namespace parallax
