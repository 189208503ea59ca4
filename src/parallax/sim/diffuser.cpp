#include "parallax/sim/diffuser.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "parallax/core/parallel.h"
#include "parallax/sim/view_pieces.h"

namespace parallax {

namespace {

// Probability that a normal variable of standard deviation sigma falls below x.
double normalCdf(double x, double sigma) {
  return 0.5 * std::erfc(-x / (sigma * std::sqrt(2.0)));
}

// The Gaussian's mass over each cell m = -radius .. radius, out to 4 sigma.
std::vector<float> kernel(double sigmaCells) {
  const int radius = int(std::ceil(4.0 * sigmaCells + 0.5));
  std::vector<float> weights(size_t(2 * radius + 1));
  for (int m = -radius; m <= radius; ++m)
    weights[size_t(m + radius)] =
        float(normalCdf(m + 0.5, sigmaCells) - normalCdf(m - 0.5, sigmaCells));
  return weights;
}

template <class Body>
void forRows(int rows, int threads, const Body& body) {
  parallelFor(rows, threads, 16, [&](int64_t begin, int64_t end) { body(int(begin), int(end)); });
}

}  // namespace

void diffuserBlur(Vec3f* cells, int columns, int rows, size_t stride, double sigmaCellsX,
                  double sigmaCellsY, int threads) {
  if (sigmaCellsX > 0) {
    const std::vector<float> wx = kernel(sigmaCellsX);
    const int rx = int(wx.size() / 2);
    forRows(rows, threads, [&](int begin, int end) {
      std::vector<Vec3f> in(static_cast<size_t>(columns));
      for (int y = begin; y < end; ++y) {
        Vec3f* row = cells + size_t(y) * stride;
        std::copy(row, row + columns, in.begin());
        for (int x = 0; x < columns; ++x) {
          Vec3f sum(0.0f);
          for (int m = std::max(-rx, -x); m <= std::min(rx, columns - 1 - x); ++m)
            sum += in[size_t(x + m)] * wx[size_t(m + rx)];
          row[x] = sum;
        }
      }
    });
  }
  if (sigmaCellsY > 0) {
    const std::vector<float> wy = kernel(sigmaCellsY);
    const int ry = int(wy.size() / 2);
    std::vector<Vec3f> blurred(size_t(rows) * stride, Vec3f(0.0f));
    forRows(rows, threads, [&](int begin, int end) {
      for (int y = begin; y < end; ++y) {
        Vec3f* out = blurred.data() + size_t(y) * stride;
        for (int m = std::max(-ry, -y); m <= std::min(ry, rows - 1 - y); ++m) {
          const Vec3f* in = cells + size_t(y + m) * stride;
          const float w = wy[size_t(m + ry)];
          for (int x = 0; x < columns; ++x) out[x] += in[x] * w;
        }
      }
    });
    for (int y = 0; y < rows; ++y)
      std::copy(blurred.data() + size_t(y) * stride, blurred.data() + size_t(y) * stride + columns,
                cells + size_t(y) * stride);
  }
}

Image stripedDiffuserBlurred(const Image& layer, SubpixelOrder order, double sigmaMm,
                             double pitchMm, int threads) {
  Image cells(3 * layer.width(), layer.height());
  for (int y = 0; y < layer.height(); ++y)
    for (int x = 0; x < layer.width(); ++x)
      for (int s = 0; s < 3; ++s)
        cells.at(3 * x + s, y) = layer.at(x, y) * stripePasses(order, s) * 3.0f;
  if (sigmaMm > 0 && pitchMm > 0)
    diffuserBlur(cells.pixels().data(), cells.width(), cells.height(), size_t(cells.width()),
                 3.0 * sigmaMm / pitchMm, sigmaMm / pitchMm, threads);
  return cells;
}

Image stripedDiffuserBlurredTransposed(const Image& cells, SubpixelOrder order, double sigmaMm,
                                       double pitchMm, int threads) {
  Image blurred = cells;
  if (sigmaMm > 0 && pitchMm > 0)
    diffuserBlur(blurred.pixels().data(), blurred.width(), blurred.height(),
                 size_t(blurred.width()), 3.0 * sigmaMm / pitchMm, sigmaMm / pitchMm, threads);
  Image layer(cells.width() / 3, cells.height());
  for (int y = 0; y < layer.height(); ++y)
    for (int x = 0; x < layer.width(); ++x)
      for (int s = 0; s < 3; ++s)
        layer.at(x, y) += blurred.at(3 * x + s, y) * stripePasses(order, s) * 3.0f;
  return layer;
}

Image diffuserBlurred(const Image& layer, double sigmaMm, double pitchMm, int threads) {
  Image out = layer;
  if (sigmaMm > 0 && pitchMm > 0)
    diffuserBlur(out.pixels().data(), out.width(), out.height(), size_t(out.width()),
                 sigmaMm / pitchMm, sigmaMm / pitchMm, threads);
  return out;
}

}  // namespace parallax
