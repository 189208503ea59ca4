// PNG encoding of 8-bit pictures, compressed on every core: the rows are cut into bands of a
// fixed height, each band is filtered and deflated on its own, and the raw deflate streams are
// joined into the one zlib stream a PNG holds (as pigz joins gzip blocks: every band but the last
// ends on a sync flush, so the next starts on a byte boundary; the Adler-32 checksums combine).
// The bands depend only on the picture, so the bytes are the same for any thread count.
#pragma once

#include <cstdint>
#include <string>

namespace parallax {

struct PngSettings {
  int compressionLevel = 2;  // zlib's 1 (fastest) .. 9 (smallest)
  int threads = 0;           // 0: every core
};

// `codes`: height rows of width x channels bytes (1: grey, 3: RGB), row 0 at the top, tagged
// as sRGB. Throws std::invalid_argument for an empty picture or another channel count.
std::string encodePng(const uint8_t* codes, int width, int height, int channels,
                      const PngSettings& settings = {});

// A 16-bit grey PNG of width x height values (row 0 at the top), untagged: data such as a depth
// map, not a colour. Throws std::invalid_argument for an empty picture.
std::string encodePngGrey16(const uint16_t* values, int width, int height,
                            const PngSettings& settings = {});

}  // namespace parallax
