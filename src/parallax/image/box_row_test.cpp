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

TEST(BoxRow, RefusesAWidthThatIsNotPositive) {
  EXPECT_THROW(BoxRow(10, 0.0), InputError);
  EXPECT_THROW(BoxRow(10, -1.0), InputError);
  EXPECT_THROW(BoxRow(10, std::nan("")), InputError);
}

}  // namespace
}  // namespace parallax
