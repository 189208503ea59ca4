#include "parallax/scene/gaussians.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace parallax {

uint16_t toHalf(float value) {
  const uint32_t bits = std::bit_cast<uint32_t>(value);
  const uint16_t sign = uint16_t((bits >> 16) & 0x8000u);
  const float magnitude = std::abs(value);
  if (!(magnitude < 65520.0f)) return uint16_t(sign | 0x7bffu);  // clamped to 65504
  if (magnitude < 0x1p-14f) {
    // Subnormal halves are multiples of 2^-24: round the magnitude to one (nearest, ties to
    // even, as the float to integer conversion of nearbyint does).
    return uint16_t(sign | uint16_t(std::nearbyint(magnitude * 0x1p24f)));
  }
  // Normal: keep 10 of the float's 23 mantissa bits, rounding on the 13 dropped.
  const uint32_t m = std::bit_cast<uint32_t>(magnitude);
  const uint32_t rebiased = m - ((127u - 15u) << 23);
  const uint32_t dropped = rebiased & 0x1fffu;
  uint32_t half = rebiased >> 13;
  if (dropped > 0x1000u || (dropped == 0x1000u && (half & 1u))) ++half;  // may carry into 0x7c00
  return uint16_t(sign | std::min<uint32_t>(half, 0x7bffu));
}

void rotationRows(const Quatf& q, Vec3f rows[3]) {
  const float n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  const float w = q.w / n, x = q.x / n, y = q.y / n, z = q.z / n;
  rows[0] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)};
  rows[1] = {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)};
  rows[2] = {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)};
}

// The real spherical harmonics with the Condon-Shortley phase in Cartesian form, the constants
// those of 3DGS's rasteriser (sqrt((2l + 1) / 4 pi (l - |m|)! / (l + |m|)!) times the
// polynomials' own factors); shBasis' test checks each against std::sph_legendre.
void shBasis(int degree, const Vec3f& d, float* basis) {
  constexpr float kC0 = 0.28209479177387814f, kC1 = 0.4886025119029199f;
  basis[0] = kC0;
  if (degree < 1) return;
  const float x = d.x, y = d.y, z = d.z;
  basis[1] = -kC1 * y;
  basis[2] = kC1 * z;
  basis[3] = -kC1 * x;
  if (degree < 2) return;
  const float xx = x * x, yy = y * y, zz = z * z;
  basis[4] = 1.0925484305920792f * x * y;
  basis[5] = -1.0925484305920792f * y * z;
  basis[6] = 0.31539156525252005f * (2 * zz - xx - yy);
  basis[7] = -1.0925484305920792f * x * z;
  basis[8] = 0.5462742152960396f * (xx - yy);
  if (degree < 3) return;
  basis[9] = -0.5900435899266435f * y * (3 * xx - yy);
  basis[10] = 2.890611442640554f * x * y * z;
  basis[11] = -0.4570457994644658f * y * (4 * zz - xx - yy);
  basis[12] = 0.3731763325901154f * z * (2 * zz - 3 * xx - 3 * yy);
  basis[13] = -0.4570457994644658f * x * (4 * zz - xx - yy);
  basis[14] = 1.445305721320277f * z * (xx - yy);
  basis[15] = -0.5900435899266435f * x * (xx - 3 * yy);
}

Vec3f shColour(const Vec3f* coefficients, int degree, const Vec3f& direction) {
  float basis[shCoefficientCount(kMaxShDegree)];
  shBasis(degree, direction, basis);
  Vec3f colour(0.5f);  // the offset 3DGS adds, so that zero coefficients are mid grey
  for (int k = 0; k < shCoefficientCount(degree); ++k) colour += coefficients[k] * basis[k];
  return {std::max(colour.x, 0.0f), std::max(colour.y, 0.0f), std::max(colour.z, 0.0f)};
}

float RayResponse::alpha(float opacity) const {
  return std::min(kMaxSplatAlpha, opacity * std::exp(-0.5f * distanceSquared));
}

namespace {

// W = S^-1 R^T: row j is column j of R (row j of R^T) over scale j.
void whitening(const Vec3f& scale, const Quatf& rotation, Vec3f whiten[3]) {
  Vec3f rows[3];
  rotationRows(rotation, rows);
  for (int j = 0; j < 3; ++j)
    whiten[j] = Vec3f{rows[0][j], rows[1][j], rows[2][j]} * (1.0f / scale[j]);
}

}  // namespace

GaussianFrame gaussianFrame(const GaussianCloud& cloud, size_t g, const Transform& worldFromFile) {
  Vec3f local[3];
  whitening(cloud.scales[g], cloud.rotations[g], local);
  const Mat4& fileFromWorld = worldFromFile.inverseMatrix();
  GaussianFrame frame;
  frame.centre = worldFromFile.point(cloud.centres[g]);
  for (int j = 0; j < 3; ++j)
    for (int column = 0; column < 3; ++column)
      frame.whiten[j][column] = local[j].x * fileFromWorld.m[0][column] +
                                local[j].y * fileFromWorld.m[1][column] +
                                local[j].z * fileFromWorld.m[2][column];
  return frame;
}

RayResponse gaussianRayResponse(const Vec3f& centre, const Vec3f& scale, const Quatf& rotation,
                                const Vec3f& origin, const Vec3f& direction) {
  GaussianFrame frame;
  frame.centre = centre;
  whitening(scale, rotation, frame.whiten);
  return gaussianRayResponse(frame, origin, direction);
}

RayResponse gaussianRayResponse(const GaussianFrame& gaussian, const Vec3f& origin,
                                const Vec3f& direction) {
  const Vec3f o = origin - gaussian.centre;
  const Vec3f local{dot(gaussian.whiten[0], o), dot(gaussian.whiten[1], o),
                    dot(gaussian.whiten[2], o)};
  const Vec3f towards{dot(gaussian.whiten[0], direction), dot(gaussian.whiten[1], direction),
                      dot(gaussian.whiten[2], direction)};
  RayResponse response;
  response.t = -dot(local, towards) / dot(towards, towards);
  // The closest point itself, not |o'|^2 - (o'.d')^2 / |d'|^2: no cancellation far away.
  const Vec3f closest = local + towards * response.t;
  response.distanceSquared = dot(closest, closest);
  return response;
}

float boundingRadius(float opacity, float alphaMin) {
  if (!(opacity > alphaMin)) return 0.0f;
  return std::sqrt(2.0f * std::log(opacity / alphaMin));
}

namespace {

// The bits of v (below 2^21) spread to every third bit.
uint64_t spreadBits(uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffull;
  v = (v | v << 16) & 0x1f0000ff0000ffull;
  v = (v | v << 8) & 0x100f00f00f00f00full;
  v = (v | v << 4) & 0x10c30c30c30c30c3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

}  // namespace

void sortForLocality(GaussianCloud& cloud) {
  const size_t n = cloud.size();
  if (n < 2) return;
  Bounds3f bounds;
  for (const Vec3f& c : cloud.centres) bounds.extend(c);
  const Vec3f extent = bounds.diagonal();
  std::vector<std::pair<uint64_t, uint32_t>> keys(n);
  for (size_t g = 0; g < n; ++g) {
    uint64_t code = 0;
    for (int a = 0; a < 3; ++a) {
      const float unit = extent[a] > 0 ? (cloud.centres[g][a] - bounds.lo[a]) / extent[a] : 0.0f;
      code |= spreadBits(uint64_t(std::clamp(unit, 0.0f, 1.0f) * 2097151.0f)) << a;
    }
    keys[g] = {code, uint32_t(g)};
  }
  std::sort(keys.begin(), keys.end());
  // In place, cycle by cycle (position i takes the Gaussian keys[i] names), so that sorting a
  // capture needs no second copy of it (docs/splats.md, "Memory").
  const size_t stride = size_t(shCoefficientCount(cloud.shDegree));
  const size_t halves = 3 * stride;
  std::vector<bool> placed(n, false);
  std::vector<uint16_t> heldSh(halves);
  for (size_t start = 0; start < n; ++start) {
    if (placed[start] || keys[start].second == start) continue;
    const Vec3f heldCentre = cloud.centres[start], heldScale = cloud.scales[start];
    const Quatf heldRotation = cloud.rotations[start];
    const float heldOpacity = cloud.opacities[start];
    std::copy_n(cloud.sh.halves(start * stride), halves, heldSh.begin());
    size_t at = start;
    for (;;) {
      placed[at] = true;
      const size_t from = keys[at].second;
      if (from == start) break;
      cloud.centres[at] = cloud.centres[from];
      cloud.scales[at] = cloud.scales[from];
      cloud.rotations[at] = cloud.rotations[from];
      cloud.opacities[at] = cloud.opacities[from];
      std::copy_n(cloud.sh.halves(from * stride), halves, cloud.sh.halves(at * stride));
      at = from;
    }
    cloud.centres[at] = heldCentre;
    cloud.scales[at] = heldScale;
    cloud.rotations[at] = heldRotation;
    cloud.opacities[at] = heldOpacity;
    std::copy(heldSh.begin(), heldSh.end(), cloud.sh.halves(at * stride));
  }
}

Bounds3f splatCentreBounds(const SplatSet& set) {
  Bounds3f bounds;
  for (const Vec3f& centre : set.cloud.centres) bounds.extend(set.worldFromFile.point(centre));
  return bounds;
}

Bounds3f splatFramingBounds(const SplatSet& set) {
  constexpr size_t kAllBelow = 1000;
  const size_t n = set.cloud.size();
  if (n < kAllBelow) return splatCentreBounds(set);
  std::vector<Vec3f> centres(n);
  for (size_t g = 0; g < n; ++g) centres[g] = set.worldFromFile.point(set.cloud.centres[g]);
  std::vector<float> values(n);
  Vec3f median;
  for (int a = 0; a < 3; ++a) {
    for (size_t g = 0; g < n; ++g) values[g] = centres[g][a];
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(n / 2), values.end());
    median[a] = values[n / 2];
  }
  for (size_t g = 0; g < n; ++g) values[g] = length(centres[g] - median);
  const size_t at = n * 8 / 10;
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(at), values.end());
  const float reach = 1.5f * values[at];
  Bounds3f bounds;
  for (const Vec3f& centre : centres)
    if (length(centre - median) <= reach) bounds.extend(centre);
  return bounds;
}

}  // namespace parallax
