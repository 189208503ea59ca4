// Gaussian splats (3DGS: Kerbl et al., SIGGRAPH 2023) as scene geometry, and the two things a
// ray tracer asks of one (docs/splats.md, "The model"): the colour it shows along a ray's own
// direction, from its spherical harmonics, and its response along the ray, in closed form
// (3DGRT: Moenne-Loccoz et al., SIGGRAPH Asia 2024).
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "parallax/core/math.h"
#include "parallax/core/transform.h"

namespace parallax {

// Spherical harmonics up to degree 3: 1, 4, 9 or 16 coefficients a colour channel.
inline constexpr int kMaxShDegree = 3;
constexpr int shCoefficientCount(int degree) {
  return (degree + 1) * (degree + 1);
}

// A rotation as a unit quaternion (w, x, y, z), the order 3DGS files keep it in.
struct Quatf {
  float w = 1, x = 0, y = 0, z = 0;
};

// The rotation matrix of a quaternion, normalised first (files keep it unnormalised): rows.
void rotationRows(const Quatf& q, Vec3f rows[3]);

// IEEE 754 half floats (binary16), as a capture's coefficients are kept (docs/splats.md,
// "Memory"): toHalf rounds to nearest, ties to even, and clamps beyond the largest finite half
// (65504; a non-finite value never reaches it, the readers refuse those); fromHalf is exact.
uint16_t toHalf(float value);
// Branch-free (a select), so that loops of it vectorise: a normal half's bits moved into a
// float's places with the exponent rebiased (15 to 127), a subnormal half (below 2^-14) its
// integer mantissa times 2^-24. No step passes through a subnormal float, whose value would
// depend on the thread's flush-to-zero mode (TBB's workers and the main thread differ).
inline float fromHalf(uint16_t half) {
  const uint32_t magnitude = half & 0x7fffu;
  const float normal = std::bit_cast<float>((magnitude << 13) + ((127u - 15u) << 23));
  const float subnormal = float(magnitude) * 0x1p-24f;
  const float value = magnitude < 0x400u ? subnormal : normal;
  return std::bit_cast<float>(std::bit_cast<uint32_t>(value) | (uint32_t(half & 0x8000u) << 16));
}

// RGB triples in half floats: 6 bytes where floats take 12. A Gaussian's spherical-harmonic
// coefficients are most of its memory (48 of them at degree 3), and their relative precision of
// 2^-11 is a fifteenth of an 8-bit step in the colour they make.
class HalfRgbArray {
 public:
  HalfRgbArray() = default;
  HalfRgbArray(std::initializer_list<Vec3f> values) {
    for (const Vec3f& v : values) push_back(v);
  }
  size_t size() const { return halves_.size() / 3; }
  bool empty() const { return halves_.empty(); }
  void resize(size_t count) { halves_.resize(3 * count); }
  void push_back(const Vec3f& v) {
    halves_.push_back(toHalf(v.x)), halves_.push_back(toHalf(v.y));
    halves_.push_back(toHalf(v.z));
  }
  // A copy, const so that `sh[i] = v` (which would change nothing) does not compile: set() writes.
  const Vec3f operator[](size_t i) const {
    return {fromHalf(halves_[3 * i]), fromHalf(halves_[3 * i + 1]), fromHalf(halves_[3 * i + 2])};
  }
  void set(size_t i, const Vec3f& v) {
    halves_[3 * i] = toHalf(v.x), halves_[3 * i + 1] = toHalf(v.y);
    halves_[3 * i + 2] = toHalf(v.z);
  }
  // Triple i's halves (R, G, B, then triple i + 1's).
  const uint16_t* halves(size_t i) const { return halves_.data() + 3 * i; }
  uint16_t* halves(size_t i) { return halves_.data() + 3 * i; }

 private:
  std::vector<uint16_t> halves_;
};

// Gaussians in world space, the values a 3DGS file's encodings stand for (its logs exponentiated,
// its logits through the sigmoid).
struct GaussianCloud {
  int shDegree = 0;
  std::vector<Vec3f> centres;
  std::vector<Vec3f> scales;     // standard deviations along the local axes, above 0
  std::vector<Quatf> rotations;  // local axes to world
  std::vector<float> opacities;  // the peak's alpha, in (0, 1]
  // shCoefficientCount(shDegree) RGB coefficients a Gaussian, coefficient-major: Gaussian g's
  // coefficient k (k = l (l + 1) + m, m from -l to l) is sh[g * count + k]; in half floats.
  HalfRgbArray sh;
  size_t size() const { return centres.size(); }
};

// Gaussian splats a file placed in the scene (docs/splats.md): the cloud as its file holds it,
// in the file's frame, and the affine map from that frame to the world. A Gaussian stays a
// Gaussian under any affine map (its whitening map composes with the inverse), and its colour is
// looked up along the ray's direction taken back into the file's frame, so nothing is resampled.
struct SplatSet {
  std::string name;  // the file
  GaussianCloud cloud;
  Transform worldFromFile;
};

// Puts the cloud's Gaussians in the order of their centres along a Morton (Z-order) curve, so
// that Gaussians near in space are near in memory: a ray meets Gaussians that are near each
// other, and a file's own order (a capture's: as training left it) scatters them, so that every
// frame and colour a ray reads missed the caches (docs/splats.md, "Speed"). The same cloud
// always gets the same order (ties by the old index).
void sortForLocality(GaussianCloud& cloud);

// The world-space bounds of the set's centres (what Scene::bounds counts).
Bounds3f splatCentreBounds(const SplatSet& set);
// The bounds a framing fits (docs/splats.md, "Framing"): the centres within 1.5 times the
// distance from their median (per axis) that holds 80 % of them, so that what a capture keeps
// far out (its distant background, its floaters) does not shrink the subject, while a compact
// object keeps all of itself (a uniform ball's 80 % radius is 0.93 of its radius); every centre
// for sets under 1000.
Bounds3f splatFramingBounds(const SplatSet& set);

// A Gaussian as a ray tracer reads it: its centre and the whitening map to its own frame,
// x' = W (x - centre) with W = S^-1 R^T (world axes to unit-deviation local axes), as rows.
struct GaussianFrame {
  Vec3f centre;
  Vec3f whiten[3];
};
// Gaussian g of the cloud in the world: W' = W L^-1 and centre' = worldFromFile(centre), for the
// linear part L of worldFromFile.
GaussianFrame gaussianFrame(const GaussianCloud& cloud, size_t g, const Transform& worldFromFile);

// The basis 3DGS's colours are written in: the real spherical harmonics with the Condon-Shortley
// phase, Y_k(d) for k < shCoefficientCount(degree), at the unit direction d.
void shBasis(int degree, const Vec3f& d, float* basis);

// The colour a Gaussian shows along the unit direction `direction` (from the eye toward it):
// sum_k c_k Y_k(direction) + 0.5 per channel, clamped below at 0, as 3DGS's rasteriser
// computes it. Display values: blended as they are, not as light.
Vec3f shColour(const Vec3f* coefficients, int degree, const Vec3f& direction);

// A Gaussian's response along a ray o + t d. In the Gaussian's own frame, x' = S^-1 R^T (x - mu),
// the ray is o' + t d' and the response exp(-|x'|^2 / 2) peaks where |x'| is least: at
// t = -(o' . d') / |d'|^2, with |x'|^2 = |o'|^2 - (o' . d')^2 / |d'|^2 there (the squared
// Mahalanobis distance of the ray from the centre).
struct RayResponse {
  float t = 0;
  float distanceSquared = 0;
  // opacity * exp(-distanceSquared / 2), capped as 3DGS caps it (kMaxSplatAlpha).
  float alpha(float opacity) const;
};
RayResponse gaussianRayResponse(const Vec3f& centre, const Vec3f& scale, const Quatf& rotation,
                                const Vec3f& origin, const Vec3f& direction);
// The same for a Gaussian given by its frame.
RayResponse gaussianRayResponse(const GaussianFrame& gaussian, const Vec3f& origin,
                                const Vec3f& direction);

// 3DGS's blending: a Gaussian whose alpha is below 1/255 is skipped, alpha is capped at 0.99, and
// a ray stops once its transmittance falls below 1e-4.
inline constexpr float kMinSplatAlpha = 1.0f / 255.0f;
inline constexpr float kMaxSplatAlpha = 0.99f;
inline constexpr float kMinTransmittance = 1e-4f;

// How far, in standard deviations, a Gaussian of `opacity` reaches alpha `alphaMin`: the
// ellipsoid that bounds every ray it can be seen along, sqrt(2 ln(opacity / alphaMin)); 0 when
// it never reaches alphaMin.
float boundingRadius(float opacity, float alphaMin = kMinSplatAlpha);

}  // namespace parallax
