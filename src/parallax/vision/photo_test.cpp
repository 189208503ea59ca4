// Photo headers, decoding with the EXIF orientation, and JPEG encoding. The expected orientations
// are written from the EXIF standard's table (where the stored 0th row and 0th column appear),
// not from the code's own mapping.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/vision/vision.h"

namespace parallax::vision {
namespace {

using Bytes = std::vector<uint8_t>;
constexpr uint64_t kMaxPixels = 100'000'000;

// A smooth picture (JPEG keeps it within a few levels), different in every corner.
Photo gradient(int width, int height) {
  Photo p{width, height, {}};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      p.rgb.push_back(uint8_t(30 + 190 * x / (width - 1)));
      p.rgb.push_back(uint8_t(30 + 190 * y / (height - 1)));
      p.rgb.push_back(uint8_t(120 + 60 * (x + y) / (width + height)));
    }
  return p;
}

// Four flat quadrants: red top-left, green top-right, blue bottom-left, white bottom-right.
enum Corner { TL, TR, BL, BR };
constexpr std::array<std::array<uint8_t, 3>, 4> kQuadrant = {
    {{220, 20, 20}, {20, 220, 20}, {20, 20, 220}, {230, 230, 230}}};
Photo quadrants(int width, int height) {
  Photo p{width, height, {}};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int q = (y >= height / 2 ? 2 : 0) + (x >= width / 2 ? 1 : 0);
      p.rgb.insert(p.rgb.end(), kQuadrant[q].begin(), kQuadrant[q].end());
    }
  return p;
}
// The colour in the middle of one quadrant of the photo.
std::array<uint8_t, 3> quadrantColour(const Photo& p, Corner c) {
  const int x = (c == TR || c == BR) ? 3 * p.width / 4 : p.width / 4;
  const int y = (c == BL || c == BR) ? 3 * p.height / 4 : p.height / 4;
  const size_t at = 3 * (size_t(y) * p.width + x);
  return {p.rgb[at], p.rgb[at + 1], p.rgb[at + 2]};
}
bool near(const std::array<uint8_t, 3>& a, const std::array<uint8_t, 3>& b) {
  for (int i = 0; i < 3; ++i)
    if (std::abs(a[i] - b[i]) > 12) return false;
  return true;
}

void put16(Bytes& b, unsigned v, bool little) {
  if (little) {
    b.insert(b.end(), {uint8_t(v), uint8_t(v >> 8)});
  } else {
    b.insert(b.end(), {uint8_t(v >> 8), uint8_t(v)});
  }
}
void put32(Bytes& b, uint32_t v, bool little) {
  put16(b, little ? v & 0xFFFF : v >> 16, little);
  put16(b, little ? v >> 16 : v & 0xFFFF, little);
}

// A TIFF structure as cameras write it: IFD0 with Make (an offset to its text), the
// orientation, and XResolution (an offset to a rational), sorted by tag.
Bytes exifTiff(bool little, unsigned orientation) {
  Bytes t;
  t.insert(t.end(), little ? "II" : "MM", (little ? "II" : "MM") + 2);
  put16(t, 42, little);
  put32(t, 8, little);
  put16(t, 3, little);
  const uint32_t data = 8 + 2 + 3 * 12 + 4;  // after IFD0
  put16(t, 0x010F, little), put16(t, 2, little), put32(t, 6, little), put32(t, data, little);
  put16(t, 0x0112, little), put16(t, 3, little), put32(t, 1, little);
  put16(t, orientation, little), put16(t, 0, little);
  put16(t, 0x011A, little), put16(t, 5, little), put32(t, 1, little), put32(t, data + 6, little);
  put32(t, 0, little);  // no IFD1
  t.insert(t.end(), {'P', 'h', 'o', 'n', 'e', 0});
  put32(t, 72, little), put32(t, 1, little);
  return t;
}

// `jpeg` with an APP1 EXIF segment holding `tiff` right after SOI.
Bytes withExif(Bytes jpeg, const Bytes& tiff) {
  Bytes app1 = {0xFF, 0xE1};
  put16(app1, unsigned(2 + 6 + tiff.size()), false);
  app1.insert(app1.end(), {'E', 'x', 'i', 'f', 0, 0});
  app1.insert(app1.end(), tiff.begin(), tiff.end());
  jpeg.insert(jpeg.begin() + 2, app1.begin(), app1.end());
  return jpeg;
}

// Where the first frame header's fields are (after its marker and length).
size_t frameHeader(const Bytes& jpeg) {
  for (size_t i = 2; i + 1 < jpeg.size(); ++i)
    if (jpeg[i] == 0xFF && jpeg[i + 1] >= 0xC0 && jpeg[i + 1] <= 0xC2) return i + 4;
  ADD_FAILURE() << "no SOF";
  return 0;
}

uint32_t crc32(const uint8_t* data, size_t n, uint32_t crc = 0) {
  crc = ~crc;
  for (size_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1)));
  }
  return ~crc;
}
void pngChunk(Bytes& png, const char* type, const Bytes& data) {
  put32(png, uint32_t(data.size()), false);
  const size_t start = png.size();
  png.insert(png.end(), type, type + 4);
  png.insert(png.end(), data.begin(), data.end());
  put32(png, crc32(png.data() + start, png.size() - start), false);
}
// An 8-bit RGB PNG, its pixels in stored (uncompressed) deflate blocks, and an eXIf chunk when
// `tiff` is given.
Bytes pngBytes(const Photo& p, const Bytes& tiff = {}) {
  Bytes png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  Bytes ihdr;
  put32(ihdr, uint32_t(p.width), false);
  put32(ihdr, uint32_t(p.height), false);
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});
  pngChunk(png, "IHDR", ihdr);
  if (!tiff.empty()) pngChunk(png, "eXIf", tiff);
  Bytes raw;
  for (int y = 0; y < p.height; ++y) {
    raw.push_back(0);  // filter: none
    raw.insert(raw.end(), p.rgb.begin() + 3 * y * p.width, p.rgb.begin() + 3 * (y + 1) * p.width);
  }
  Bytes z = {0x78, 0x01};
  for (size_t at = 0; at < raw.size(); at += 65535) {
    const size_t n = std::min<size_t>(65535, raw.size() - at);
    z.push_back(at + n == raw.size() ? 1 : 0);
    put16(z, unsigned(n), true);
    put16(z, unsigned(~n & 0xFFFF), true);
    z.insert(z.end(), raw.begin() + at, raw.begin() + at + n);
  }
  uint32_t a = 1, b = 0;  // Adler-32
  for (uint8_t v : raw) a = (a + v) % 65521, b = (b + a) % 65521;
  put32(z, b << 16 | a, false);
  pngChunk(png, "IDAT", z);
  pngChunk(png, "IEND", {});
  return png;
}

// The message of the InputError that reading `bytes` throws ("" if none).
std::string refusal(const Bytes& bytes, uint64_t maxPixels = kMaxPixels) {
  try {
    readPhotoHeader(bytes, "shot.jpg", maxPixels);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "shot.jpg");
    return e.what();
  }
  return "";
}

TEST(PhotoHeader, ReadsTheEncodersJpeg) {
  const Bytes jpeg = encodeJpeg(gradient(40, 30), 90);
  const PhotoHeader h = readPhotoHeader(jpeg, "a.jpg", kMaxPixels);
  EXPECT_EQ(h.format, PhotoFormat::Jpeg);
  EXPECT_EQ(h.storedWidth, 40);
  EXPECT_EQ(h.storedHeight, 30);
  EXPECT_EQ(h.orientation, 1);
  EXPECT_EQ(h.width, 40);
  EXPECT_EQ(h.height, 30);
  EXPECT_GE(h.decodeBytes, 40u * 30 * 3 * 2);
}

TEST(PhotoHeader, ReadsExifOrientationInBothByteOrders) {
  const Bytes plain = encodeJpeg(gradient(40, 30), 90);
  for (bool little : {true, false})
    for (unsigned o = 1; o <= 8; ++o) {
      const PhotoHeader h = readPhotoHeader(withExif(plain, exifTiff(little, o)), "a", kMaxPixels);
      EXPECT_EQ(h.orientation, int(o)) << little;
      EXPECT_EQ(h.storedWidth, 40);
      EXPECT_EQ(h.width, o >= 5 ? 30 : 40) << o;
      EXPECT_EQ(h.height, o >= 5 ? 40 : 30) << o;
    }
}

TEST(PhotoHeader, ReadsPngAndItsExif) {
  const Photo p = gradient(7, 5);
  PhotoHeader h = readPhotoHeader(pngBytes(p), "a.png", kMaxPixels);
  EXPECT_EQ(h.format, PhotoFormat::Png);
  EXPECT_EQ(h.storedWidth, 7);
  EXPECT_EQ(h.storedHeight, 5);
  EXPECT_EQ(h.orientation, 1);
  h = readPhotoHeader(pngBytes(p, exifTiff(true, 6)), "a.png", kMaxPixels);
  EXPECT_EQ(h.orientation, 6);
  EXPECT_EQ(h.width, 5);
  EXPECT_EQ(h.height, 7);
}

TEST(PhotoHeader, ProgressiveJpegNeedsMoreMemory) {
  Bytes jpeg = encodeJpeg(gradient(40, 30), 90);
  const uint64_t baseline = readPhotoHeader(jpeg, "a", kMaxPixels).decodeBytes;
  jpeg[frameHeader(jpeg) - 3] = 0xC2;  // SOF0 -> SOF2 (the header is all that is read)
  EXPECT_GT(readPhotoHeader(jpeg, "a", kMaxPixels).decodeBytes, baseline);
}

TEST(PhotoHeader, RefusesOtherFiles) {
  EXPECT_NE(refusal({}).find("not a JPEG or PNG photo"), std::string::npos);
  EXPECT_NE(refusal({'G', 'I', 'F', '8', '9', 'a', 1, 0, 1, 0}).find("not a JPEG or PNG"),
            std::string::npos);
  EXPECT_NE(refusal({0xFF, 0xD8}).find("not a JPEG or PNG"), std::string::npos);
}

TEST(PhotoHeader, RefusesTooManyPixels) {
  Bytes jpeg = encodeJpeg(gradient(40, 30), 90);
  const size_t sof = frameHeader(jpeg);
  jpeg[sof + 1] = 9000 >> 8, jpeg[sof + 2] = 9000 & 0xFF;    // height
  jpeg[sof + 3] = 12000 >> 8, jpeg[sof + 4] = 12000 & 0xFF;  // width
  EXPECT_EQ(refusal(jpeg), "shot.jpg: 12000x9000 pixels is more than the 100000000 allowed");
  EXPECT_EQ(refusal(jpeg, 108'000'000), "");
  jpeg[sof + 1] = jpeg[sof + 2] = 0;
  EXPECT_NE(refusal(jpeg).find("12000x0 pixels, which is none"), std::string::npos);
}

TEST(PhotoHeader, RefusesEveryTruncatedHeader) {
  const Bytes jpeg = withExif(encodeJpeg(gradient(40, 30), 90), exifTiff(true, 6));
  size_t sos = 0;
  for (size_t i = 2; i + 1 < jpeg.size() && !sos; ++i)
    if (jpeg[i] == 0xFF && jpeg[i + 1] == 0xDA) sos = i;
  const size_t headerEnd = sos + 2 + (jpeg[sos + 2] << 8 | jpeg[sos + 3]);
  for (size_t n = 0; n < headerEnd; ++n)
    EXPECT_NE(refusal(Bytes(jpeg.begin(), jpeg.begin() + n)), "") << n;
  EXPECT_EQ(refusal(Bytes(jpeg.begin(), jpeg.begin() + headerEnd)), "");
  const Bytes png = pngBytes(gradient(7, 5), exifTiff(false, 3));
  const size_t idat = 33 + 12 + exifTiff(false, 3).size();
  for (size_t n = 0; n < idat + 8; ++n)
    EXPECT_NE(refusal(Bytes(png.begin(), png.begin() + n)), "") << n;
  EXPECT_EQ(refusal(Bytes(png.begin(), png.begin() + idat + 8)), "");
}

TEST(PhotoHeader, RefusesLyingExif) {
  const Bytes plain = encodeJpeg(gradient(40, 30), 90);
  Bytes tiff = exifTiff(false, 9);
  EXPECT_NE(refusal(withExif(plain, tiff)).find("EXIF orientation 9, not 1 to 8"),
            std::string::npos);
  tiff = exifTiff(false, 0);
  EXPECT_NE(refusal(withExif(plain, tiff)).find("EXIF orientation 0"), std::string::npos);
  tiff = exifTiff(true, 1);
  tiff[4] = 0xF0;  // IFD0 beyond the block
  EXPECT_NE(refusal(withExif(plain, tiff)).find("lies outside it"), std::string::npos);
  tiff = exifTiff(true, 1);
  tiff[8] = 0xFF;  // 255 entries in a block of 3
  EXPECT_NE(refusal(withExif(plain, tiff)).find("truncated EXIF block"), std::string::npos);
  tiff = exifTiff(true, 1);
  tiff[0] = tiff[1] = 'X';
  EXPECT_NE(refusal(withExif(plain, tiff)).find("byte order"), std::string::npos);
  // A segment length running past the end of the file.
  Bytes jpeg = withExif(plain, exifTiff(true, 1));
  jpeg[4] = 0xFF;
  EXPECT_NE(refusal(Bytes(jpeg.begin(), jpeg.begin() + 300)).find("truncated JPEG header"),
            std::string::npos);
  // Only the first EXIF block counts (as in the decoders): a second one is not read.
  jpeg = withExif(withExif(plain, exifTiff(true, 9)), exifTiff(true, 3));
  EXPECT_EQ(readPhotoHeader(jpeg, "a", kMaxPixels).orientation, 3);
}

TEST(PhotoHeader, RefusesJpegsNoCameraWrites) {
  Bytes jpeg = encodeJpeg(gradient(40, 30), 90);
  const size_t sof = frameHeader(jpeg);
  Bytes lossless = jpeg;
  lossless[sof - 3] = 0xC3;
  EXPECT_NE(refusal(lossless).find("lossless"), std::string::npos);
  Bytes twelveBit = jpeg;
  twelveBit[sof] = 12;
  EXPECT_NE(refusal(twelveBit).find("12-bit JPEG"), std::string::npos);
  Bytes twoComponents = jpeg;
  twoComponents[sof + 5] = 2;
  EXPECT_NE(refusal(twoComponents).find("2 colour components"), std::string::npos);
}

// decodePhoto on a JPEG whose stored picture has four quadrants and the orientation tag `o`:
// where the stored top-left and top-right quadrants appear, as the EXIF standard's table says
// ("0th row at the visual top/bottom/left/right, 0th column at ...").
TEST(DecodePhoto, AppliesEveryExifOrientationAsTheStandardSays) {
  struct Expect {
    int orientation;
    Corner storedTopLeft, storedTopRight;
  };
  const Expect table[] = {
      {1, TL, TR},  // 0th row top, 0th column left
      {2, TR, TL},  // top, right
      {3, BR, BL},  // bottom, right
      {4, BL, BR},  // bottom, left
      {5, TL, BL},  // 0th row left, 0th column top
      {6, TR, BR},  // right, top
      {7, BR, TR},  // right, bottom
      {8, BL, TL},  // left, bottom
  };
  const Photo stored = quadrants(64, 32);
  const Bytes plain = encodeJpeg(stored, 95);
  for (bool little : {true, false})
    for (const Expect& e : table) {
      const Photo p = decodePhoto(withExif(plain, exifTiff(little, unsigned(e.orientation))),
                                  "a.jpg", kMaxPixels);
      const bool turned = e.orientation >= 5;
      EXPECT_EQ(p.width, turned ? 32 : 64) << e.orientation;
      EXPECT_EQ(p.height, turned ? 64 : 32) << e.orientation;
      EXPECT_TRUE(near(quadrantColour(p, e.storedTopLeft), kQuadrant[TL])) << e.orientation;
      EXPECT_TRUE(near(quadrantColour(p, e.storedTopRight), kQuadrant[TR])) << e.orientation;
    }
}

TEST(DecodePhoto, PngIsExactAndTurned) {
  const Photo stored = gradient(9, 4);
  const Photo same = decodePhoto(pngBytes(stored), "a.png", kMaxPixels);
  EXPECT_EQ(same.width, 9);
  EXPECT_EQ(same.height, 4);
  EXPECT_EQ(same.rgb, stored.rgb);
  // Orientation 6: the stored 0th row is the right-hand column, read top to bottom.
  const Photo turned = decodePhoto(pngBytes(stored, exifTiff(false, 6)), "a.png", kMaxPixels);
  ASSERT_EQ(turned.width, 4);
  ASSERT_EQ(turned.height, 9);
  for (int i = 0; i < 9; ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(turned.rgb[3 * (i * 4 + 3) + c], stored.rgb[3 * i + c]) << i;
}

TEST(DecodePhoto, RefusesWhatDoesNotDecode) {
  Bytes png = pngBytes(gradient(9, 4));
  png[png.size() - 20] ^= 0xFF;  // the image data's checksum no longer matches
  EXPECT_THROW(decodePhoto(png, "a.png", kMaxPixels), InputError);
  EXPECT_THROW(decodePhoto(Bytes{1, 2, 3}, "a.png", kMaxPixels), InputError);
  // A JPEG cut anywhere in its image data decodes in part or not at all: never another error.
  const Bytes jpeg = encodeJpeg(gradient(40, 30), 90);
  for (size_t n = 0; n < jpeg.size(); n += 7) {
    try {
      const Photo p = decodePhoto(Bytes(jpeg.begin(), jpeg.begin() + n), "a.jpg", kMaxPixels);
      EXPECT_EQ(p.width, 40);
      EXPECT_EQ(p.height, 30);
    } catch (const InputError&) {
    }
  }
}

TEST(EncodeJpeg, RoundTripsEveryOrientation) {
  const Photo photo = gradient(48, 36);
  for (int o = 1; o <= 8; ++o) {
    const Bytes jpeg = encodeJpeg(photo, 95, o);
    const PhotoHeader h = readPhotoHeader(jpeg, "a.jpg", kMaxPixels);
    EXPECT_EQ(h.orientation, o);
    EXPECT_EQ(h.storedWidth, o >= 5 ? 36 : 48) << o;
    const Photo back = decodePhoto(jpeg, "a.jpg", kMaxPixels);
    ASSERT_EQ(back.width, 48) << o;
    ASSERT_EQ(back.height, 36) << o;
    double sum = 0;
    int worst = 0;
    for (size_t i = 0; i < photo.rgb.size(); ++i) {
      const int d = std::abs(int(back.rgb[i]) - int(photo.rgb[i]));
      sum += d;
      worst = std::max(worst, d);
    }
    EXPECT_LT(sum / double(photo.rgb.size()), 1.5) << o;
    EXPECT_LE(worst, 10) << o;
  }
}

}  // namespace
}  // namespace parallax::vision
