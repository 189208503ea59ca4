#include "parallax/image/metrics.h"

#include "parallax/core/lane_kernel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "parallax/core/error.h"

namespace parallax {

namespace {

void checkSameSize(const Image& a, const Image& b, const char* metric) {
  if (a.width() != b.width() || a.height() != b.height() || a.empty())
    throw InputError("", "",
                     std::string(metric) + " needs two non-empty images of the same size (got " +
                         std::to_string(a.width()) + "x" + std::to_string(a.height()) + " and " +
                         std::to_string(b.width()) + "x" + std::to_string(b.height()) + ")");
}

double encode(float linear, MetricEncoding encoding) {
  if (encoding == MetricEncoding::Linear) return linear;
  return linearToSrgb(std::clamp(linear, 0.0f, 1.0f));
}

// A row-major grid of doubles, for the SSIM moment maps.
struct Plane {
  int width = 0, height = 0;
  std::vector<double> v;
  Plane(int w, int h) : width(w), height(h), v(size_t(w) * size_t(h)) {}
  double& at(int x, int y) { return v[size_t(y) * size_t(width) + size_t(x)]; }
  double at(int x, int y) const { return v[size_t(y) * size_t(width) + size_t(x)]; }
};

// Separable filter, keeping only the positions where the whole kernel lies inside ("valid").
Plane filterValid(const Plane& in, const std::vector<double>& kernel) {
  const int k = int(kernel.size());
  Plane across(in.width - k + 1, in.height);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < across.width; ++x) {
      double sum = 0;
      for (int i = 0; i < k; ++i) sum += kernel[size_t(i)] * in.at(x + i, y);
      across.at(x, y) = sum;
    }
  Plane out(across.width, in.height - k + 1);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      double sum = 0;
      for (int i = 0; i < k; ++i) sum += kernel[size_t(i)] * across.at(x, y + i);
      out.at(x, y) = sum;
    }
  return out;
}

}  // namespace

Image boxFilterY(const Image& image, double heightPx) {
  const auto transpose = [](const Image& in) {
    Image out(in.height(), in.width());
    for (int y = 0; y < in.height(); ++y)
      for (int x = 0; x < in.width(); ++x) out.at(y, x) = in.at(x, y);
    return out;
  };
  return transpose(boxFilterX(transpose(image), heightPx));
}

double meanLuminance(const Image& image) {
  double sum = 0;
  for (const Vec3f& p : image.pixels()) sum += luminance(p);
  return image.empty() ? 0.0 : sum / double(image.pixels().size());
}

double meanSquaredError(const Image& a, const Image& b, MetricEncoding encoding) {
  checkSameSize(a, b, "the mean squared error");
  double sum = 0;
  for (size_t i = 0; i < a.pixels().size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = encode(a.pixels()[i][c], encoding) - encode(b.pixels()[i][c], encoding);
      sum += d * d;
    }
  return sum / (3.0 * double(a.pixels().size()));
}

double psnr(const Image& a, const Image& b, double peak, MetricEncoding encoding) {
  const double mse = meanSquaredError(a, b, encoding);
  return mse > 0 ? 10.0 * std::log10(peak * peak / mse) : std::numeric_limits<double>::infinity();
}

double ssim(const Image& a, const Image& b) {
  checkSameSize(a, b, "SSIM");
  constexpr int kWindow = 11;
  constexpr double kSigma = 1.5, kC1 = 0.01 * 0.01, kC2 = 0.03 * 0.03;
  if (a.width() < kWindow || a.height() < kWindow)
    throw InputError("", "", "SSIM needs images of at least 11x11 pixels");
  std::vector<double> kernel(kWindow);
  double total = 0;
  for (int i = 0; i < kWindow; ++i) {
    const double d = i - kWindow / 2;
    total += kernel[size_t(i)] = std::exp(-d * d / (2 * kSigma * kSigma));
  }
  for (double& k : kernel) k /= total;

  const int w = a.width(), h = a.height();
  Plane x(w, h), y(w, h), xx(w, h), yy(w, h), xy(w, h);
  for (size_t i = 0; i < x.v.size(); ++i) {
    x.v[i] = encode(luminance(a.pixels()[i]), MetricEncoding::Srgb);
    y.v[i] = encode(luminance(b.pixels()[i]), MetricEncoding::Srgb);
    xx.v[i] = x.v[i] * x.v[i], yy.v[i] = y.v[i] * y.v[i], xy.v[i] = x.v[i] * y.v[i];
  }
  const Plane mx = filterValid(x, kernel), my = filterValid(y, kernel);
  const Plane mxx = filterValid(xx, kernel), myy = filterValid(yy, kernel);
  const Plane mxy = filterValid(xy, kernel);
  double sum = 0;
  for (size_t i = 0; i < mx.v.size(); ++i) {
    const double ux = mx.v[i], uy = my.v[i];
    const double vx = mxx.v[i] - ux * ux, vy = myy.v[i] - uy * uy, cxy = mxy.v[i] - ux * uy;
    sum += (2 * ux * uy + kC1) * (2 * cxy + kC2) / ((ux * ux + uy * uy + kC1) * (vx + vy + kC2));
  }
  return sum / double(mx.v.size());
}

// A lane kernel: std::floor is a libm call on the x86-64 baseline (no SSE4.1 round).
PARALLAX_LANE_KERNEL Image boxFilterX(const Image& image, double widthPx) {
  if (!(widthPx > 0)) throw InputError("", "", "the box filter's width must be positive");
  const int w = image.width();
  Image out(w, image.height());
  std::vector<double> prefix(size_t(w) + 1);  // prefix[i]: integral of one channel over [0, i)
  for (int y = 0; y < image.height(); ++y)
    for (int c = 0; c < 3; ++c) {
      for (int x = 0; x < w; ++x) prefix[size_t(x) + 1] = prefix[size_t(x)] + image.at(x, y)[c];
      const auto integral = [&](double t) {  // of the box-pixel row over [0, t]
        const int i = std::min(int(std::floor(t)), w - 1);
        return prefix[size_t(i)] + (t - i) * image.at(i, y)[c];
      };
      for (int x = 0; x < w; ++x) {
        const double lo = std::max(0.0, x + 0.5 - 0.5 * widthPx);
        const double hi = std::min(double(w), x + 0.5 + 0.5 * widthPx);
        out.at(x, y)[c] = float((integral(hi) - integral(lo)) / (hi - lo));
      }
    }
  return out;
}

}  // namespace parallax
