#include "parallax/io/animation.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <stdexcept>

#include "parallax/io/image_file.h"

namespace parallax {
namespace {

constexpr std::string_view kPngSignature = "\x89PNG\r\n\x1a\n";
// Image data is split into chunks of at most this many bytes, as libpng does (with 8 KiB);
// the PNG limit is 2^31 - 1 bytes per chunk.
constexpr size_t kMaxChunkData = size_t(1) << 16;

void appendU32(std::string& out, uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out += char((value >> shift) & 0xFF);
}
void appendU16(std::string& out, uint32_t value) {
  out += char((value >> 8) & 0xFF);
  out += char(value & 0xFF);
}
uint32_t readU32(std::string_view bytes, size_t at) {
  uint32_t value = 0;
  for (size_t i = 0; i < 4; ++i) value = value << 8 | uint8_t(bytes[at + i]);
  return value;
}

// A chunk: length, type, data, CRC over type and data (PNG spec, section 5.3).
void appendChunk(std::string& out, std::string_view type, std::string_view data) {
  appendU32(out, uint32_t(data.size()));
  std::string typeAndData(type);
  typeAndData += data;
  out += typeAndData;
  appendU32(out, pngCrc32(typeAndData));
}

// The parts of a single-image PNG that an APNG reuses.
struct PngParts {
  std::string header;     // IHDR data
  std::string imageData;  // all IDAT payloads, concatenated: one zlib stream
};

PngParts splitPng(std::string_view png) {
  if (png.substr(0, kPngSignature.size()) != kPngSignature)
    throw std::runtime_error("encodeApng: encoder produced no PNG signature");
  PngParts parts;
  size_t at = kPngSignature.size();
  while (at + 12 <= png.size()) {
    const size_t length = readU32(png, at);
    if (at + 12 + length > png.size()) break;
    const std::string_view type = png.substr(at + 4, 4);
    const std::string_view data = png.substr(at + 8, length);
    if (type == "IHDR") parts.header = data;
    if (type == "IDAT") parts.imageData += data;
    if (type == "IEND") return parts;
    at += 12 + length;
  }
  throw std::runtime_error("encodeApng: encoder produced a truncated PNG");
}

// fcTL: the frame's region (the whole canvas), delay and how it replaces the previous frame.
std::string frameControl(uint32_t sequence, int width, int height, int delayMs) {
  std::string data;
  appendU32(data, sequence);
  appendU32(data, uint32_t(width));
  appendU32(data, uint32_t(height));
  appendU32(data, 0);  // x offset
  appendU32(data, 0);  // y offset
  appendU16(data, uint32_t(delayMs));
  appendU16(data, 1000);  // delay denominator: milliseconds
  data += char(0);        // dispose_op NONE: the next frame covers everything anyway
  data += char(0);        // blend_op SOURCE: replace, do not composite
  return data;
}

}  // namespace

uint32_t pngCrc32(std::string_view bytes) {
  // zlib's CRC-32 is PNG's (the same polynomial and conditioning).
  return uint32_t(crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), uInt(bytes.size())));
}

std::string encodeApng(const std::vector<Image>& frames, int delayMs, int loops) {
  if (frames.empty()) throw std::invalid_argument("encodeApng: no frames");
  const int width = frames[0].width(), height = frames[0].height();
  for (const Image& frame : frames)
    if (frame.empty() || frame.width() != width || frame.height() != height)
      throw std::invalid_argument("encodeApng: frames must be non-empty and of equal size");
  std::vector<std::string> pngs;
  pngs.reserve(frames.size());
  for (const Image& frame : frames) pngs.push_back(pngBytes(frame, false));
  return encodeApngFromPngs(pngs, delayMs, loops);
}

std::string encodeApngFromPngs(const std::vector<std::string>& pngFrames, int delayMs, int loops) {
  if (pngFrames.empty()) throw std::invalid_argument("encodeApng: no frames");
  if (delayMs < 0 || delayMs > 65535)
    throw std::invalid_argument("encodeApng: delay must be 0..65535 ms");
  if (loops < 0) throw std::invalid_argument("encodeApng: loops must be >= 0 (0 = forever)");

  std::string out(kPngSignature);
  std::string header;
  uint32_t sequence = 0;  // shared by fcTL and fdAT chunks, from 0, no gaps
  for (size_t i = 0; i < pngFrames.size(); ++i) {
    const PngParts parts = splitPng(pngFrames[i]);
    if (i == 0) {
      header = parts.header;
      appendChunk(out, "IHDR", parts.header);
      std::string animationControl;
      appendU32(animationControl, uint32_t(pngFrames.size()));
      appendU32(animationControl, uint32_t(loops));
      appendChunk(out, "acTL", animationControl);
    } else if (parts.header != header) {
      throw std::invalid_argument("encodeApng: frames must share their size and colour type");
    }
    const uint32_t width = readU32(header, 0), height = readU32(header, 4);
    appendChunk(out, "fcTL", frameControl(sequence++, int(width), int(height), delayMs));
    const std::string_view data = parts.imageData;
    for (size_t at = 0; at < data.size(); at += kMaxChunkData) {
      const std::string_view piece = data.substr(at, kMaxChunkData);
      if (i == 0) {
        appendChunk(out, "IDAT", piece);
      } else {
        std::string frameData;
        appendU32(frameData, sequence++);
        frameData += piece;
        appendChunk(out, "fdAT", frameData);
      }
    }
  }
  appendChunk(out, "IEND", "");
  return out;
}

}  // namespace parallax
