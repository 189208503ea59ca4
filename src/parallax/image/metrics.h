// Image comparison and resampling for judging simulated views against references. Images hold
// linear light; PSNR and SSIM compare sRGB-encoded values in [0, 1] (linear values clamped
// first), because that is what a viewer compares on a screen and what the metrics were
// designed for (Wang et al. 2004 used 8-bit grey codes).
#pragma once

#include "parallax/image/image.h"

namespace parallax {

enum class MetricEncoding { Srgb, Linear };

// Rec. 709 / sRGB luminance Y of a linear RGB value.
inline float luminance(const Vec3f& rgb) {
  return 0.2126f * rgb.x + 0.7152f * rgb.y + 0.0722f * rgb.z;
}
double meanLuminance(const Image& image);

// Mean over pixels and channels of the squared difference. Throws InputError when sizes differ.
double meanSquaredError(const Image& a, const Image& b,
                        MetricEncoding encoding = MetricEncoding::Srgb);
// 10 log10(peak^2 / MSE); infinity for identical images.
double psnr(const Image& a, const Image& b, double peak = 1.0,
            MetricEncoding encoding = MetricEncoding::Srgb);

// Each channel clamped to [0, 1] and sRGB-encoded: what PSNR compares. psnr(a, b) equals
// psnr(srgbEncoded(a), srgbEncoded(b), 1, MetricEncoding::Linear) exactly, so a caller that
// compares one image with several encodes it once.
Image srgbEncoded(const Image& image);

// What the dense measure takes of one picture against its ideal view, in one pass over the
// rows (each row encoded, then compared while it is in cache): `encoded` = srgbEncoded(picture);
// squaredError = the sum over pixels and channels of (encoded - idealEncoded)^2, so that
// meanSquaredError(picture, ideal) = squaredError / (3 pixels); flickerSquares (with a previous
// eye's encoded picture and ideal; NaN without) = the sum of
// ((encoded - idealEncoded) - (previousEncoded - previousIdealEncoded))^2; luminance = the sum of
// the picture's (linear) luminances, meanLuminance times the pixel count. Rows in parallel,
// their sums added in row order: the same figures for any thread count.
struct EncodedComparison {
  Image encoded;
  double squaredError = 0, flickerSquares = 0, luminance = 0;
};
EncodedComparison compareEncoded(const Image& picture, const Image& idealEncoded,
                                 const Image* previousEncoded = nullptr,
                                 const Image* previousIdealEncoded = nullptr);

// Mean SSIM of the sRGB-encoded luminance (Wang et al. 2004): an 11x11 Gaussian window of
// sigma 1.5, C1 = 0.01^2, C2 = 0.03^2 for values in [0, 1], averaged over the window positions
// that lie wholly inside the image. Needs images of at least 11x11 pixels.
double ssim(const Image& a, const Image& b);

// Horizontal box filter of (fractional) width widthPx centred on each pixel, over the image as
// a row of box pixels: each output is the mean of the input over [x + 1/2 - w/2, x + 1/2 + w/2],
// the box clipped to the image and renormalised at the edges. Brings a reference down to the
// display's spatial resolution (one aperture period).
Image boxFilterX(const Image& image, double widthPx);
// The same by the prefix integrals of each row, whatever the width: boxFilterX's way for boxes
// wider than BoxRow::kMostTaps pixels, and the second code path its tests check the stencil
// against (`out`: a picture of the image's size to write into, else a new one).
Image boxFilterXByPrefixes(const Image& image, double widthPx, Image out = Image());
// The same along y (columns), for displays with vertical parallax (pinhole grids).
Image boxFilterY(const Image& image, double heightPx);

}  // namespace parallax
