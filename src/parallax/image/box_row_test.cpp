// BoxRow (the stencil boxFilterX and the layer solvers use) against the prefix integrals'
// second code path, and its transpose against the definition <B x, y> = <x, B^T y>.
#include "parallax/image/box_row.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "parallax/core/error.h"
#include "parallax/core/random.h"
#include "parallax/image/metrics.h"

namespace parallax {
namespace {

Image randomRows(int width, int height, uint64_t seed) {
  Rng rng(seed);
  Image image(width, height);
  for (Vec3f& p : image.pixels()) p = Vec3f(rng.uniform(), rng.uniform(), rng.uniform());
  return image;
}

// Widths of 1 to 16 taps, odd and even, whole and fractional, on rows longer and shorter than
// the box (a 5-pixel row is clipped at every column): the stencil equals the prefixes.
TEST(BoxRow, StencilIsThePrefixIntegrals) {
  for (const int columns : {5, 37, 200})
    for (const double width : {1.0, 2.5, 4.3, 9.0, 9.045, 12.75, 14.9}) {
      SCOPED_TRACE(std::to_string(columns) + " columns, width " + std::to_string(width));
      const Image image = randomRows(columns, 3, uint64_t(columns) * 100 + uint64_t(width));
      const BoxRow box(columns, width);
      ASSERT_LE(box.tapCount(), BoxRow::kMostTaps);
      const Image byPrefixes = boxFilterXByPrefixes(image, width);
      const Image filtered = boxFilterX(image, width);
      for (int y = 0; y < 3; ++y) {
        std::vector<Vec3f> out(static_cast<size_t>(columns));
        box.apply(&image.at(0, y), out.data());
        for (int x = 0; x < columns; ++x)
          for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(out[size_t(x)][c], byPrefixes.at(x, y)[c], 1e-6) << x;
            EXPECT_EQ(filtered.at(x, y)[c], out[size_t(x)][c]) << x;
          }
      }
    }
  // Wider boxes go by the prefixes.
  const Image image = randomRows(300, 2, 5);
  EXPECT_GT(BoxRow(300, 54.0).tapCount(), BoxRow::kMostTaps);
  const Image wide = boxFilterX(image, 54.0), byPrefixes = boxFilterXByPrefixes(image, 54.0);
  for (size_t i = 0; i < wide.pixels().size(); ++i)
    EXPECT_EQ(wide.pixels()[i], byPrefixes.pixels()[i]);
}

TEST(BoxRow, TransposeIsTheAdjoint) {
  for (const int columns : {5, 37, 200})
    for (const double width : {1.0, 4.3, 9.045, 14.9}) {
      const Image x = randomRows(columns, 1, 7), y = randomRows(columns, 1, 8);
      const BoxRow box(columns, width);
      std::vector<Vec3f> bx(static_cast<size_t>(columns)), bty(static_cast<size_t>(columns));
      box.apply(&x.at(0, 0), bx.data());
      box.applyTransposed(&y.at(0, 0), bty.data());
      double left = 0, right = 0;
      for (int i = 0; i < columns; ++i)
        for (int c = 0; c < 3; ++c) {
          left += double(bx[size_t(i)][c]) * y.at(i, 0)[c];
          right += double(x.at(i, 0)[c]) * bty[size_t(i)][c];
        }
      EXPECT_NEAR(left, right, 1e-5 * std::abs(left)) << columns << " " << width;
    }
}

// The stencil's shifted-vector loop (AVX-512 CPUs) against its plain loop: the same bits for B
// and B^T at every tap count from 2 to 16, on rows of exactly their length (ASan sees a read
// past one), long and short, whole and fractional widths.
TEST(BoxRow, ShiftedStencilIsThePlainLoopBitForBit) {
  for (const int columns : {20, 37, 200, 1920})
    for (const double width :
         {1.5, 2.5, 3.02, 4.3, 5.0, 6.6, 7.9, 9.045, 10.5, 12.75, 13.2, 14.9}) {
      SCOPED_TRACE(std::to_string(columns) + " columns, width " + std::to_string(width));
      const Image image = randomRows(columns, 1, uint64_t(columns) + uint64_t(10 * width));
      const BoxRow box(columns, width);
      std::vector<Vec3f> shifted(static_cast<size_t>(columns)), plain(shifted);
      std::vector<Vec3f> shiftedT(shifted), plainT(shifted);
      const bool before = allowShiftedStencil(true);
      box.apply(&image.at(0, 0), shifted.data());
      box.applyTransposed(&image.at(0, 0), shiftedT.data());
      allowShiftedStencil(false);
      box.apply(&image.at(0, 0), plain.data());
      box.applyTransposed(&image.at(0, 0), plainT.data());
      allowShiftedStencil(before);
      for (int x = 0; x < columns; ++x) {
        ASSERT_EQ(shifted[size_t(x)], plain[size_t(x)]) << x;
        ASSERT_EQ(shiftedT[size_t(x)], plainT[size_t(x)]) << x;
      }
    }
}

TEST(BoxRow, RefusesAWidthThatIsNotPositive) {
  EXPECT_THROW(BoxRow(10, 0.0), InputError);
  EXPECT_THROW(BoxRow(10, -1.0), InputError);
  EXPECT_THROW(BoxRow(10, std::nan("")), InputError);
}

}  // namespace
}  // namespace parallax
