// The photo maker checked against what it does not compute: the moiré of two gratings, the
// parallax of a gap, the lens sheet's sampling, a pinhole's projection and OpenCV's distortion
// formula, a thin lens's circle of confusion, each derived here from the geometry alone.
#include "parallax/photomaker/photo_maker.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace parallax::photomaker {
namespace {

constexpr double kPi = 3.14159265358979323846;

Image solid(int width, int height, float value) {
  return Image(width, height, Vec3f(value));
}

// The frequency (cycles per sample) of the strongest component of `signal` within [lo, hi]:
// its mean removed, a Hann window, the discrete-time Fourier transform's power searched on a
// fine grid and refined by golden section (a peak between DFT bins, found to far better than a
// bin).
double peakFrequency(const std::vector<double>& signal, double lo, double hi) {
  const size_t n = signal.size();
  double mean = 0;
  for (double v : signal) mean += v;
  mean /= double(n);
  std::vector<double> w(n);
  for (size_t i = 0; i < n; ++i)
    w[i] = (signal[i] - mean) * 0.5 * (1 - std::cos(2 * kPi * double(i) / double(n - 1)));
  const auto power = [&](double f) {
    double re = 0, im = 0;
    for (size_t i = 0; i < n; ++i) {
      re += w[i] * std::cos(2 * kPi * f * double(i));
      im += w[i] * std::sin(2 * kPi * f * double(i));
    }
    return re * re + im * im;
  };
  const int steps = 1000;
  double best = lo, bestPower = -1;
  for (int s = 0; s <= steps; ++s) {
    const double f = lo + (hi - lo) * s / steps;
    const double p = power(f);
    if (p > bestPower) best = f, bestPower = p;
  }
  double a = std::max(lo, best - (hi - lo) / steps), b = std::min(hi, best + (hi - lo) / steps);
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int it = 0; it < 60; ++it) {
    const double c = b - g * (b - a), d = a + g * (b - a);
    if (power(c) > power(d))
      b = d;
    else
      a = c;
  }
  return 0.5 * (a + b);
}

// The brightness of a picture column: the sum over rows and channels.
std::vector<double> columnSums(const Image& image) {
  std::vector<double> sums(size_t(image.width()), 0.0);
  for (int j = 0; j < image.height(); ++j)
    for (int i = 0; i < image.width(); ++i) {
      const Vec3f& v = image.at(i, j);
      sums[size_t(i)] += double(v.x) + double(v.y) + double(v.z);
    }
  return sums;
}

double linearSum(const PhotoPixels& photo, int x, int y) {
  const size_t at = (size_t(y) * size_t(photo.width) + size_t(x)) * 3;
  return double(srgb8ToLinear(photo.rgb[at])) + double(srgb8ToLinear(photo.rgb[at + 1])) +
         double(srgb8ToLinear(photo.rgb[at + 2]));
}

// The brightness-weighted mean position and variance (per axis) of a photo's light within a
// window, positions in sensor pixels (pixel i spans [i, i + 1)).
struct Blob {
  double x = 0, y = 0, varX = 0, varY = 0, mass = 0;
};
// Pixels not above `floor` are left out (the grey room around the panel, where it shows).
Blob blobIn(const PhotoPixels& photo, int x0, int y0, int x1, int y1, double floor = 0) {
  Blob b;
  double sx = 0, sy = 0, sxx = 0, syy = 0;
  for (int y = std::max(0, y0); y < std::min(photo.height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(photo.width, x1); ++x) {
      const double w = linearSum(photo, x, y);
      if (w <= floor) continue;
      const double px = x + 0.5, py = y + 0.5;
      b.mass += w, sx += w * px, sy += w * py, sxx += w * px * px, syy += w * py * py;
    }
  b.x = sx / b.mass, b.y = sy / b.mass;
  b.varX = sxx / b.mass - b.x * b.x, b.varY = syy / b.mass - b.y * b.y;
  return b;
}

// -- Barrier ------------------------------------------------------------------------------------

// Two vertical slit gratings, front period Tf and rear period Tr (panel pixels), seen by an eye
// on the axis at distance Z. The eye's line through front point x meets the rear at
// x (Z + g) / Z, so the rear grating, seen on the front plane, has period Tr Z / (Z + g) (it is
// farther away: it looks smaller) and frequency (Z + g) / (Z Tr). Their product beats at the
// difference of frequencies: the moiré period on the front plane is
//     1 / |1 / Tf - (Z + g) / (Z Tr)|.
// (Writing the rear's frequency as Z / ((Z + g) Tr) instead, magnifying it, would put the peak
// at 0.0906 instead of 0.0758 cycles per pixel at Z = 100: outside the tolerance by far, inside
// the searched band.)
TEST(PhotoMakerBarrier, MoireOfTwoSlitGratingsHasTheAnalyticPeriod) {
  PhysicalBarrier display;
  display.gapMm = 3.0;
  display.front.width = 400, display.front.height = 40;
  display.rear.width = 440, display.rear.height = 48;  // every ray from the eye lands on it
  const int tf = 3, tr = 4;
  Image front = solid(display.front.width, display.front.height, 0.0f);
  Image rear = solid(display.rear.width, display.rear.height, 0.0f);
  for (int j = 0; j < front.height(); ++j)
    for (int i = 0; i < front.width(); i += tf) front.at(i, j) = Vec3f(1.0f);
  for (int j = 0; j < rear.height(); ++j)
    for (int i = 0; i < rear.width(); i += tr) rear.at(i, j) = Vec3f(1.0f);
  for (double z : {100.0, 250.0}) {
    const Image seen = eyeViewBarrier(display, front, rear, {0, 0, z}, display.front.width, 8, 16);
    // One picture pixel is one front pixel: frequencies in cycles per front pixel.
    const double expected = std::abs(1.0 / tf - (z + display.gapMm) / (z * tr));
    const double measured = peakFrequency(columnSums(seen), 0.06, 0.1);
    EXPECT_NEAR(measured / expected, 1.0, 0.01)
        << "Z " << z << ": measured " << measured << ", expected " << expected;
  }
}

// One white rear column at x0 behind a white front, the eye at (X, 0, Z). The line from the eye
// through front point x (z = 0) reaches the rear (z = -g) at r = x + (x - X) g / Z; it meets
// the column where r = x0: x = (x0 Z + X g) / (Z + g) = x0 + (X - x0) g / (Z + g). The front is
// a fine grating of 0.01 mm pixels here, so its stripes average out under a rear pixel and the
// light's centroid is the geometry's, not the two panels' stripe alignment.
TEST(PhotoMakerBarrier, RearColumnAppearsWhereTheGapPutsIt) {
  PhysicalBarrier display;
  display.gapMm = 3.0;
  display.front.width = 2000, display.front.height = 30, display.front.pitchMm = 0.01;
  display.rear.width = 60, display.rear.height = 5;
  const Image front = solid(display.front.width, display.front.height, 1.0f);
  Image rear = solid(display.rear.width, display.rear.height, 0.0f);
  const int column = 25;
  for (int j = 0; j < rear.height(); ++j) rear.at(column, j) = Vec3f(1.0f);
  const double pitch = display.rear.pitchMm;
  const double x0 = (column + 0.5 - 0.5 * display.rear.width) * pitch;
  const double z = 400, g = display.gapMm;
  for (double x : {-300.0, 0.0, 250.0}) {
    const Image seen = eyeViewBarrier(display, front, rear, {x, 0, z}, 2000, 2, 16);
    const std::vector<double> sums = columnSums(seen);
    double mass = 0, moment = 0;
    for (size_t i = 0; i < sums.size(); ++i) {
      const double at = -10.0 + (double(i) + 0.5) * 0.01;  // the picture spans the front
      mass += sums[i], moment += sums[i] * at;
    }
    const double expected = x0 + (x - x0) * g / (z + g);
    ASSERT_GT(mass, 0.0);
    EXPECT_NEAR(moment / mass, expected, 0.05 * pitch) << "eye at x " << x;
  }
}

// -- Lenticular ---------------------------------------------------------------------------------

// The eye at distance Z on the axis looks through lens k's axis (across c_k, z = 0) along a
// line that goes on to the pixel plane (z = -G) at c_k + G c_k / Z = c_k (Z + G) / Z (the lens
// is focused on the pixels, so it shows the point its chief ray lands on). The lenses therefore
// sample the pixel plane every pitch (Z + G) / Z: a pixel grating of period P on the panel is
// seen, lens by lens, at frequency (Z + G) / (Z P) per lens-plane millimetre, aliased by the
// lens sampling (1 / pitch) to the moiré frequency |(Z + G) / (Z P) - 1 / pitch|.
// (pitch Z / (Z - G) for the sampling period would give 0.0278 cycles per picture pixel and
// Z / (Z + G) 0.0227, against 0.025 here.)
TEST(PhotoMakerLenticular, MoireWithAPixelGratingHasTheAnalyticPeriod) {
  PhysicalLenticular display;
  display.panel.width = 500, display.panel.height = 20, display.panel.pitchMm = 0.1;
  display.pitchMm = 0.5, display.slantDegrees = 0, display.phaseMm = 0.25;
  display.focalGapMm = 4.0;
  const int period = 5;  // pixels: P = 0.5 mm, the lens pitch
  Image panel = solid(display.panel.width, display.panel.height, 0.0f);
  for (int j = 0; j < panel.height(); ++j)
    for (int i = 0; i < panel.width(); i += period) panel.at(i, j) = Vec3f(1.0f);
  const double z = 40, g = display.focalGapMm, pMm = period * display.panel.pitchMm;
  const int width = 400;  // 0.125 mm per picture pixel over the 50 mm panel
  const Image seen = eyeViewLenticular(display, panel, {0, 0, z}, width, 4, 16);
  // The outer lenses send the eye to points beyond the panel's edge (c (Z + G) / Z > 25 mm):
  // the middle 40 mm only.
  std::vector<double> sums = columnSums(seen);
  sums = std::vector<double>(sums.begin() + 40, sums.end() - 40);
  const double mmPerPixel = 50.0 / width;
  const double expected = std::abs((z + g) / (z * pMm) - 1.0 / display.pitchMm) * mmPerPixel;
  const double measured = peakFrequency(sums, 0.015, 0.035);
  EXPECT_NEAR(measured / expected, 1.0, 0.01) << measured << " vs " << expected;
}

// One lit subpixel column (green, at x_s) under vertical lenses; the eye at (X, 0, Z). Through
// lens k the eye's ray has across slope (c_k - X) / Z, so the lens shows the pixel-plane point
// c_k + G (c_k - X) / Z = c_k - G tan(theta), theta the eye's angle from the normal seen from
// the lens (positive: the eye to the right; it sees the point to the left of the lens axis).
// The lens lights up for the eye at X_k = c_k + (c_k - x_s) Z / G, and the brightness of lens k
// over a sweep of eyes is centred there.
TEST(PhotoMakerLenticular, EachLensShowsThePointItsDirectionSelects) {
  PhysicalLenticular display;
  display.panel.width = 60, display.panel.height = 20, display.panel.pitchMm = 0.1;
  display.pitchMm = 0.5, display.slantDegrees = 0, display.phaseMm = 0.25;
  display.focalGapMm = 1.0;
  Image panel = solid(display.panel.width, display.panel.height, 0.0f);
  const int column = 30;
  for (int j = 0; j < panel.height(); ++j) panel.at(column, j) = Vec3f(0, 1, 0);
  const double xs = (column + 0.5 - 30) * 0.1;  // the green stripe's centre: 0.05 mm
  const double z = 500, g = display.focalGapMm;
  // The picture: one pixel per lens (lens k spans [0.5 k, 0.5 k + 0.5] mm: picture column k + 6).
  for (int k : {-1, 0, 1}) {
    const double ck = display.phaseMm + k * display.pitchMm;
    const double xk = ck + (ck - xs) * z / g;
    double mass = 0, moment = 0, elsewhere = 0;
    for (int s = -40; s <= 40; ++s) {
      const double x = xk + 0.5 * s;
      const Image seen = eyeViewLenticular(display, panel, {x, 0, z}, 12, 4, 16);
      const std::vector<double> sums = columnSums(seen);
      mass += sums[size_t(k + 6)], moment += sums[size_t(k + 6)] * x;
      for (int other = 0; other < 12; ++other)
        if (other != k + 6) elsewhere += sums[size_t(other)];
    }
    ASSERT_GT(mass, 0.0) << "lens " << k;
    EXPECT_NEAR(moment / mass, xk, 0.1) << "lens " << k;  // 0.1 mm of eye: 0.0002 mm of pixels
    EXPECT_EQ(elsewhere, 0.0) << "lens " << k;
  }
}

// The slant and phase conventions. The lens axis direction is a = (sin s, cos s) (its top
// leans right for s > 0), across n = (cos s, -sin s), lens k's axis at across c_k = phase +
// k pitch. An eye far away on the axis sees through lens k the pixel-plane point at across c_k
// and along p.a (no power along the axis), so lens k lights where that point's x,
// c_k cos s + (p.a) sin s, is the lit column's x_s: p.a = (x_s - c_k cos s) / sin s. The lit
// spot is the part of lens k at that along-coordinate; its centre is c_k n + (p.a) a:
//     x = x_s,   y = -c_k sin s + (p.a) cos s = (x_s cos s - c_k) / sin s.
// The spots stack above the column, the lens to the right lit lower. (The phase as an x
// intercept instead of an across coordinate would move every spot by 0.07 mm here.)
TEST(PhotoMakerLenticular, SlantAndPhaseFollowTheirConventions) {
  PhysicalLenticular display;
  display.panel.width = 60, display.panel.height = 60, display.panel.pitchMm = 0.1;
  display.panel.fillFactor = 1.0;  // a continuous column: the spots' centres are the geometry's
  display.pitchMm = 0.5, display.slantDegrees = 20, display.phaseMm = 0.4;
  display.focalGapMm = 1.0;
  Image panel = solid(display.panel.width, display.panel.height, 0.0f);
  const int column = 30;
  for (int j = 0; j < panel.height(); ++j) panel.at(column, j) = Vec3f(0, 1, 0);
  const double xs = 0.05;
  const int size = 240;  // 0.025 mm picture pixels over 6 mm
  const Image seen = eyeViewLenticular(display, panel, {0, 0, 1e5}, size, size, 4);
  const double s = display.slantDegrees * kPi / 180;
  double total = 0, inWindows = 0;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) total += double(seen.at(i, j).y);
  int spots = 0;
  for (int k = -3; k <= 2; ++k) {
    const double ck = display.phaseMm + k * display.pitchMm;
    const double yk = (xs * std::cos(s) - ck) / std::sin(s);
    if (std::abs(yk) > 2.7) continue;
    ++spots;
    double mass = 0, mx = 0, my = 0;
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i) {
        const double x = -3 + (i + 0.5) * 0.025, y = 3 - (j + 0.5) * 0.025;
        if (std::abs(y - yk) > 0.6 || std::abs(x - xs) > 0.6) continue;
        const double w = seen.at(i, j).y;
        mass += w, mx += w * x, my += w * y;
      }
    ASSERT_GT(mass, 0.0) << "lens " << k;
    inWindows += mass;
    EXPECT_NEAR(mx / mass, xs, 0.01) << "lens " << k;
    EXPECT_NEAR(my / mass, yk, 0.02) << "lens " << k;
  }
  EXPECT_EQ(spots, 4);
  EXPECT_NEAR(inWindows / total, 1.0, 1e-9);  // no light anywhere else
}

// -- Camera -------------------------------------------------------------------------------------

// The test's own camera frame: forward to the target, right = forward x (0, 1, 0), up = right x
// forward, then right and up turned by the roll (right toward up for a positive roll).
struct Frame {
  double c[3], right[3], down[3], forward[3];
};
Frame frameOf(const PhoneCamera& camera) {
  Frame f{};
  double fw[3], n = 0;
  for (int a = 0; a < 3; ++a) {
    f.c[a] = camera.positionMm[size_t(a)];
    fw[a] = camera.lookAtMm[size_t(a)] - f.c[a];
    n += fw[a] * fw[a];
  }
  for (double& v : fw) v /= std::sqrt(n);
  double r[3] = {-fw[2], 0, fw[0]};  // forward x (0, 1, 0)
  const double rn = std::hypot(r[0], r[2]);
  r[0] /= rn, r[2] /= rn;
  const double u[3] = {r[1] * fw[2] - r[2] * fw[1], r[2] * fw[0] - r[0] * fw[2],
                       r[0] * fw[1] - r[1] * fw[0]};
  const double roll = camera.rollDegrees * kPi / 180;
  for (int a = 0; a < 3; ++a) {
    f.forward[a] = fw[a];
    f.right[a] = std::cos(roll) * r[a] + std::sin(roll) * u[a];
    f.down[a] = -(-std::sin(roll) * r[a] + std::cos(roll) * u[a]);
  }
  return f;
}
// A world point's place on the sensor by the pinhole and OpenCV's forward radial model:
// x_d = x (1 + k1 r^2 + k2 r^4), pixel = centre + focal x_d, the centre at (width/2, height/2).
void project(const PhoneCamera& camera, const double p[3], double& u, double& v) {
  const Frame f = frameOf(camera);
  double x = 0, y = 0, depth = 0;
  for (int a = 0; a < 3; ++a) {
    const double d = p[a] - f.c[a];
    x += d * f.right[a], y += d * f.down[a], depth += d * f.forward[a];
  }
  x /= depth, y /= depth;
  const double r2 = x * x + y * y;
  const double k = 1 + camera.k1 * r2 + camera.k2 * r2 * r2;
  u = 0.5 * camera.width + camera.focalPx * x * k;
  v = 0.5 * camera.height + camera.focalPx * y * k;
}

// A front panel of 2 mm pixels, black but for a few white ones, over an identical white rear
// with no gap (so the rear's stripes are the front's and a white pixel's light is centred on it).
struct WhitePixels {
  PhysicalBarrier display;
  Image front, rear;
  std::vector<std::pair<int, int>> lit;
  WhitePixels(std::vector<std::pair<int, int>> pixels) : lit(std::move(pixels)) {
    display.gapMm = 0;
    display.front.width = display.rear.width = 200;
    display.front.height = display.rear.height = 120;
    display.front.pitchMm = display.rear.pitchMm = 2.0;
    front = solid(200, 120, 0.0f);
    rear = solid(200, 120, 1.0f);
    for (auto [i, j] : lit) front.at(i, j) = Vec3f(1.0f);
  }
  void centre(size_t n, double p[3]) const {
    p[0] = (lit[n].first + 0.5 - 100) * 2.0;
    p[1] = (60 - lit[n].second - 0.5) * 2.0;
    p[2] = 0;
  }
};

PhoneCamera smallCamera() {
  PhoneCamera camera;
  camera.width = 640, camera.height = 480, camera.focalPx = 500;
  camera.samplesPerPixel = 16;
  return camera;
}

TEST(PhotoMakerCamera, PictureUpIsDisplayUpAndRollTurnsTheSceneClockwise) {
  const WhitePixels scene({{120, 40}});  // right of and above the display's centre
  double p[3];
  scene.centre(0, p);
  ASSERT_GT(p[0], 0);
  ASSERT_GT(p[1], 0);
  PhoneCamera camera = smallCamera();
  camera.positionMm = {0, 0, 400};
  camera.focalPx = 1000;
  // The room shows beyond the panel's top and bottom edges (0.15 in all): left out.
  const PhotoPixels upright = photographBarrier(scene.display, scene.front, scene.rear, camera);
  const Blob a = blobIn(upright, 0, 0, 640, 480, 0.2);
  EXPECT_GT(a.x, 320);      // right
  EXPECT_LT(a.y, 240);      // up: row 0 is the top
  camera.rollDegrees = 90;  // the camera turned counter-clockwise: right now points up
  const PhotoPixels rolled = photographBarrier(scene.display, scene.front, scene.rear, camera);
  const Blob b = blobIn(rolled, 0, 0, 640, 480, 0.2);
  // Clockwise by 90 degrees about the centre: (dx, dy) -> (-dy, dx) in picture coordinates.
  EXPECT_NEAR(b.x - 320, -(a.y - 240), 0.5);
  EXPECT_NEAR(b.y - 240, a.x - 320, 0.5);
}

// A pinhole photo of white pixels lands where the pinhole projection puts them, and with
// radial distortion where OpenCV's forward formula moves the projection (the photo maker
// inverts that formula for its rays; this applies it forward).
TEST(PhotoMakerCamera, WhitePixelsLandAtTheirProjection) {
  const WhitePixels scene({{150, 30}, {40, 90}, {100, 60}, {185, 105}});
  for (auto [k1, k2] : {std::pair{0.0, 0.0}, std::pair{-0.15, 0.04}, std::pair{0.1, 0.0}}) {
    PhoneCamera camera = smallCamera();
    camera.positionMm = {40, -30, 300};
    camera.lookAtMm = {10, 5, 0};
    camera.rollDegrees = 7;
    camera.k1 = k1, camera.k2 = k2;
    const PhotoPixels photo = photographBarrier(scene.display, scene.front, scene.rear, camera);
    for (size_t n = 0; n < scene.lit.size(); ++n) {
      double p[3], u, v;
      scene.centre(n, p);
      project(camera, p, u, v);
      ASSERT_TRUE(u > 15 && u < 625 && v > 15 && v < 465) << u << " " << v;
      const Blob b = blobIn(photo, int(u) - 12, int(v) - 12, int(u) + 13, int(v) + 13);
      ASSERT_GT(b.mass, 0.0);
      EXPECT_NEAR(b.x, u, 0.2) << "k1 " << k1 << " pixel " << n;
      EXPECT_NEAR(b.y, v, 0.2) << "k1 " << k1 << " pixel " << n;
    }
  }
}

// A thin lens of aperture A focused at Df images a point at distance Dp as a uniform disk of
// diameter focal A |1/Dp - 1/Df| sensor pixels (a lens point a offset from the centre sends the
// ray for normalised sensor point x to the object plane at Dp x + a (1 - Dp / Df)), centred on
// the pinhole projection; a disk of diameter c adds c^2 / 16 to the variance along each axis.
TEST(PhotoMakerCamera, DefocusBlurIsTheCircleOfConfusion) {
  // A 3 x 3 block of white pixels (6 mm, 10 sensor pixels): a source large enough that most of
  // the aperture's rays for a pixel in the blur see it, so 256 samples measure the blur's
  // moments to a few hundredths of a pixel.
  std::vector<std::pair<int, int>> block;
  for (int j = 59; j <= 61; ++j)
    for (int i = 99; i <= 101; ++i) block.push_back({i, j});
  const WhitePixels scene(block);
  PhoneCamera camera = smallCamera();
  camera.width = camera.height = 64;
  camera.positionMm = {0, 0, 300};
  camera.samplesPerPixel = 256;
  const PhotoPixels sharp = photographBarrier(scene.display, scene.front, scene.rear, camera);
  camera.apertureMm = 8, camera.focusDistanceMm = 150;
  const PhotoPixels blurred = photographBarrier(scene.display, scene.front, scene.rear, camera);
  const Blob a = blobIn(sharp, 0, 0, 64, 64), b = blobIn(blurred, 0, 0, 64, 64);
  const double c = camera.focalPx * camera.apertureMm * std::abs(1 / 300.0 - 1 / 150.0);
  EXPECT_NEAR(b.varX - a.varX, c * c / 16, 0.03 * c * c / 16);
  EXPECT_NEAR(b.varY - a.varY, c * c / 16, 0.03 * c * c / 16);
  EXPECT_NEAR(b.x, a.x, 0.05);
  EXPECT_NEAR(b.y, a.y, 0.05);
  EXPECT_NEAR(b.mass, a.mass, 0.01 * a.mass);  // the blur moves light, it neither adds nor loses
  // Focused on the panel, the same aperture blurs nothing.
  camera.focusDistanceMm = 300;
  const Blob f =
      blobIn(photographBarrier(scene.display, scene.front, scene.rear, camera), 0, 0, 64, 64);
  EXPECT_NEAR(f.varX, a.varX, 0.01 * a.varX);
  EXPECT_NEAR(f.varY, a.varY, 0.01 * a.varY);
}

// A camera where the eye is, its sensor pixels exactly the eye view's pixels (focal Z w / W),
// photographs what the eye sees: the lenticular photo path against the eye view, block by block.
TEST(PhotoMakerCamera, LenticularPhotoIsWhatTheEyeSees) {
  PhysicalLenticular display;
  display.panel.width = 120, display.panel.height = 80, display.panel.pitchMm = 0.25;
  display.pitchMm = 0.6, display.slantDegrees = 8, display.phaseMm = 0.1;
  display.focalGapMm = 1.5, display.spotSigmaMm = 0.02;
  Image panel(120, 80);
  for (int j = 0; j < 80; ++j)
    for (int i = 0; i < 120; ++i) panel.at(i, j) = Vec3f(i / 120.0f, j / 80.0f, 0.5f);
  const double z = 300;
  const Image seen = eyeViewLenticular(display, panel, {0, 0, z}, 120, 80, 256);
  PhoneCamera camera;
  camera.positionMm = {0, 0, z};
  camera.width = 120, camera.height = 80;
  camera.focalPx = z * 120 / 30.0;
  camera.samplesPerPixel = 256;
  const PhotoPixels photo = photographLenticular(display, panel, camera);
  double worst = 0;
  for (int by = 0; by < 80; by += 20)
    for (int bx = 0; bx < 120; bx += 20) {
      double eye[3] = {0, 0, 0}, cam[3] = {0, 0, 0};
      for (int j = by; j < by + 20; ++j)
        for (int i = bx; i < bx + 20; ++i)
          for (int c = 0; c < 3; ++c) {
            eye[c] += seen.at(i, j)[c];
            cam[c] += srgb8ToLinear(photo.rgb[(size_t(j) * 120 + size_t(i)) * 3 + size_t(c)]);
          }
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(cam[c] / eye[c] - 1));
    }
  EXPECT_LT(worst, 0.03);  // sampling noise: 0.014 measured at 256 samples per pixel
}

TEST(PhotoMakerCamera, SameBytesWhateverTheThreadCount) {
  const WhitePixels scene({{150, 30}, {40, 90}});
  PhoneCamera camera = smallCamera();
  camera.width = 320, camera.height = 240, camera.samplesPerPixel = 4;
  camera.positionMm = {20, 10, 400};
  camera.apertureMm = 3, camera.focusDistanceMm = 380, camera.k1 = -0.1;
  camera.noiseSigma = 0.01, camera.shotNoise = 0.001, camera.seed = 7;
  const PhotoPixels one = photographBarrier(scene.display, scene.front, scene.rear, camera, 1);
  const PhotoPixels two = photographBarrier(scene.display, scene.front, scene.rear, camera, 2);
  EXPECT_EQ(one.rgb, two.rgb);
  camera.seed = 8;  // and the seed matters (the noise, the samples)
  EXPECT_NE(photographBarrier(scene.display, scene.front, scene.rear, camera, 2).rgb, one.rgb);

  PhysicalLenticular lenticular;
  lenticular.panel.width = 200, lenticular.panel.height = 120;
  lenticular.spotSigmaMm = 0.03, lenticular.focalLengthMm = 1.2;
  const Image panel = solid(200, 120, 0.5f);
  EXPECT_EQ(photographLenticular(lenticular, panel, camera, 1).rgb,
            photographLenticular(lenticular, panel, camera, 2).rgb);
  const Image a = eyeViewLenticular(lenticular, panel, {10, 0, 500}, 100, 60, 4, 1);
  const Image b = eyeViewLenticular(lenticular, panel, {10, 0, 500}, 100, 60, 4, 2);
  for (size_t i = 0; i < a.pixels().size(); ++i) ASSERT_EQ(a.pixels()[i], b.pixels()[i]);
}

// The sensor's noise: a photo of the grey room alone (the camera turned away from the display:
// 0.05 everywhere), decoded back to linear light, has the read noise's and shot noise's
// variance, sigma^2 + shot 0.05, and a normal distribution's share within one sigma.
TEST(PhotoMakerCamera, NoiseHasItsVarianceAndIsNormal) {
  const WhitePixels scene({{100, 60}});
  PhoneCamera camera = smallCamera();
  camera.width = 320, camera.height = 240, camera.samplesPerPixel = 1;
  camera.positionMm = {0, 0, 600};
  camera.lookAtMm = {0, 0, 1000};
  for (double shot : {0.0, 0.002}) {
    camera.noiseSigma = 0.01, camera.shotNoise = shot;
    const PhotoPixels photo = photographBarrier(scene.display, scene.front, scene.rear, camera);
    double sum = 0, sum2 = 0;
    for (uint8_t code : photo.rgb) {
      const double v = srgb8ToLinear(code);
      sum += v, sum2 += v * v;
    }
    const double count = double(photo.rgb.size());
    const double mean = sum / count, sigma = std::sqrt(sum2 / count - mean * mean);
    const double expected = std::sqrt(0.01 * 0.01 + shot * 0.05);
    EXPECT_NEAR(mean, 0.05, 0.0005) << "shot " << shot;
    EXPECT_NEAR(sigma / expected, 1.0, 0.02) << "shot " << shot;
    double within = 0;
    for (uint8_t code : photo.rgb) within += std::abs(srgb8ToLinear(code) - mean) < expected;
    EXPECT_NEAR(within / count, 0.6827, 0.02) << "shot " << shot;
  }
}

TEST(PhotoMakerCamera, RejectsPicturesOfAnotherSize) {
  PhysicalBarrier display;
  display.front.width = display.rear.width = 20;
  display.front.height = display.rear.height = 10;
  PhoneCamera camera = smallCamera();
  EXPECT_THROW(photographBarrier(display, solid(20, 10, 1), solid(20, 11, 1), camera),
               std::invalid_argument);
  PhysicalLenticular lenticular;
  EXPECT_THROW(eyeViewLenticular(lenticular, solid(20, 10, 1), {0, 0, 500}, 10, 10, 1),
               std::invalid_argument);
}

// The accuracy study's photo: 4032 x 3024 at 16 samples per pixel, an aperture, distortion and
// noise (run with --gtest_also_run_disabled_tests; prints seconds).
TEST(PhotoMakerSpeed, DISABLED_TwelveMegapixelPhotos) {
  PhysicalBarrier barrier;
  barrier.front.width = barrier.rear.width = 1920;
  barrier.front.height = barrier.rear.height = 1080;
  const Image front = solid(1920, 1080, 0.8f), rear = solid(1920, 1080, 0.6f);
  PhoneCamera camera;
  camera.positionMm = {30, 20, 600};
  camera.rollDegrees = 3;
  camera.apertureMm = 2, camera.k1 = 0.05, camera.k2 = -0.01;
  camera.noiseSigma = 0.005, camera.shotNoise = 0.0005;
  auto start = std::chrono::steady_clock::now();
  const PhotoPixels a = photographBarrier(barrier, front, rear, camera);
  const double barrierSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  PhysicalLenticular lenticular;
  lenticular.panel.width = 1920, lenticular.panel.height = 1080;
  lenticular.spotSigmaMm = 0.02;
  start = std::chrono::steady_clock::now();
  const PhotoPixels b = photographLenticular(lenticular, front, camera);
  const double lenticularSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("4032 x 3024 at 16 spp: barrier %.2f s, lenticular %.2f s\n", barrierSeconds,
              lenticularSeconds);
  EXPECT_EQ(a.rgb.size(), b.rgb.size());
}

}  // namespace
}  // namespace parallax::photomaker
