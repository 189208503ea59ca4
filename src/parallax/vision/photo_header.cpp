// readPhotoHeader: our own reader of the few header fields that decide whether a photo may be
// decoded and how it is turned, so that untrusted bytes reach OpenCV's decoders only once their
// size is known and allowed. No OpenCV here: every read is bounds-checked against the span.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "parallax/core/error.h"
#include "parallax/vision/vision.h"

namespace parallax::vision {
namespace {

[[noreturn]] void refuse(const std::string& name, const std::string& why) {
  throw InputError(name, "", why);
}

// `n` bytes at `at` lie inside `size`, written so that no sum can overflow.
bool fits(size_t size, size_t at, size_t n) {
  return at <= size && n <= size - at;
}

uint16_t be16(std::span<const uint8_t> b, size_t at) {
  return uint16_t(b[at] << 8 | b[at + 1]);
}
uint32_t be32(std::span<const uint8_t> b, size_t at) {
  return uint32_t(b[at]) << 24 | uint32_t(b[at + 1]) << 16 | uint32_t(b[at + 2]) << 8 |
         uint32_t(b[at + 3]);
}

// The orientation tag (0x0112) of IFD0 of an EXIF block's TIFF structure (the bytes after
// "Exif\0\0" in JPEG's APP1, a PNG's eXIf chunk); 1 when IFD0 has none.
int exifOrientation(std::span<const uint8_t> tiff, const std::string& name) {
  if (tiff.size() < 8) refuse(name, "truncated EXIF block");
  bool little;
  if (tiff[0] == 'I' && tiff[1] == 'I') {
    little = true;
  } else if (tiff[0] == 'M' && tiff[1] == 'M') {
    little = false;
  } else {
    refuse(name, "EXIF block without a TIFF byte order (II or MM)");
  }
  const auto u16 = [&](size_t at) {
    return little ? uint16_t(tiff[at] | tiff[at + 1] << 8) : be16(tiff, at);
  };
  const auto u32 = [&](size_t at) {
    return little ? uint32_t(u16(at)) | uint32_t(u16(at + 2)) << 16 : be32(tiff, at);
  };
  if (u16(2) != 42) refuse(name, "EXIF block without the TIFF magic number 42");
  const size_t ifd = u32(4);
  if (!fits(tiff.size(), ifd, 2)) refuse(name, "EXIF block whose first directory lies outside it");
  const size_t entries = u16(ifd);
  if ((tiff.size() - ifd - 2) / 12 < entries) refuse(name, "truncated EXIF block");
  for (size_t i = 0; i < entries; ++i) {
    const size_t entry = ifd + 2 + 12 * i;
    if (u16(entry) != 0x0112) continue;
    const uint16_t type = u16(entry + 2);
    const uint32_t count = u32(entry + 4);
    // SHORT as the standard says; LONG from a few writers. Either sits in the value field.
    if ((type != 3 && type != 4) || count != 1)
      refuse(name, "EXIF orientation that is not one number");
    const uint32_t value = type == 3 ? u16(entry + 8) : u32(entry + 8);
    if (value < 1 || value > 8)
      refuse(name, "EXIF orientation " + std::to_string(value) + ", not 1 to 8");
    return int(value);
  }
  return 1;
}

struct Stored {
  PhotoFormat format = PhotoFormat::Jpeg;
  uint32_t width = 0, height = 0;
  int orientation = 1;
  uint64_t workingBytesPerPixel = 0;  // the decoder's own buffers beyond its output
};

bool isJpegFrame(uint8_t marker) {
  return marker >= 0xC0 && marker <= 0xC2;
}
// The other SOFn: lossless, hierarchical and arithmetic-coded frames (C4 is DHT, C8 JPG, CC DAC).
bool isOtherFrame(uint8_t marker) {
  return marker >= 0xC3 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
}

// The segments up to the first scan (SOS): the frame header (SOF0 baseline, SOF1 extended,
// SOF2 progressive, which cameras write) and the first EXIF APP1.
Stored readJpeg(std::span<const uint8_t> b, const std::string& name) {
  Stored s;
  bool frame = false, exif = false;
  size_t at = 2;  // after SOI
  for (;;) {
    if (at >= b.size()) refuse(name, "truncated JPEG header");
    if (b[at] != 0xFF) refuse(name, "broken JPEG header (no marker where a segment starts)");
    while (at < b.size() && b[at] == 0xFF) ++at;  // a marker may be preceded by fill bytes
    if (at >= b.size()) refuse(name, "truncated JPEG header");
    const uint8_t marker = b[at++];
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) continue;  // no length, no data
    if (marker == 0x00 || marker == 0xD8) refuse(name, "broken JPEG header (a stray marker)");
    if (marker == 0xD9) refuse(name, "JPEG that ends before its image data");
    if (!fits(b.size(), at, 2)) refuse(name, "truncated JPEG header");
    const size_t length = be16(b, at);  // counts its own two bytes
    if (length < 2) refuse(name, "broken JPEG header (a segment length below 2)");
    if (!fits(b.size(), at, length)) refuse(name, "truncated JPEG header");
    const std::span<const uint8_t> data = b.subspan(at + 2, length - 2);
    at += length;
    if (marker == 0xDA) {  // SOS: the image data begins; the header is complete
      if (!frame) refuse(name, "JPEG whose image data comes before its frame header");
      return s;
    }
    if (isOtherFrame(marker))
      refuse(name, "lossless, hierarchical or arithmetic-coded JPEG, not a camera's photo");
    if (isJpegFrame(marker)) {
      if (frame) refuse(name, "JPEG with two frame headers");
      frame = true;
      if (data.size() < 6) refuse(name, "truncated JPEG frame header");
      if (data[0] != 8) refuse(name, std::to_string(data[0]) + "-bit JPEG, not 8-bit");
      s.height = be16(data, 1);
      s.width = be16(data, 3);
      const size_t components = data[5];
      if (components != 1 && components != 3 && components != 4)
        refuse(name, "JPEG of " + std::to_string(components) + " colour components");
      if (data.size() < 6 + 3 * components) refuse(name, "truncated JPEG frame header");
      // A progressive decoder keeps every component's coefficients, 2 bytes each, until the
      // last scan (the most, with no chroma subsampling).
      s.workingBytesPerPixel = marker == 0xC2 ? 2 * components : 0;
    } else if (marker == 0xE1 && !exif && data.size() >= 6 && data[0] == 'E' && data[1] == 'x' &&
               data[2] == 'i' && data[3] == 'f' && data[4] == 0 && data[5] == 0) {
      exif = true;  // XMP and other APP1 blocks carry no orientation the decoders read
      s.orientation = exifOrientation(data.subspan(6), name);
    }
  }
}

bool isValidPngDepth(int depth, int colourType) {
  switch (colourType) {
    case 0:
      return depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16;
    case 3:
      return depth == 1 || depth == 2 || depth == 4 || depth == 8;
    case 2:
    case 4:
    case 6:
      return depth == 8 || depth == 16;
    default:
      return false;
  }
}

// IHDR, then the chunks before the image data (IDAT) for an eXIf orientation.
Stored readPng(std::span<const uint8_t> b, const std::string& name) {
  Stored s;
  s.format = PhotoFormat::Png;
  // The signature (8), IHDR's length and type (8), its 13 bytes and its CRC (4).
  if (b.size() < 33) refuse(name, "truncated PNG header");
  if (be32(b, 8) != 13 || be32(b, 12) != 0x49484452)  // "IHDR"
    refuse(name, "PNG whose first chunk is not a 13-byte IHDR");
  s.width = be32(b, 16);
  s.height = be32(b, 20);
  const int depth = b[24], colourType = b[25];
  if (s.width > 0x7FFFFFFFu || s.height > 0x7FFFFFFFu)  // PNG's own limit
    refuse(name, "PNG wider or taller than 2^31 - 1 pixels");
  if (!isValidPngDepth(depth, colourType))
    refuse(name, "PNG of bit depth " + std::to_string(depth) + " and colour type " +
                     std::to_string(colourType) + ", which PNG does not define");
  if (b[26] != 0 || b[27] != 0 || b[28] > 1)
    refuse(name, "PNG with an unknown compression, filter or interlace method");
  bool exif = false;
  size_t at = 33;
  for (;;) {
    if (!fits(b.size(), at, 8)) refuse(name, "truncated PNG header");
    const size_t length = be32(b, at);
    const uint32_t type = be32(b, at + 4);
    if (length > 0x7FFFFFFFu) refuse(name, "PNG chunk longer than 2^31 - 1 bytes");
    if (type == 0x49444154) return s;  // "IDAT": the image data begins
    if (type == 0x49454E44) refuse(name, "PNG that ends before its image data");  // "IEND"
    if (!fits(b.size(), at + 8, length) || !fits(b.size(), at + 8 + length, 4))
      refuse(name, "truncated PNG header");
    if (type == 0x65584966 && !exif) {  // "eXIf": a bare TIFF structure
      exif = true;
      s.orientation = exifOrientation(b.subspan(at + 8, length), name);
    }
    at += 12 + length;  // length, type, data, CRC
  }
}

}  // namespace

PhotoHeader readPhotoHeader(std::span<const uint8_t> bytes, const std::string& name,
                            uint64_t maxPixels) {
  static constexpr uint8_t kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  Stored s;
  if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) {
    s = readJpeg(bytes, name);
  } else if (bytes.size() >= 8 && std::equal(kPngSignature, kPngSignature + 8, bytes.begin())) {
    s = readPng(bytes, name);
  } else {
    refuse(name, "not a JPEG or PNG photo");
  }
  if (s.width == 0 || s.height == 0)
    refuse(name, "photo of " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                     " pixels, which is none");
  const uint64_t pixels = uint64_t(s.width) * s.height;
  if (pixels > maxPixels)
    refuse(name, std::to_string(s.width) + "x" + std::to_string(s.height) +
                     " pixels is more than the " + std::to_string(maxPixels) + " allowed");
  PhotoHeader h;
  h.format = s.format;
  h.storedWidth = int(s.width);
  h.storedHeight = int(s.height);
  h.orientation = s.orientation;
  const bool turned = s.orientation >= 5;  // 5 to 8 turn the photo by a quarter
  h.width = turned ? h.storedHeight : h.storedWidth;
  h.height = turned ? h.storedWidth : h.storedHeight;
  // The decoder's BGR picture and the upright RGB copy made from it (3 bytes per pixel each),
  // plus what the decoder keeps besides (a progressive JPEG's coefficients).
  h.decodeBytes = pixels * (2 * 3 + s.workingBytesPerPixel);
  return h;
}

}  // namespace parallax::vision
