// Animated PNG (APNG) output for frame sequences such as eye sweeps. Viewers without APNG
// support show the first frame as an ordinary PNG.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "parallax/image/image.h"

namespace parallax {

// CRC-32 as used by PNG chunks (ISO 3309 / ITU-T V.42, polynomial 0xEDB88320 reflected;
// PNG specification, annex D). crc32("IEND") == 0xAE426082.
uint32_t pngCrc32(std::string_view bytes);

// An APNG (https://wiki.mozilla.org/APNG_Specification) showing each frame for `delayMs`
// milliseconds, played `loops` times (0 = forever). Chunk order: IHDR, acTL, then per frame
// an fcTL followed by its image data (IDAT for frame 0, so it is also the default image;
// fdAT for the rest), IEND. Every frame covers the whole canvas and replaces it.
// Throws std::invalid_argument for no frames, frames of different sizes, delayMs outside
// [0, 65535] or loops < 0.
std::string encodeApng(const std::vector<Image>& frames, int delayMs, int loops = 0);
// The same from frames already encoded as PNGs (pngBytes(frame, false)), which must share one
// header (size and colour type); throws std::invalid_argument otherwise.
std::string encodeApngFromPngs(const std::vector<std::string>& pngFrames, int delayMs,
                               int loops = 0);

}  // namespace parallax
