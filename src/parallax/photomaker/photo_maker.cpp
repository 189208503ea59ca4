// The photo maker (photo_maker.h): every sensor sample is a ray through a thin lens, traced
// through the panels' physics; nothing here comes from the display, sim or camera modules, so
// that calibration tested against these photos is tested against physics, not against itself.
//
// Speed: the accuracy study renders hundreds of 12-megapixel photos at 16 samples per pixel, 200
// million rays each. Samples are made and traced in batches laid out lane by lane (structure of
// arrays) by loops without branches or library calls, which the lane kernels' AVX-512 and AVX2
// clones run 8 and 4 at a time (core/lane_kernel.h); every sample's random numbers come from its
// pixel's stream and its index, so the bytes do not depend on the batch or the thread.
#include "parallax/photomaker/photo_maker.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "parallax/core/lane_kernel.h"
#include "parallax/core/parallel.h"
#include "parallax/core/random.h"

namespace parallax::photomaker {

namespace {

constexpr double kPi = 3.14159265358979323846;
// What a ray that misses the display sees: a dim grey room, so that the panel's border shows in
// a photo (as it does in a real one, where the estimator must find it).
constexpr double kRoomLight = 0.05;
// SplitMix64's increment (core/random.h): draw m of a generator in state s is mix64(s + m g).
constexpr uint64_t kGolden = 0x9e3779b97f4a7c15ull;
// Sample indices of a pixel's stream that no sample uses: its noise, its aperture offset.
constexpr uint32_t kNoiseSample = 0xffffff00u, kOffsetSample = 0xfffffffeu;
// Samples traced per batch (a few pixels' worth): its arrays stay in the first-level cache.
constexpr int kBatchLanes = 256;

#define PM_INLINE [[gnu::always_inline]] inline

// Two uniform numbers in [0, 1) from one 64-bit draw.
PM_INLINE double highUniform(uint64_t bits) {
  return double(bits >> 32) * 0x1p-32;
}
PM_INLINE double lowUniform(uint64_t bits) {
  return double(bits & 0xffffffffu) * 0x1p-32;
}
// Four from one draw: 16 bits each, the middle of their 1/65536 bin (so the mean is exact).
// Enough for a jitter within one stratum (1/4 of a pixel or of the aperture at 16 samples):
// 1/262144 of a pixel. One draw for a sample's pixel and aperture positions halves the
// multiplies, most of the camera's own cost.
PM_INLINE double quarterUniform(uint64_t bits, int quarter) {
  return (double((bits >> (16 * quarter)) & 0xffffu) + 0.5) * 0x1p-16;
}

// sin and cos on [-pi/4, pi/4] by their Taylor series (error below 3e-9: a sample's place on an
// aperture of a few millimetres), written out so that a lane loop vectorises it.
PM_INLINE void sinCosQuarter(double t, double& s, double& c) {
  // Horner's form of the series, by reciprocals (x / 6 is a division: the compiler keeps it).
  const double t2 = t * t;
  s = t *
      (1 - t2 * (1.0 / 6) *
               (1 - t2 * (1.0 / 20) *
                        (1 - t2 * (1.0 / 42) * (1 - t2 * (1.0 / 72) * (1 - t2 * (1.0 / 110))))));
  c = 1 - t2 * (1.0 / 2) *
              (1 - t2 * (1.0 / 12) *
                       (1 - t2 * (1.0 / 30) *
                                (1 - t2 * (1.0 / 56) *
                                         (1 - t2 * (1.0 / 90) * (1 - t2 * (1.0 / 132))))));
}

// The natural logarithm of x in (0, 1] without libm (whose calls no loop vectorises): x =
// m 2^e with m in [sqrt(1/2), sqrt(2)), ln m = 2 atanh(s) with s = (m - 1) / (m + 1), |s| <=
// 0.172, by its series to s^13 (error below 2e-12).
PM_INLINE double lnUnit(double x) {
  const uint64_t bits = std::bit_cast<uint64_t>(x);
  double e = double(int32_t(bits >> 52) - 1023);
  double m = std::bit_cast<double>((bits & 0x000fffffffffffffull) | 0x3ff0000000000000ull);
  const bool high = m > 1.4142135623730951;
  m = high ? 0.5 * m : m;
  e = high ? e + 1 : e;
  const double s = (m - 1) / (m + 1), s2 = s * s;
  const double series =
      1 +
      s2 * (1.0 / 3 +
            s2 * (1.0 / 5 + s2 * (1.0 / 7 + s2 * (1.0 / 9 + s2 * (1.0 / 11 + s2 * (1.0 / 13))))));
  return e * 0.6931471805599453 + 2 * s * series;
}

// Two independent standard normal numbers from 64 random bits (Box-Muller): radius from the
// high 32 bits (uniform in (0, 1): at most 6.8 sigma), angle from the low 32: two bits pick
// the quadrant, the rest the angle within it, rotated there from [-pi/4, pi/4).
PM_INLINE void normalPair(uint64_t bits, double& z0, double& z1) {
  const double u = (double(bits >> 32) + 0.5) * 0x1p-32;
  const double radius = std::sqrt(-2 * lnUnit(u));
  const uint32_t low = uint32_t(bits);
  const uint32_t quadrant = low >> 30;
  const double t = (double(low & 0x3fffffffu) * 0x1p-30 - 0.5) * (kPi / 2);
  double s, c;
  sinCosQuarter(t, s, c);
  // The angle quadrant * pi/2 + pi/4 + t: turn (cos, sin) of pi/4 + t by the quadrant.
  const double h = 0.7071067811865476;
  const double cq = h * (c - s), sq = h * (c + s);
  const double cosA = quadrant == 0 ? cq : quadrant == 1 ? -sq : quadrant == 2 ? -cq : sq;
  const double sinA = quadrant == 0 ? sq : quadrant == 1 ? cq : quadrant == 2 ? -sq : -cq;
  z0 = radius * cosA;
  z1 = radius * sinA;
}

// Shirley and Chiu's concentric map from the unit square to the unit disk: area-preserving and
// keeping strata compact, so stratified square samples stay stratified on the aperture.
PM_INLINE void concentricDisk(double u, double v, double& x, double& y) {
  const double a = 2 * u - 1, b = 2 * v - 1;
  const bool wide = std::abs(a) > std::abs(b);
  const double r = wide ? a : b;
  const double t = (wide ? b : a) / (r == 0 ? 1.0 : r);
  double s, c;
  sinCosQuarter(kPi / 4 * t, s, c);
  // wide: angle t pi/4; else pi/2 - t pi/4, where cos and sin trade places.
  x = r * (wide ? c : s);
  y = r * (wide ? s : c);
}

// floor(q) for |q| < 2^31 without libm's call (baseline x86-64 has no rounding instruction):
// truncate, then step down where truncation went up.
PM_INLINE double floorSmall(double q) {
  const double k = double(int32_t(q));
  return k > q ? k - 1 : k;
}

// Stratification of n samples: an exact a x b grid (a the largest divisor of n not above
// sqrt(n)), so every stratum has the same area for any n and the mean stays unbiased (16: 4 x 4,
// 8: 2 x 4, a prime: 1 x n strips). The strata's corners are tabled.
struct Strata {
  int columns = 1, rows = 1;
  double invColumns = 1, invRows = 1;
  std::vector<double> cornerU, cornerV;  // of stratum k, in [0, 1)
  explicit Strata(int n) {
    for (int a = 1; a * a <= n; ++a)
      if (n % a == 0) rows = a;
    columns = n / rows;
    invColumns = 1.0 / columns, invRows = 1.0 / rows;
    for (int k = 0; k < n; ++k) {
      cornerU.push_back((k % columns) * invColumns);
      cornerV.push_back((k / columns) * invRows);
    }
  }
};

// A stride coprime with n near n / golden ratio: sample k takes aperture stratum
// (k * stride + offset) mod n, so that a pixel's sub-area and its aperture stratum are not tied
// to each other (k-th with k-th would correlate the pixel's left edge with the lens's left edge).
int decorrelatingStride(int n) {
  if (n <= 2) return 1;
  const int target = std::max(1, int(std::lround(n * 0.6180339887)));
  for (int d = 0; d < n; ++d) {
    for (int s : {target + d, target - d})
      if (s >= 1 && s < n && std::gcd(s, n) == 1) return s;
  }
  return 1;
}

// A batch of rays, lane by lane: origin, direction (toward the display), and each lane's
// generator state for the tracer's own draws (a lenticular spot).
struct Rays {
  std::vector<double> ox, oy, oz, dx, dy, dz;
  std::vector<uint64_t> state;
  // The aperture position's two uniform numbers, between the camera's loops.
  std::vector<double> lensU, lensV;
  // Each pixel's undistortion factor at its centre.
  std::vector<double> centreFactor;
  // Light gathered per lane and channel.
  std::vector<double> r, g, b;
  explicit Rays(int lanes) {
    for (auto* v : {&ox, &oy, &oz, &dx, &dy, &dz, &lensU, &lensV, &centreFactor, &r, &g, &b})
      v->assign(size_t(lanes), 0.0);
    state.assign(size_t(lanes), 0);
  }
};

// One LCD panel's transmittance (or emission) at a point of its plane, the picture looked up
// through the panel's pixel structure. Only one colour is ever non-zero at a point: a point lies
// in at most one stripe's aperture.
class PanelLookup {
 public:
  PanelLookup(const LcdPanel& panel, const Image& picture, const char* name)
      : width_(panel.width),
        height_(panel.height),
        channelBase_(panel.bgr ? 2 : 0),
        channelStep_(panel.bgr ? -1 : 1),
        pixels_(picture.empty() ? nullptr : &picture.pixels()[0].x) {
    if (panel.width <= 0 || panel.height <= 0 || !(panel.pitchMm > 0))
      throw std::invalid_argument(std::string(name) + " panel: size and pitch must be positive");
    if (double(panel.width) * panel.height * 3 >= 2147483648.0)
      throw std::invalid_argument(std::string(name) + " panel: too many pixels");
    if (picture.width() != panel.width || picture.height() != panel.height)
      throw std::invalid_argument(
          std::string(name) + " picture is " + std::to_string(picture.width()) + " x " +
          std::to_string(picture.height()) + ", the panel " + std::to_string(panel.width) + " x " +
          std::to_string(panel.height));
    const double angle = panel.rotationDegrees * kPi / 180;
    cos_ = std::cos(angle), sin_ = std::sin(angle);
    ox_ = panel.offsetXMm, oy_ = panel.offsetYMm;
    pitch_ = panel.pitchMm;
    invPitch_ = 1.0 / panel.pitchMm;
    widthPx_ = panel.width, heightPx_ = panel.height;
    // An aperture is the middle `fill` of its stripe (and of its pixel's height): the fraction
    // f of the cell in [0, 1) is open when |f - 1/2| < fill / 2.
    const double fill = std::clamp(panel.fillFactor, 0.0, 1.0);
    openLo_ = 0.5 - 0.5 * fill;
    openHi_ = 0.5 + 0.5 * fill;
  }

  // A point of the panel's plane from the panel's own (u, v) in pixels from its centre (u to
  // the right along its rows, v up): the panel is turned counter-clockwise by its rotation, so
  // world = offset + R(angle) local, and local = R(-angle) (world - offset).
  void world(double u, double v, double& x, double& y) const {
    x = ox_ + (cos_ * u - sin_ * v) * pitch_;
    y = oy_ + (sin_ * u + cos_ * v) * pitch_;
  }
  // The point (x, y) as a column from the panel's left edge and a row from its top edge, in
  // pixels (row 0 at the top).
  PM_INLINE void cell(double x, double y, double& column, double& row) const {
    const double dx = x - ox_, dy = y - oy_;
    column = (cos_ * dx + sin_ * dy) * invPitch_ + 0.5 * widthPx_;
    row = 0.5 * heightPx_ - (-sin_ * dx + cos_ * dy) * invPitch_;
  }
  PM_INLINE bool inside(double column, double row) const {
    return (column >= 0) & (column < widthPx_) & (row >= 0) & (row < heightPx_);
  }
  // What the point at (column, row) sees: the channel of the stripe it falls in, and that
  // channel's picture value where the point is in the stripe's aperture, 0 in the black matrix
  // and off the panel. Without branches: whether a jittered sample lands in an aperture is a
  // coin toss a branch predictor loses, and the lane loops must not branch.
  PM_INLINE float sample(double column, double row, int& channel) const {
    const bool on = inside(column, row);
    // Clamped (NaN to 0), so that a point off the panel still reads a pixel of the picture
    // (then unused).
    double c = column > 0 ? column : 0.0, r = row > 0 ? row : 0.0;
    c = c < widthPx_ ? c : widthPx_;
    r = r < heightPx_ ? r : heightPx_;
    const int i = std::min(int(c), width_ - 1), j = std::min(int(r), height_ - 1);
    const double fy = r - j;
    const double stripe = (c - i) * 3;
    const int s = std::min(int(stripe), 2);
    const double fx = stripe - s;
    const bool open = on & (fy > openLo_) & (fy < openHi_) & (fx > openLo_) & (fx < openHi_);
    channel = channelBase_ + channelStep_ * s;
    // Read whatever the aperture (a load only where open would be a masked gather, which the
    // vectoriser does not take), 32-bit indexed (the constructor checked the size).
    const float value = pixels_[(j * width_ + i) * 3 + channel];
    return value * (open ? 1.0f : 0.0f);
  }

 private:
  int width_, height_;
  // Stripe s (0, 1, 2 from the left) carries channel base + step s: R G B or B G R (as numbers,
  // not a select on a flag, which the vectoriser does not take).
  int channelBase_, channelStep_;
  const float* pixels_;
  double cos_ = 1, sin_ = 0, ox_ = 0, oy_ = 0, pitch_ = 1, invPitch_ = 1;
  double widthPx_ = 0, heightPx_ = 0;
  double openLo_ = 0, openHi_ = 1;
};

// Adds `value` to the lane's channel and `room` to all three.
PM_INLINE void deposit(Rays& rays, int l, int channel, double value, double room) {
  rays.r[size_t(l)] = room + (channel == 0 ? value : 0.0);
  rays.g[size_t(l)] = room + (channel == 1 ? value : 0.0);
  rays.b[size_t(l)] = room + (channel == 2 ? value : 0.0);
}

// The barrier: front panel at z = 0, rear at z = -gap, straight rays between (the gap is
// air-equivalent), rear(q) * front(p) * backlight, channel by channel.
struct BarrierTracer {
  PanelLookup front, rear;
  double gap, backlight;

  BarrierTracer(const PhysicalBarrier& display, const Image& frontPicture, const Image& rearPicture)
      : front(display.front, frontPicture, "front"),
        rear(display.rear, rearPicture, "rear"),
        gap(display.gapMm),
        backlight(display.backlight) {
    if (!(display.gapMm >= 0)) throw std::invalid_argument("barrier gap must not be negative");
  }
  const PanelLookup& outline() const { return front; }
};

PARALLAX_LANE_KERNEL
void traceLanes(const BarrierTracer& t, Rays& rays, int lanes) {
  const PanelLookup& front = t.front;
  const PanelLookup& rear = t.rear;
  const double gap = t.gap, backlight = t.backlight;
  PARALLAX_SIMD
  for (int l = 0; l < lanes; ++l) {
    const double ox = rays.ox[size_t(l)], oy = rays.oy[size_t(l)], oz = rays.oz[size_t(l)];
    const double dx = rays.dx[size_t(l)], dy = rays.dy[size_t(l)], dz = rays.dz[size_t(l)];
    const bool toward = (dz < 0) & (oz > 0);
    const double inv = toward ? 1.0 / -dz : 0.0;
    const double t0 = oz * inv;
    const double px = ox + t0 * dx, py = oy + t0 * dy;
    double fc, fr;
    front.cell(px, py, fc, fr);
    const bool hit = toward & front.inside(fc, fr);
    int cf;
    const float tf = front.sample(fc, fr, cf);
    // On to z = -gap: the same line, gap / -d.z further in units of d.
    const double s = gap * inv;
    double rc, rr;
    rear.cell(px + s * dx, py + s * dy, rc, rr);
    int cr;
    const float tr = rear.sample(rc, rr, cr);
    // Light from the backlight leaves the rear stripe with its colour; a front stripe of another
    // colour absorbs it. A ray that misses the front panel sees the room.
    const double light = hit & (cf == cr) ? backlight * double(tf) * double(tr) : 0.0;
    deposit(rays, l, cf, light, hit ? 0.0 : kRoomLight);
  }
}

// The lenticular sheet over an emitting panel. Lens k covers across-coordinates within half a
// pitch of its axis c_k = phase + k pitch (across = p . n, n = (cos s, -sin s) with s the slant,
// perpendicular to the axis direction a = (sin s, cos s) whose top leans right for s > 0).
//
// The lens, an ideal thin cylinder of focal length f at z = 0, bends only the across component.
// Paraxially a ray entering at across offset h = p.n - c_k from the axis with across slope
// m = (d.n) / (-d.z) (across millimetres per millimetre of depth) leaves with slope
// m' = m - h / f. At the pixel plane, G = focalGap deeper, it lands at
//     across = p.n + G m' = c_k + h + G m - G h / f = c_k + G m + (1 - G / f) h.
// With f = G every ray of slope m lands at c_k + G m, where the chief ray through the axis
// lands: the lens is focused on the pixels and one direction sees one point. With f != G the
// term (1 - G / f) h spreads a direction's rays over (1 - G / f) pitch: the defocus blur, a box
// as wide as the lens scaled by 1 - G / f. Along the axis the cylinder has no power: the ray
// goes straight on, along = p.a + G (d.a) / (-d.z). The spot (the lens's own aberrations and
// the diffuse pixel) adds a Gaussian across offset of spotSigma.
struct LenticularTracer {
  PanelLookup panel;
  double nx, ny, ax, ay;  // across and along unit vectors in the plane
  double pitch, invPitch, phase, gap, defocus, spot;

  LenticularTracer(const PhysicalLenticular& display, const Image& picture)
      : panel(display.panel, picture, "panel") {
    if (!(display.pitchMm > 0)) throw std::invalid_argument("lens pitch must be positive");
    if (!(display.focalGapMm > 0)) throw std::invalid_argument("focal gap must be positive");
    const double slant = display.slantDegrees * kPi / 180;
    nx = std::cos(slant), ny = -std::sin(slant);
    ax = std::sin(slant), ay = std::cos(slant);
    pitch = display.pitchMm;
    invPitch = 1.0 / pitch;
    // Lens indices are labels: the phase within one pitch gives the same axes. Then every
    // point of the panel has a lens index below 2^31 in size, as floorSmall needs.
    phase = display.phaseMm - pitch * std::floor(display.phaseMm / pitch);
    const LcdPanel& p = display.panel;
    const double reach = std::hypot(p.offsetXMm, p.offsetYMm) +
                         0.5 * p.pitchMm * std::hypot(double(p.width), double(p.height));
    if (!(reach / pitch < 1e9)) throw std::invalid_argument("lens pitch too small for the panel");
    gap = display.focalGapMm;
    defocus = display.focalLengthMm == 0 ? 0.0 : 1.0 - gap / display.focalLengthMm;
    spot = std::max(0.0, display.spotSigmaMm);
  }
  const PanelLookup& outline() const { return panel; }
};

PARALLAX_LANE_KERNEL
void traceLanes(const LenticularTracer& t, Rays& rays, int lanes) {
  const PanelLookup& panel = t.panel;
  const double nx = t.nx, ny = t.ny, ax = t.ax, ay = t.ay;
  const double pitch = t.pitch, invPitch = t.invPitch, phase = t.phase, gap = t.gap;
  const double defocus = t.defocus, spot = t.spot;
  // The spot's across offsets first (in the light's place, read before it is written), drawn
  // only where there is a spot: they cost a logarithm each.
  if (spot > 0) {
    PARALLAX_SIMD
    for (int l = 0; l < lanes; ++l) {
      double z, unused;
      normalPair(mix64(rays.state[size_t(l)] + 3 * kGolden), z, unused);
      rays.r[size_t(l)] = spot * z;
    }
  } else {
    std::fill(rays.r.begin(), rays.r.begin() + lanes, 0.0);
  }
  PARALLAX_SIMD
  for (int l = 0; l < lanes; ++l) {
    const double ox = rays.ox[size_t(l)], oy = rays.oy[size_t(l)], oz = rays.oz[size_t(l)];
    const double dx = rays.dx[size_t(l)], dy = rays.dy[size_t(l)], dz = rays.dz[size_t(l)];
    const bool toward = (dz < 0) & (oz > 0);
    const double inv = toward ? 1.0 / -dz : 0.0;
    const double t0 = oz * inv;
    const double px = ox + t0 * dx, py = oy + t0 * dy;
    // The sheet covers the panel: outside the panel's outline (seen straight on) is the room.
    double oc, orow;
    panel.cell(px, py, oc, orow);
    const bool hit = toward & panel.inside(oc, orow);
    // A lane that misses is traced from the origin instead (and dropped), so that the lens
    // index below stays within the panel's lenses (the constructor bounded them).
    const double hx = hit ? px : 0.0, hy = hit ? py : 0.0;
    const double pn = hx * nx + hy * ny, pa = hx * ax + hy * ay;
    const double ck = phase + floorSmall((pn - phase) * invPitch + 0.5) * pitch;
    const double depth = gap * inv;
    const double jitter = rays.r[size_t(l)];
    const double across = ck + depth * (dx * nx + dy * ny) + defocus * (pn - ck) + jitter;
    const double along = pa + depth * (dx * ax + dy * ay);
    double c, r;
    panel.cell(across * nx + along * ax, across * ny + along * ay, c, r);
    int channel;
    const float value = panel.sample(c, r, channel);
    deposit(rays, l, channel, hit ? double(value) : 0.0, hit ? 0.0 : kRoomLight);
  }
}

// Which sample of which pixel each lane of a batch is, and its aperture stratum before the
// pixel's offset: the same for every batch of a photo.
struct LaneTable {
  int samples = 1, pixels = 1, lanes = 1;
  std::vector<int> pixel, sample, lensBase;
  std::vector<double> cornerU, cornerV;
  LaneTable(const Strata& strata, int n, int stride) : samples(n) {
    pixels = std::max(1, kBatchLanes / n);
    lanes = pixels * n;
    for (int l = 0; l < lanes; ++l) {
      const int k = l % n;
      pixel.push_back(l / n);
      sample.push_back(k);
      lensBase.push_back(int((int64_t(k) * stride) % n));
      cornerU.push_back(strata.cornerU[size_t(k)]);
      cornerV.push_back(strata.cornerV[size_t(k)]);
    }
  }
};

// The phone: pose, thin lens with OpenCV's radial distortion, sensor.
struct CameraModel {
  PhoneCamera settings;
  Strata strata;
  double c[3], forward[3], right[3], down[3];
  double invFocal = 1, lensRadius = 0;
  bool distorted = false;
  int stride = 1;

  explicit CameraModel(const PhoneCamera& camera) : settings(camera), strata(1) {
    if (camera.width <= 0 || camera.height <= 0)
      throw std::invalid_argument("camera sensor size must be positive");
    if (camera.samplesPerPixel < 1)
      throw std::invalid_argument("camera samples per pixel must be at least 1");
    if (!(camera.focalPx > 0)) throw std::invalid_argument("camera focal length must be positive");
    if (!(camera.apertureMm >= 0)) throw std::invalid_argument("camera aperture must be >= 0");
    if (camera.apertureMm > 0 && !(camera.focusDistanceMm > 0))
      throw std::invalid_argument("camera focus distance must be positive");
    strata = Strata(camera.samplesPerPixel);
    double view[3], norm = 0;
    for (int a = 0; a < 3; ++a) {
      c[a] = camera.positionMm[size_t(a)];
      view[a] = camera.lookAtMm[size_t(a)] - c[a];
      norm += view[a] * view[a];
    }
    if (!(norm > 0)) throw std::invalid_argument("camera looks at its own position");
    for (int a = 0; a < 3; ++a) forward[a] = view[a] / std::sqrt(norm);
    // Right = forward x world up (0, 1, 0); picture up = right x forward. With forward -z (a
    // camera in front of the display looking at it), right is +x and up +y, as the viewer
    // sees them.
    double r0[3] = {-forward[2], 0, forward[0]};
    const double rn = std::hypot(r0[0], r0[2]);
    if (rn < 1e-6)
      throw std::invalid_argument("camera looks straight up or down: its roll is undefined");
    r0[0] /= rn, r0[2] /= rn;
    const double up[3] = {r0[1] * forward[2] - r0[2] * forward[1],
                          r0[2] * forward[0] - r0[0] * forward[2],
                          r0[0] * forward[1] - r0[1] * forward[0]};
    // Roll: the camera turned by rollDegrees counter-clockwise as its user sees through it
    // (right turns toward up), so the scene turns clockwise in the picture.
    const double roll = camera.rollDegrees * kPi / 180;
    const double cr = std::cos(roll), sr = std::sin(roll);
    for (int a = 0; a < 3; ++a) {
      right[a] = cr * r0[a] + sr * up[a];
      down[a] = sr * r0[a] - cr * up[a];  // -(cr up - sr right)
    }
    invFocal = 1.0 / camera.focalPx;
    lensRadius = 0.5 * camera.apertureMm;
    distorted = camera.k1 != 0 || camera.k2 != 0;
    stride = decorrelatingStride(camera.samplesPerPixel);
  }
};

// The rays of the samples of pixels i0 .. i0 + table.pixels - 1 (those below `width`) of row j.
// A sensor sample at pixel position (i + u, j + v) is the distorted normalised point
// x_d = (i + u - width/2) / focal (y likewise, the principal point at the sensor's centre).
// A real lens bends the ray that arrives at distorted point x_d from direction x_u, where
// x_d = x_u (1 + k1 r_u^2 + k2 r_u^4): the ray's direction is x_u = s x_d, s the root of
// h(s) = s (1 + k1 w + k2 w^2) - 1 with w = r_u^2 = s^2 |x_d|^2, by Newton's method
// (h'(s) = 1 + 3 k1 w + 5 k2 w^2). Each pixel's centre is solved from s0 = 1 / (1 + k1 r_d^2 +
// k2 r_d^4), within 2 k1^2 r^4 (relative) of the root; each step squares the error times about
// 3 k1 r^2, so four steps leave below 1e-20 for |k1| <= 0.3 at r = 0.8 (a phone's corner).
// A sample then takes one step from its pixel centre's s, which is within 2 k1 r dr (dr: the
// sample's distance from the centre, under 1e-3 of the focal length at 500 pixels' focal) of
// its own: 3 k1 r^2 (2 k1 r dr)^2 leaves 3e-7 relative for k1 = 0.3, 1e-4 of a pixel.
PARALLAX_LANE_KERNEL
void cameraLanes(const CameraModel& cam, const LaneTable& table, int i0, int j,
                 const uint64_t* streams, const int* lensOffsets, Rays& rays) {
  const int lanes = table.lanes, n = table.samples;
  const double cx = 0.5 * cam.settings.width, cy = 0.5 * cam.settings.height;
  const double invFocal = cam.invFocal, invColumns = cam.strata.invColumns,
               invRows = cam.strata.invRows;
  const double k1 = cam.settings.k1, k2 = cam.settings.k2;
  const double blur = cam.settings.blurSigmaPx;
  const double fx = cam.forward[0], fy = cam.forward[1], fz = cam.forward[2];
  const double rx = cam.right[0], ry = cam.right[1], rz = cam.right[2];
  const double wx = cam.down[0], wy = cam.down[1], wz = cam.down[2];
  const double ccx = cam.c[0], ccy = cam.c[1], ccz = cam.c[2];
  const int* pixel = table.pixel.data();
  const int* sample = table.sample.data();
  const double* cornerU = table.cornerU.data();
  const double* cornerV = table.cornerV.data();
  // The sensor point (normalised, distorted) in dx, dy for now.
  PARALLAX_SIMD
  for (int l = 0; l < lanes; ++l) {
    const uint64_t state = streams[pixel[l]] + Rng::sampleOffset(uint32_t(sample[l]));
    rays.state[size_t(l)] = state;
    const uint64_t bits = mix64(state + kGolden);
    double u = cornerU[l] + quarterUniform(bits, 0) * invColumns;
    double v = cornerV[l] + quarterUniform(bits, 1) * invRows;
    if (blur > 0) {
      // The lens's own blur, diffraction and demosaicing: a Gaussian point spread, each sample
      // moved on the sensor by it.
      double gx, gy;
      normalPair(mix64(state + 5 * kGolden), gx, gy);
      u += blur * gx, v += blur * gy;
    }
    rays.lensU[size_t(l)] = quarterUniform(bits, 2);
    rays.lensV[size_t(l)] = quarterUniform(bits, 3);
    rays.dx[size_t(l)] = (double(i0 + pixel[l]) + u - cx) * invFocal;
    rays.dy[size_t(l)] = (double(j) + v - cy) * invFocal;
  }
  if (cam.distorted) {
    // One Newton step for h(s) at squared radius r2 from s.
    const auto newton = [k1, k2](double r2, double s) {
      const double w = s * s * r2;
      const double h = s * (1 + w * (k1 + w * k2)) - 1;
      const double slope = 1 + w * (3 * k1 + 5 * w * k2);
      // Past the fold of a strong barrel (slope <= 0) no direction lands here: keep s.
      return slope > 0 ? s - h / slope : s;
    };
    double* centre = rays.centreFactor.data();
    const int pixels = table.pixels;
    PARALLAX_SIMD
    for (int p = 0; p < pixels; ++p) {
      const double x = (double(i0 + p) + 0.5 - cx) * invFocal,
                   y = (double(j) + 0.5 - cy) * invFocal;
      const double r2 = x * x + y * y;
      double s = 1 / (1 + r2 * (k1 + r2 * k2));
      for (int step = 0; step < 4; ++step) s = newton(r2, s);
      centre[p] = s;
    }
    PARALLAX_SIMD
    for (int l = 0; l < lanes; ++l) {
      const double x = rays.dx[size_t(l)], y = rays.dy[size_t(l)];
      const double s = newton(x * x + y * y, centre[pixel[l]]);
      rays.dx[size_t(l)] = x * s, rays.dy[size_t(l)] = y * s;
    }
  }
  // The pinhole ray: from the centre, direction forward + x right + y down (unit depth).
  PARALLAX_SIMD
  for (int l = 0; l < lanes; ++l) {
    const double x = rays.dx[size_t(l)], y = rays.dy[size_t(l)];
    rays.ox[size_t(l)] = ccx, rays.oy[size_t(l)] = ccy, rays.oz[size_t(l)] = ccz;
    rays.dx[size_t(l)] = fx + rx * x + wx * y;
    rays.dy[size_t(l)] = fy + ry * x + wy * y;
    rays.dz[size_t(l)] = fz + rz * x + wz * y;
  }
  if (cam.lensRadius > 0) {
    // Thin lens: every ray from the sensor point passes the point of the focus plane
    // (focusDistance along the axis) that the chief ray reaches, from a point of the aperture.
    const double radius = cam.lensRadius, focus = cam.settings.focusDistanceMm;
    const int* lensBase = table.lensBase.data();
    const double* strataU = cam.strata.cornerU.data();
    const double* strataV = cam.strata.cornerV.data();
    PARALLAX_SIMD
    for (int l = 0; l < lanes; ++l) {
      int stratum = lensBase[l] + lensOffsets[pixel[l]];
      stratum = stratum >= n ? stratum - n : stratum;
      const double u = strataU[stratum] + rays.lensU[size_t(l)] * invColumns;
      const double v = strataV[stratum] + rays.lensV[size_t(l)] * invRows;
      double a, b;
      concentricDisk(u, v, a, b);
      a *= radius, b *= radius;
      const double ox = ccx + rx * a + wx * b, oy = ccy + ry * a + wy * b,
                   oz = ccz + rz * a + wz * b;
      rays.dx[size_t(l)] = ccx + rays.dx[size_t(l)] * focus - ox;
      rays.dy[size_t(l)] = ccy + rays.dy[size_t(l)] * focus - oy;
      rays.dz[size_t(l)] = ccz + rays.dz[size_t(l)] * focus - oz;
      rays.ox[size_t(l)] = ox, rays.oy[size_t(l)] = oy, rays.oz[size_t(l)] = oz;
    }
  }
}

// Exposure, read noise and shot noise (one Gaussian of their summed variance per channel,
// drawn from the pixel's own stream at a sample index no sample uses, so that the noise, like
// the light, depends on the seed and the pixel only), as linear values for the sRGB encoder.
PARALLAX_LANE_KERNEL
void exposeLanes(const double* light, const uint64_t* streams, int pixels, double scale,
                 double read2, double shot, bool noisy, double* normals, float* out) {
  if (!noisy) {
    PARALLAX_SIMD
    for (int q = 0; q < 3 * pixels; ++q) out[q] = float(light[q] * scale);
    return;
  }
  // The normal numbers first, channel by channel (one plane each): a loop of whole vectors.
  PARALLAX_SIMD
  for (int p = 0; p < pixels; ++p) {
    const uint64_t state = streams[p] + Rng::sampleOffset(kNoiseSample);
    double z0, z1, z2, unused;
    normalPair(mix64(state + kGolden), z0, z1);
    normalPair(mix64(state + 2 * kGolden), z2, unused);
    normals[p] = z0, normals[pixels + p] = z1, normals[2 * pixels + p] = z2;
  }
  for (int p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c) {
      const double v = light[3 * p + c] * scale;
      out[3 * p + c] =
          float(v + std::sqrt(read2 + shot * std::max(0.0, v)) * normals[c * pixels + p]);
    }
}

// Each pixel's light: its lanes' sums in sample order (the same sums whatever the batch).
void sumPixels(const Rays& rays, int pixels, int n, double* light) {
  for (int p = 0; p < pixels; ++p) {
    double r = 0, g = 0, b = 0;
    for (int k = 0; k < n; ++k) {
      const size_t l = size_t(p) * size_t(n) + size_t(k);
      r += rays.r[l], g += rays.g[l], b += rays.b[l];
    }
    light[3 * p] = r, light[3 * p + 1] = g, light[3 * p + 2] = b;
  }
}

template <class Tracer>
PhotoPixels photograph(const Tracer& tracer, const PhoneCamera& settings, int threads) {
  const CameraModel camera(settings);
  const LaneTable table(camera.strata, settings.samplesPerPixel, camera.stride);
  PhotoPixels photo;
  photo.width = settings.width;
  photo.height = settings.height;
  photo.rgb.resize(size_t(settings.width) * size_t(settings.height) * 3);
  const double scale = settings.exposure / settings.samplesPerPixel;
  const bool noisy = settings.noiseSigma > 0 || settings.shotNoise > 0;
  const double read2 = settings.noiseSigma * settings.noiseSigma;
  const double shot = std::max(0.0, settings.shotNoise);
  const int n = settings.samplesPerPixel, width = settings.width;
  parallelFor(settings.height, threads, 1, [&](int64_t begin, int64_t end) {
    Rays rays(table.lanes);
    std::vector<uint64_t> streams(size_t(width) + size_t(table.pixels));
    std::vector<int> offsets(streams.size());
    std::vector<double> light(size_t(width) * 3), normals(size_t(width) * 3);
    std::vector<float> row(size_t(width) * 3);
    for (int64_t j = begin; j < end; ++j) {
      for (int i = 0; i < int(streams.size()); ++i) {
        streams[size_t(i)] = Rng::pixelStream(uint32_t(i), uint32_t(j), settings.seed);
        offsets[size_t(i)] =
            int(Rng::forSample(streams[size_t(i)], kOffsetSample).next() % uint32_t(n));
      }
      for (int i0 = 0; i0 < width; i0 += table.pixels) {
        // The last batch may reach past the row: those lanes are traced and dropped.
        cameraLanes(camera, table, i0, int(j), &streams[size_t(i0)], &offsets[size_t(i0)], rays);
        traceLanes(tracer, rays, table.lanes);
        sumPixels(rays, std::min(table.pixels, width - i0), n, &light[size_t(i0) * 3]);
      }
      exposeLanes(light.data(), streams.data(), width, scale, read2, shot, noisy, normals.data(),
                  row.data());
      linearToSrgb8(row.data(), row.size(), &photo.rgb[size_t(j) * row.size()]);
    }
  });
  return photo;
}

// An eye's view: pixel (i, j) of a width x height picture over a panel's rectangle (in that
// panel's own frame, row 0 at its top), the mean over stratified points of the pixel of the
// light reaching the eye through each point.
template <class Tracer>
Image eyeView(const Tracer& tracer, const LcdPanel& panel, const std::array<double, 3>& eyeMm,
              int width, int height, int samplesPerPixel, int threads) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("eye view size must be positive");
  if (samplesPerPixel < 1) throw std::invalid_argument("eye view samples must be at least 1");
  if (!(eyeMm[2] > 0)) throw std::invalid_argument("the eye must be in front of the display");
  const PanelLookup& outline = tracer.outline();
  const Strata strata(samplesPerPixel);
  const LaneTable table(strata, samplesPerPixel, 1);
  const int n = samplesPerPixel;
  Image image(width, height);
  // Picture pixels in panel pixels: the picture spans the panel's width and height.
  const double du = double(panel.width) / width, dv = double(panel.height) / height;
  parallelFor(height, threads, 1, [&](int64_t begin, int64_t end) {
    Rays rays(table.lanes);
    std::vector<double> light(size_t(table.pixels) * 3);
    for (int64_t j = begin; j < end; ++j) {
      for (int i0 = 0; i0 < width; i0 += table.pixels) {
        for (int l = 0; l < table.lanes; ++l) {
          const int i = i0 + table.pixel[size_t(l)];
          const uint64_t state = Rng::pixelStream(uint32_t(i), uint32_t(j), 0x5eedu) +
                                 Rng::sampleOffset(uint32_t(table.sample[size_t(l)]));
          const uint64_t bits = mix64(state + kGolden);
          const double su = table.cornerU[size_t(l)] + highUniform(bits) * strata.invColumns;
          const double sv = table.cornerV[size_t(l)] + lowUniform(bits) * strata.invRows;
          double x, y;
          outline.world((i + su) * du - 0.5 * panel.width, 0.5 * panel.height - (j + sv) * dv, x,
                        y);
          rays.state[size_t(l)] = state;
          rays.ox[size_t(l)] = eyeMm[0], rays.oy[size_t(l)] = eyeMm[1];
          rays.oz[size_t(l)] = eyeMm[2];
          rays.dx[size_t(l)] = x - eyeMm[0], rays.dy[size_t(l)] = y - eyeMm[1];
          rays.dz[size_t(l)] = -eyeMm[2];
        }
        traceLanes(tracer, rays, table.lanes);
        const int pixels = std::min(table.pixels, width - i0);
        sumPixels(rays, pixels, n, light.data());
        for (int p = 0; p < pixels; ++p)
          image.at(i0 + p, int(j)) =
              Vec3f(float(light[size_t(3 * p)] / n), float(light[size_t(3 * p + 1)] / n),
                    float(light[size_t(3 * p + 2)] / n));
      }
    }
  });
  return image;
}

}  // namespace

PhotoPixels photographBarrier(const PhysicalBarrier& display, const Image& front, const Image& rear,
                              const PhoneCamera& camera, int threads) {
  const BarrierTracer tracer(display, front, rear);
  return photograph(tracer, camera, threads);
}

PhotoPixels photographLenticular(const PhysicalLenticular& display, const Image& panel,
                                 const PhoneCamera& camera, int threads) {
  const LenticularTracer tracer(display, panel);
  return photograph(tracer, camera, threads);
}

Image eyeViewBarrier(const PhysicalBarrier& display, const Image& front, const Image& rear,
                     const std::array<double, 3>& eyeMm, int width, int height, int samplesPerPixel,
                     int threads) {
  const BarrierTracer tracer(display, front, rear);
  return eyeView(tracer, display.front, eyeMm, width, height, samplesPerPixel, threads);
}

Image eyeViewLenticular(const PhysicalLenticular& display, const Image& panel,
                        const std::array<double, 3>& eyeMm, int width, int height,
                        int samplesPerPixel, int threads) {
  const LenticularTracer tracer(display, panel);
  return eyeView(tracer, display.panel, eyeMm, width, height, samplesPerPixel, threads);
}

}  // namespace parallax::photomaker
