// Image files. Reading: PNG, JPEG (8-bit sRGB, decoded to linear) and PFM (linear float).
// Writing, by extension: .png (8-bit sRGB) and .pfm (linear float). Writes go to a temporary
// name beside the target and are renamed into place, so no half-written file is ever left.
#pragma once

#include <string>
#include <string_view>

#include "parallax/image/image.h"

namespace parallax {

// Throws InputError (naming the file) if it is missing, unreadable or not an image.
Image readImage(const std::string& path);
// Throws InputError for an unknown extension and std::runtime_error for an I/O failure.
void writeImage(const std::string& path, const Image& image);
// The bytes of an 8-bit sRGB PNG of `image` (linear light, clamped to [0,1]), in memory.
// Throws std::invalid_argument for an empty image.
std::string pngBytes(const Image& image);
// Writes bytes to `path` atomically (temporary file + rename); creates missing parent folders.
void writeFileAtomically(const std::string& path, std::string_view bytes);

}  // namespace parallax
