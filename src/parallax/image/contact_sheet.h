// A contact sheet: many frames (e.g. the views of an eye sweep) shrunk to thumbnails and laid
// out in a grid, each optionally captioned with a tiny built-in 5x7 bitmap font.
#pragma once

#include <string>
#include <vector>

#include "parallax/image/image.h"

namespace parallax {

// Glyph cell of the built-in font: 5x7 pixels plus one column of spacing.
inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphHeight = 7;
inline constexpr int kGlyphAdvance = kGlyphWidth + 1;
// A captioned sheet reserves this strip below each thumbnail: padding, then one line of text.
inline constexpr int kLabelPadding = 2;
inline constexpr int kLabelStripHeight = kLabelPadding + kGlyphHeight;

// The 5x7 bitmap of a character: row r (0 = top), bit (kGlyphWidth - 1 - c) = column c.
// Digits, A-Z (lower case drawn as upper case), space and - . , = + : / ( ) % _ are defined;
// any other character is drawn as a hollow box.
const unsigned char* glyphRows(char character);

// Lays out `frames` row by row, `columns` per row (fewer if there are fewer frames), each
// scaled by area averaging to `thumbnailWidth` pixels wide (height keeps the aspect ratio,
// rounded, at least 1). Cells are as tall as the tallest thumbnail, plus kLabelStripHeight if
// `labels` is non-empty; `gapPx` of `background` separates cells and surrounds the grid:
//   width  = columns * thumbnailWidth + (columns + 1) * gapPx
//   height = rows * cellHeight + (rows + 1) * gapPx
// Label i starts at the left edge of thumbnail i, kLabelPadding below the cell's thumbnail
// area (the tallest thumbnail), is clipped to the thumbnail width and drawn in white on a dark
// background (luminance < 0.18), else black. Throws std::invalid_argument for no frames, an empty
// frame, columns < 1, thumbnailWidth < 1, gapPx < 0, or labels that are non-empty but not one per
// frame.
// A frame as the sheet shows it: thumbnailWidth wide, the height keeping the aspect ratio
// (rounded, at least 1), by area averaging. A frame already of that size is copied as it is, so
// callers may shrink frames early (and keep only the thumbnails) without changing the sheet.
Image contactThumbnail(const Image& frame, int thumbnailWidth);

Image contactSheet(const std::vector<Image>& frames, int columns, int thumbnailWidth,
                   const std::vector<std::string>& labels = {}, int gapPx = 4,
                   Vec3f background = Vec3f(0.02f));

}  // namespace parallax
