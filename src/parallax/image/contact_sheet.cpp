#include "parallax/image/contact_sheet.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace parallax {
namespace {

struct Glyph {
  char character;
  std::array<unsigned char, kGlyphHeight> rows;  // bit 4 is the leftmost column
};

// A 5x7 font drawn for this project, in the style of classic character-LCD fonts.
constexpr Glyph kFont[] = {
    {' ', {0b00000, 0b00000, 0b00000, 0b00000, 0b00000, 0b00000, 0b00000}},
    {'0', {0b01110, 0b10001, 0b10011, 0b10101, 0b11001, 0b10001, 0b01110}},
    {'1', {0b00100, 0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110}},
    {'2', {0b01110, 0b10001, 0b00001, 0b00010, 0b00100, 0b01000, 0b11111}},
    {'3', {0b11111, 0b00010, 0b00100, 0b00010, 0b00001, 0b10001, 0b01110}},
    {'4', {0b00010, 0b00110, 0b01010, 0b10010, 0b11111, 0b00010, 0b00010}},
    {'5', {0b11111, 0b10000, 0b11110, 0b00001, 0b00001, 0b10001, 0b01110}},
    {'6', {0b00110, 0b01000, 0b10000, 0b11110, 0b10001, 0b10001, 0b01110}},
    {'7', {0b11111, 0b00001, 0b00010, 0b00100, 0b01000, 0b01000, 0b01000}},
    {'8', {0b01110, 0b10001, 0b10001, 0b01110, 0b10001, 0b10001, 0b01110}},
    {'9', {0b01110, 0b10001, 0b10001, 0b01111, 0b00001, 0b00010, 0b01100}},
    {'A', {0b01110, 0b10001, 0b10001, 0b11111, 0b10001, 0b10001, 0b10001}},
    {'B', {0b11110, 0b10001, 0b10001, 0b11110, 0b10001, 0b10001, 0b11110}},
    {'C', {0b01110, 0b10001, 0b10000, 0b10000, 0b10000, 0b10001, 0b01110}},
    {'D', {0b11100, 0b10010, 0b10001, 0b10001, 0b10001, 0b10010, 0b11100}},
    {'E', {0b11111, 0b10000, 0b10000, 0b11110, 0b10000, 0b10000, 0b11111}},
    {'F', {0b11111, 0b10000, 0b10000, 0b11110, 0b10000, 0b10000, 0b10000}},
    {'G', {0b01110, 0b10001, 0b10000, 0b10111, 0b10001, 0b10001, 0b01111}},
    {'H', {0b10001, 0b10001, 0b10001, 0b11111, 0b10001, 0b10001, 0b10001}},
    {'I', {0b01110, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110}},
    {'J', {0b00111, 0b00010, 0b00010, 0b00010, 0b00010, 0b10010, 0b01100}},
    {'K', {0b10001, 0b10010, 0b10100, 0b11000, 0b10100, 0b10010, 0b10001}},
    {'L', {0b10000, 0b10000, 0b10000, 0b10000, 0b10000, 0b10000, 0b11111}},
    {'M', {0b10001, 0b11011, 0b10101, 0b10101, 0b10001, 0b10001, 0b10001}},
    {'N', {0b10001, 0b10001, 0b11001, 0b10101, 0b10011, 0b10001, 0b10001}},
    {'O', {0b01110, 0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b01110}},
    {'P', {0b11110, 0b10001, 0b10001, 0b11110, 0b10000, 0b10000, 0b10000}},
    {'Q', {0b01110, 0b10001, 0b10001, 0b10001, 0b10101, 0b10010, 0b01101}},
    {'R', {0b11110, 0b10001, 0b10001, 0b11110, 0b10100, 0b10010, 0b10001}},
    {'S', {0b01111, 0b10000, 0b10000, 0b01110, 0b00001, 0b00001, 0b11110}},
    {'T', {0b11111, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100}},
    {'U', {0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b01110}},
    {'V', {0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b01010, 0b00100}},
    {'W', {0b10001, 0b10001, 0b10001, 0b10101, 0b10101, 0b10101, 0b01010}},
    {'X', {0b10001, 0b10001, 0b01010, 0b00100, 0b01010, 0b10001, 0b10001}},
    {'Y', {0b10001, 0b10001, 0b01010, 0b00100, 0b00100, 0b00100, 0b00100}},
    {'Z', {0b11111, 0b00001, 0b00010, 0b00100, 0b01000, 0b10000, 0b11111}},
    {'-', {0b00000, 0b00000, 0b00000, 0b11111, 0b00000, 0b00000, 0b00000}},
    {'.', {0b00000, 0b00000, 0b00000, 0b00000, 0b00000, 0b01100, 0b01100}},
    {',', {0b00000, 0b00000, 0b00000, 0b00000, 0b01100, 0b00100, 0b01000}},
    {'=', {0b00000, 0b00000, 0b11111, 0b00000, 0b11111, 0b00000, 0b00000}},
    {'+', {0b00000, 0b00100, 0b00100, 0b11111, 0b00100, 0b00100, 0b00000}},
    {':', {0b00000, 0b01100, 0b01100, 0b00000, 0b01100, 0b01100, 0b00000}},
    {'/', {0b00000, 0b00001, 0b00010, 0b00100, 0b01000, 0b10000, 0b00000}},
    {'(', {0b00010, 0b00100, 0b01000, 0b01000, 0b01000, 0b00100, 0b00010}},
    {')', {0b01000, 0b00100, 0b00010, 0b00010, 0b00010, 0b00100, 0b01000}},
    {'%', {0b11000, 0b11001, 0b00010, 0b00100, 0b01000, 0b10011, 0b00011}},
    {'_', {0b00000, 0b00000, 0b00000, 0b00000, 0b00000, 0b00000, 0b11111}},
};
constexpr Glyph kUnknownGlyph = {'?',
                                 {0b11111, 0b10001, 0b10001, 0b10001, 0b10001, 0b10001, 0b11111}};

void drawLabel(Image& sheet, const std::string& text, int left, int top, int maxWidth, Vec3f ink) {
  for (size_t k = 0; k < text.size(); ++k) {
    const unsigned char* rows = glyphRows(text[k]);
    for (int r = 0; r < kGlyphHeight; ++r)
      for (int c = 0; c < kGlyphWidth; ++c) {
        const int x = int(k) * kGlyphAdvance + c;
        if (x >= maxWidth || !(rows[r] >> (kGlyphWidth - 1 - c) & 1)) continue;
        sheet.at(left + x, top + r) = ink;
      }
  }
}

}  // namespace

const unsigned char* glyphRows(char character) {
  const char upper = character >= 'a' && character <= 'z' ? char(character - 'a' + 'A') : character;
  for (const Glyph& glyph : kFont)
    if (glyph.character == upper) return glyph.rows.data();
  return kUnknownGlyph.rows.data();
}

Image contactThumbnail(const Image& frame, int thumbnailWidth) {
  const int height = std::max(
      1, int(std::lround(double(thumbnailWidth) * frame.height() / double(frame.width()))));
  return resizeArea(frame, thumbnailWidth, height);
}

Image contactSheet(const std::vector<Image>& frames, int columns, int thumbnailWidth,
                   const std::vector<std::string>& labels, int gapPx, Vec3f background) {
  if (frames.empty()) throw std::invalid_argument("contactSheet: no frames");
  if (columns < 1 || thumbnailWidth < 1 || gapPx < 0)
    throw std::invalid_argument("contactSheet: columns and thumbnail width must be >= 1");
  if (!labels.empty() && labels.size() != frames.size())
    throw std::invalid_argument("contactSheet: need one label per frame");
  std::vector<Image> thumbnails;
  int thumbnailHeight = 1;
  for (const Image& frame : frames) {
    if (frame.empty()) throw std::invalid_argument("contactSheet: empty frame");
    thumbnails.push_back(contactThumbnail(frame, thumbnailWidth));
    thumbnailHeight = std::max(thumbnailHeight, thumbnails.back().height());
  }
  const int count = int(frames.size());
  columns = std::min(columns, count);
  const int rows = (count + columns - 1) / columns;
  const int cellHeight = thumbnailHeight + (labels.empty() ? 0 : kLabelStripHeight);
  Image sheet(columns * thumbnailWidth + (columns + 1) * gapPx,
              rows * cellHeight + (rows + 1) * gapPx, background);
  // Rec. 709 luminance decides the ink colour that stands out from the background.
  const float luminance = dot(background, Vec3f(0.2126f, 0.7152f, 0.0722f));
  const Vec3f ink = luminance < 0.18f ? Vec3f(1.0f) : Vec3f(0.0f);
  for (int i = 0; i < count; ++i) {
    const int left = gapPx + (i % columns) * (thumbnailWidth + gapPx);
    const int top = gapPx + (i / columns) * (cellHeight + gapPx);
    const Image& thumbnail = thumbnails[size_t(i)];
    for (int y = 0; y < thumbnail.height(); ++y)
      for (int x = 0; x < thumbnail.width(); ++x) sheet.at(left + x, top + y) = thumbnail.at(x, y);
    if (!labels.empty())
      drawLabel(sheet, labels[size_t(i)], left, top + thumbnailHeight + kLabelPadding,
                thumbnailWidth, ink);
  }
  return sheet;
}

}  // namespace parallax
