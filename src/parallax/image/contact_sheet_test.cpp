#include "parallax/image/contact_sheet.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <utility>

namespace parallax {
namespace {

using Pixel = std::pair<int, int>;

// Every pixel of `sheet` inside the rectangle that differs from `background`.
std::set<Pixel> inkedPixels(const Image& sheet, int left, int top, int width, int height,
                            Vec3f background) {
  std::set<Pixel> inked;
  for (int y = top; y < top + height; ++y)
    for (int x = left; x < left + width; ++x)
      if (!(sheet.at(x, y) == background)) inked.insert({x - left, y - top});
  return inked;
}

TEST(ResizeByArea, CheckerAveragesToHalfInLinearLight) {
  Image checker(8, 6);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 8; ++x) checker.at(x, y) = Vec3f(float((x + y) % 2));
  const Image half = resizeArea(checker, 4, 3);
  for (const Vec3f& p : half.pixels()) EXPECT_FLOAT_EQ(p.x, 0.5f);
}

TEST(ResizeByArea, MatchesBruteForceIntegrationAtNonIntegerRatios) {
  // 7x5 -> 3x2: output pixels cover 7/3 x 5/2 source pixels. Integrating with 35x35 midpoint
  // samples per output pixel is exact here: sample boundaries fall on 1/15 and 1/14 of a source
  // pixel, so every source pixel edge is a sample boundary.
  Image source(7, 5);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x)
      source.at(x, y) = Vec3f(float(x * 5 + y), float((x * 3 + y * 7) % 11), float(x == y));
  const Image out = resizeArea(source, 3, 2);
  constexpr int n = 35;
  for (int oy = 0; oy < 2; ++oy)
    for (int ox = 0; ox < 3; ++ox) {
      Vec3f sum(0.0f);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const double sx = (ox + (i + 0.5) / n) * 7.0 / 3.0;
          const double sy = (oy + (j + 0.5) / n) * 5.0 / 2.0;
          sum += source.at(int(sx), int(sy));
        }
      const Vec3f expected = sum / float(n * n);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(out.at(ox, oy)[c], expected[c], 1e-4f);
    }
}

TEST(ContactSheet, LayoutSizeFollowsColumnsGapsAndLabelStrip) {
  const std::vector<Image> frames(5, Image(40, 20, Vec3f(0.3f)));
  // 3 columns of 10-px thumbnails (5 px tall), 2 rows, 4 px gaps around and between.
  Image sheet = contactSheet(frames, 3, 10);
  EXPECT_EQ(sheet.width(), 3 * 10 + 4 * 4);
  EXPECT_EQ(sheet.height(), 2 * 5 + 3 * 4);
  sheet = contactSheet(frames, 3, 10, std::vector<std::string>(5, "x"), 2);
  EXPECT_EQ(sheet.width(), 3 * 10 + 4 * 2);
  EXPECT_EQ(sheet.height(), 2 * (5 + kLabelStripHeight) + 3 * 2);
  // More columns than frames: no empty columns.
  sheet = contactSheet({frames[0], frames[1]}, 8, 10);
  EXPECT_EQ(sheet.width(), 2 * 10 + 3 * 4);
  EXPECT_EQ(sheet.height(), 5 + 2 * 4);
}

TEST(ContactSheet, PlacesThumbnailsRowByRowOnTheBackground) {
  const Vec3f background(0.1f, 0.2f, 0.3f);
  std::vector<Image> frames;
  for (int i = 0; i < 4; ++i) frames.emplace_back(6, 4, Vec3f(float(i) / 4.0f, 0.5f, 1.0f));
  const Image sheet = contactSheet(frames, 3, 3, {}, 1, background);  // 3x2 thumbnails
  ASSERT_EQ(sheet.width(), 3 * 3 + 4);
  ASSERT_EQ(sheet.height(), 2 * 2 + 3);
  int backgroundPixels = 0;
  for (int y = 0; y < sheet.height(); ++y)
    for (int x = 0; x < sheet.width(); ++x) {
      const int column = (x - 1) / 4, row = (y - 1) / 3;
      const bool inThumbnail = x % 4 != 0 && y % 3 != 0 && row * 3 + column < 4;
      if (inThumbnail)
        EXPECT_FLOAT_EQ(sheet.at(x, y).x, float(row * 3 + column) / 4.0f) << x << "," << y;
      else
        backgroundPixels += sheet.at(x, y) == background;
    }
  EXPECT_EQ(backgroundPixels, sheet.width() * sheet.height() - 4 * 3 * 2);
}

TEST(ContactSheet, DrawsLabelsBelowEachThumbnail) {
  const Vec3f background(0.0f);
  const std::vector<Image> frames(3, Image(8, 4, Vec3f(0.5f)));
  // Thumbnails 16x8, gap 4: cell i's label strip starts at x = 4 + 20 i, y = 4 + 8 + 2.
  const Image sheet = contactSheet(frames, 3, 16, {"-", "L", ""}, 4, background);
  const int stripTop = 4 + 8 + kLabelPadding;
  // A minus sign is one horizontal bar across the glyph's middle row.
  std::set<Pixel> minus;
  for (int c = 0; c < kGlyphWidth; ++c) minus.insert({c, 3});
  EXPECT_EQ(inkedPixels(sheet, 4, stripTop, 16, kGlyphHeight, background), minus);
  // An L is the full left column plus the bottom row: catches flipped rows or bit order.
  std::set<Pixel> ell;
  for (int r = 0; r < kGlyphHeight; ++r) ell.insert({0, r});
  for (int c = 0; c < kGlyphWidth; ++c) ell.insert({c, kGlyphHeight - 1});
  EXPECT_EQ(inkedPixels(sheet, 24, stripTop, 16, kGlyphHeight, background), ell);
  EXPECT_TRUE(inkedPixels(sheet, 44, stripTop, 16, kGlyphHeight, background).empty());
  // Dark background: white ink. Nothing is drawn outside the label rows.
  EXPECT_EQ(sheet.at(4, stripTop + 3), Vec3f(1.0f));
  EXPECT_EQ(inkedPixels(sheet, 0, 4 + 8, sheet.width(), kLabelPadding, background).size(), 0u);
}

TEST(ContactSheet, LabelsAreClippedToTheirCellAndUseDarkInkOnLightBackground) {
  const Vec3f background(0.9f);
  const std::vector<Image> frames(2, Image(8, 8, Vec3f(0.5f)));
  const Image sheet = contactSheet(frames, 2, 8, {"mmmm", ""}, 4, background);
  const int stripTop = 4 + 8 + kLabelPadding;
  const auto inked = inkedPixels(sheet, 0, stripTop, sheet.width(), kGlyphHeight, background);
  ASSERT_FALSE(inked.empty());
  for (const auto& [x, y] : inked) {
    EXPECT_GE(x, 4);
    EXPECT_LT(x, 4 + 8);
    EXPECT_EQ(sheet.at(x, stripTop + y), Vec3f(0.0f));
  }
  // Lower case is drawn as upper case.
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(glyphRows('m')), kGlyphHeight),
            std::string(reinterpret_cast<const char*>(glyphRows('M')), kGlyphHeight));
}

TEST(ContactSheet, RejectsBadArguments) {
  const std::vector<Image> frames(2, Image(4, 4));
  EXPECT_THROW(contactSheet({}, 2, 4), std::invalid_argument);
  EXPECT_THROW(contactSheet(frames, 0, 4), std::invalid_argument);
  EXPECT_THROW(contactSheet(frames, 2, 0), std::invalid_argument);
  EXPECT_THROW(contactSheet(frames, 2, 4, {"only one"}), std::invalid_argument);
  EXPECT_THROW(contactSheet({Image(4, 4), Image()}, 2, 4), std::invalid_argument);
}

TEST(ContactSheet, ThumbnailsMadeEarlyGiveTheSameSheet) {
  // Frames of an odd size with detail in every pixel: the shrink is not trivial.
  std::vector<Image> frames;
  for (int f = 0; f < 4; ++f) {
    Image frame(203, 117);
    for (int y = 0; y < frame.height(); ++y)
      for (int x = 0; x < frame.width(); ++x)
        frame.at(x, y) = {float((x * 7 + y * 3 + f) % 11) / 10.0f, float(y % 5) / 4.0f,
                          float(f) / 3.0f};
    frames.push_back(frame);
  }
  std::vector<Image> thumbnails;
  for (const Image& frame : frames) thumbnails.push_back(contactThumbnail(frame, 50));
  EXPECT_EQ(thumbnails.front().width(), 50);
  EXPECT_EQ(thumbnails.front().height(), 29);  // 117 * 50 / 203 = 28.8
  const std::vector<std::string> labels = {"a", "b", "c", "d"};
  const Image direct = contactSheet(frames, 2, 50, labels);
  const Image early = contactSheet(thumbnails, 2, 50, labels);
  ASSERT_EQ(direct.width(), early.width());
  ASSERT_EQ(direct.height(), early.height());
  EXPECT_EQ(direct.pixels(), early.pixels());
}

}  // namespace
}  // namespace parallax
