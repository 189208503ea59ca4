#include "parallax/io/png_encoder.h"

#include <zlib.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "parallax/core/parallel.h"

namespace parallax {

namespace {

// About 1 MiB of pixels per band: enough to keep deflate's 32 KiB window busy (a band loses only
// its first window's matches), few enough bands to spread over the cores.
constexpr size_t kBandBytes = size_t(1) << 20;

void appendBigEndian(std::string& out, uint32_t value) {
  const char bytes[4] = {char(value >> 24), char(value >> 16), char(value >> 8), char(value)};
  out.append(bytes, 4);
}

void appendChunk(std::string& out, const char type[4], const std::string& data) {
  appendBigEndian(out, uint32_t(data.size()));
  const size_t typeAt = out.size();
  out.append(type, 4);
  out += data;
  const uLong crc =
      crc32(0L, reinterpret_cast<const Bytef*>(out.data() + typeAt), uInt(4 + data.size()));
  appendBigEndian(out, uint32_t(crc));
}

// PNG's Paeth predictor (PNG specification, section 9.4).
inline uint8_t paeth(int left, int up, int upLeft) {
  const int p = left + up - upLeft;
  const int pa = std::abs(p - left), pb = std::abs(p - up), pc = std::abs(p - upLeft);
  if (pa <= pb && pa <= pc) return uint8_t(left);
  return uint8_t(pb <= pc ? up : upLeft);
}

// One row filtered five ways; the filter whose output has the least sum of absolute values (as
// signed bytes) is kept: the PNG specification's recommended heuristic (section 12.8).
void filterRow(const uint8_t* row, const uint8_t* above, size_t bytes, int stride, uint8_t* out,
               std::vector<uint8_t> trial[5]) {
  for (int f = 0; f < 5; ++f) trial[f].resize(bytes);
  for (size_t i = 0; i < bytes; ++i) {
    const int left = i >= size_t(stride) ? row[i - size_t(stride)] : 0;
    const int up = above ? above[i] : 0;
    const int upLeft = above && i >= size_t(stride) ? above[i - size_t(stride)] : 0;
    trial[0][i] = row[i];
    trial[1][i] = uint8_t(row[i] - left);
    trial[2][i] = uint8_t(row[i] - up);
    trial[3][i] = uint8_t(row[i] - ((left + up) >> 1));
    trial[4][i] = uint8_t(row[i] - paeth(left, up, upLeft));
  }
  int best = 0;
  uint64_t bestCost = UINT64_MAX;
  for (int f = 0; f < 5; ++f) {
    uint64_t cost = 0;
    for (size_t i = 0; i < bytes; ++i) cost += uint64_t(std::abs(int(int8_t(trial[f][i]))));
    if (cost < bestCost) bestCost = cost, best = f;
  }
  out[0] = uint8_t(best);
  std::memcpy(out + 1, trial[best].data(), bytes);
}

struct Band {
  std::string deflated;
  uLong adler = 1;
  size_t rawBytes = 0;
};

// Filters rows [begin, end) and deflates them as a raw stream: ended by a sync flush, or, for
// the last band, by the stream's final block.
Band compressBand(const uint8_t* codes, size_t rowBytes, int stride, int begin, int end, bool last,
                  int level) {
  std::vector<uint8_t> filtered(size_t(end - begin) * (rowBytes + 1));
  std::vector<uint8_t> trial[5];
  for (int y = begin; y < end; ++y) {
    const uint8_t* row = codes + size_t(y) * rowBytes;
    filterRow(row, y > 0 ? row - rowBytes : nullptr, rowBytes, stride,
              filtered.data() + size_t(y - begin) * (rowBytes + 1), trial);
  }
  Band band;
  band.rawBytes = filtered.size();
  band.adler = adler32(1L, filtered.data(), uInt(filtered.size()));
  z_stream z{};
  if (deflateInit2(&z, level, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("PNG encoding: zlib could not start");
  band.deflated.resize(deflateBound(&z, uLong(filtered.size())) + 16);
  z.next_in = filtered.data();
  z.avail_in = uInt(filtered.size());
  z.next_out = reinterpret_cast<Bytef*>(band.deflated.data());
  z.avail_out = uInt(band.deflated.size());
  const int status = deflate(&z, last ? Z_FINISH : Z_SYNC_FLUSH);
  const bool done = last ? status == Z_STREAM_END : status == Z_OK && z.avail_in == 0;
  band.deflated.resize(z.total_out);
  deflateEnd(&z);
  if (!done) throw std::runtime_error("PNG encoding: zlib failed");
  return band;
}

// `codes`: height rows of width x channels samples of bitDepth / 8 bytes each (big-endian for
// 16 bits, as PNG stores them). The filters work on whole pixels: their byte stride is the
// pixel's bytes (PNG specification, section 9.2). `srgb` tags the samples as sRGB colours.
std::string encodeSamples(const uint8_t* codes, int width, int height, int channels, int bitDepth,
                          bool srgb, const PngSettings& settings) {
  const int pixelBytes = channels * bitDepth / 8;
  const size_t rowBytes = size_t(width) * size_t(pixelBytes);
  const int bandRows = int(std::clamp<size_t>(kBandBytes / rowBytes, 1, size_t(height)));
  const int bands = (height + bandRows - 1) / bandRows;
  std::vector<Band> compressed(static_cast<size_t>(bands));
  const int level = std::clamp(settings.compressionLevel, 1, 9);
  parallelFor(bands, settings.threads, 1, [&](int64_t first, int64_t end) {
    for (int64_t b = first; b < end; ++b) {
      const int begin = int(b) * bandRows;
      compressed[size_t(b)] =
          compressBand(codes, rowBytes, pixelBytes, begin, std::min(height, begin + bandRows),
                       b + 1 == bands, level);
    }
  });

  std::string png("\x89PNG\r\n\x1a\n", 8);
  std::string header;
  appendBigEndian(header, uint32_t(width));
  appendBigEndian(header, uint32_t(height));
  header += char(bitDepth);               // bits per sample
  header += char(channels == 1 ? 0 : 2);  // colour type: grey, or RGB
  header.append(3, '\0');                 // deflate, adaptive filtering, no interlace
  appendChunk(png, "IHDR", header);
  if (srgb) appendChunk(png, "sRGB", std::string(1, '\0'));  // perceptual rendering intent
  // The zlib stream: its header (deflate, 32 KiB window, no dictionary; 0x7801 is a multiple of
  // 31), the bands' raw deflate data, one IDAT chunk each, and the Adler-32 of all the data.
  uLong adler = 1;
  for (size_t b = 0; b < compressed.size(); ++b) {
    Band& band = compressed[b];
    adler = adler32_combine(adler, band.adler, z_off_t(band.rawBytes));
    std::string data =
        b == 0 ? std::string("\x78\x01", 2) + band.deflated : std::move(band.deflated);
    if (b + 1 == compressed.size()) appendBigEndian(data, uint32_t(adler));
    appendChunk(png, "IDAT", data);
  }
  appendChunk(png, "IEND", "");
  return png;
}

}  // namespace

std::string encodePng(const uint8_t* codes, int width, int height, int channels,
                      const PngSettings& settings) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("encodePng: empty picture");
  if (channels != 1 && channels != 3)
    throw std::invalid_argument("encodePng: 1 (grey) or 3 (RGB) channels");
  return encodeSamples(codes, width, height, channels, 8, true, settings);
}

std::string encodePngGrey16(const uint16_t* values, int width, int height,
                            const PngSettings& settings) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("encodePngGrey16: empty picture");
  const size_t count = size_t(width) * size_t(height);
  std::vector<uint8_t> bigEndian(2 * count);
  for (size_t i = 0; i < count; ++i) {
    bigEndian[2 * i] = uint8_t(values[i] >> 8);
    bigEndian[2 * i + 1] = uint8_t(values[i] & 0xFF);
  }
  return encodeSamples(bigEndian.data(), width, height, 1, 16, false, settings);
}

}  // namespace parallax
