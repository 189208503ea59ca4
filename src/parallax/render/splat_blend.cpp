#include "parallax/render/splat_blend.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <optional>

#include "parallax/core/lane_kernel.h"
#include "parallax/image/image.h"

namespace parallax {

SplatColours::SplatColours(const Scene& scene) {
  for (const SplatSet& splats : scene.splats) {
    Set set;
    set.first = count_;
    set.cloud = &splats.cloud;
    const Mat4& fileFromWorld = splats.worldFromFile.inverseMatrix();
    for (int r = 0; r < 3; ++r)
      set.fileFromWorld[r] = {fileFromWorld.m[r][0], fileFromWorld.m[r][1], fileFromWorld.m[r][2]};
    sets_.push_back(set);
    count_ += uint32_t(splats.cloud.size());
  }
}

size_t SplatColours::setOf(uint32_t gaussian) const {
  // The last set whose first index is at most `gaussian` (sets are few: a linear search).
  size_t s = sets_.size() - 1;
  while (sets_[s].first > gaussian) --s;
  return s;
}

PARALLAX_LANE_KERNEL Vec3f SplatColours::AlongRay::colour(uint32_t gaussian) {
  const size_t s = colours_.setOf(gaussian);
  const Set& set = colours_.sets_[s];
  if (s != set_) {
    const Vec3f local = normalize(Vec3f{dot(set.fileFromWorld[0], direction_),
                                        dot(set.fileFromWorld[1], direction_),
                                        dot(set.fileFromWorld[2], direction_)});
    float basis[shCoefficientCount(kMaxShDegree)];
    shBasis(set.cloud->shDegree, local, basis);
    count_ = shCoefficientCount(set.cloud->shDegree);
    for (int k = 0; k < count_; ++k)
      basis_[3 * k] = basis_[3 * k + 1] = basis_[3 * k + 2] = basis[k];
    set_ = s;
  }
  // shColour's sum with the basis already made, four coefficients (twelve floats, whole RGB
  // triples) at a time into independent sums: one short dependency chain, not sixteen.
  const uint16_t* c = set.cloud->sh.halves(size_t(gaussian - set.first) * size_t(count_));
  const int floats = 3 * count_;
  // The halves widened first, in one plain loop that vectorises (integer shifts, a compare, a
  // select: fromHalf's steps), then summed as floats (measured: 9.3 s for the 100 k capture's
  // 960x540 view, against 12.6 s widening inside the sums and 9.3 s with a table of all halves;
  // floats throughout took 7.0 s, at 96 more bytes a Gaussian).
  alignas(64) float wide[3 * shCoefficientCount(kMaxShDegree)];
  for (int i = 0; i < floats; ++i) {
    const int32_t half = c[i];
    const int32_t magnitude = half & 0x7fff;
    const float normal = std::bit_cast<float>((magnitude << 13) + ((127 - 15) << 23));
    const float subnormal = float(magnitude) * 0x1p-24f;
    const float value = magnitude < 0x400 ? subnormal : normal;
    wide[i] = std::bit_cast<float>(std::bit_cast<int32_t>(value) | ((half & 0x8000) << 16));
  }
  float sums[12] = {};
  int at = 0;
  for (; at + 12 <= floats; at += 12)
    for (int i = 0; i < 12; ++i) sums[i] += wide[at + i] * basis_[at + i];
  for (int i = 0; at + i < floats; ++i) sums[i] += wide[at + i] * basis_[at + i];
  Vec3f colour;
  for (int channel = 0; channel < 3; ++channel)
    colour[channel] = std::max(
        0.5f + sums[channel] + sums[channel + 3] + sums[channel + 6] + sums[channel + 9], 0.0f);
  return colour;
}

Vec3f SplatColours::colour(uint32_t gaussian, const Vec3f& direction) const {
  const Set& set = sets_[setOf(gaussian)];
  const Vec3f local =
      normalize(Vec3f{dot(set.fileFromWorld[0], direction), dot(set.fileFromWorld[1], direction),
                      dot(set.fileFromWorld[2], direction)});
  const int degree = set.cloud->shDegree;
  const size_t perGaussian = size_t(shCoefficientCount(degree));
  Vec3f coefficients[shCoefficientCount(kMaxShDegree)];
  for (size_t k = 0; k < perGaussian; ++k)
    coefficients[k] = set.cloud->sh[size_t(gaussian - set.first) * perGaussian + k];
  return shColour(coefficients, degree, local);
}

namespace {

// Blends a batch of hits (nearest first) into `blend`; false once the walk is over (the batch
// was not full, or the splats became opaque).
bool blendBatch(const SplatHit* batch, int count, SplatColours::AlongRay& along,
                SplatBlend& blend) {
  for (int i = 0; i < count; ++i) {
    // 3DGS's forward pass: a Gaussian that would leave less than kMinTransmittance ends the
    // walk unblended.
    const float next = blend.transmittance * (1.0f - batch[i].alpha);
    if (next < kMinTransmittance) {
      blend.opaque = true;
      return false;
    }
    blend.colour += along.colour(batch[i].gaussian) * (batch[i].alpha * blend.transmittance);
    blend.transmittance = next;
    ++blend.blended;
  }
  return count == kSplatBatch;
}

}  // namespace

SplatBlend blendSplats(const Accelerator& accelerator, const SplatColours& colours,
                       const Ray& ray) {
  SplatBlend blend;
  SplatColours::AlongRay along(colours, ray.direction);
  SplatHit batch[kSplatBatch];
  SplatCursor cursor;
  for (;;) {
    const int count = accelerator.nextSplats(ray, cursor, batch, kSplatBatch, &blend.evaluated);
    if (!blendBatch(batch, count, along, blend)) return blend;
    cursor = {batch[kSplatBatch - 1].t, batch[kSplatBatch - 1].gaussian, true};
  }
}

void blendSplats16(const Accelerator& accelerator, const SplatColours& colours,
                   const RayPacket16& rays, SplatBlend blends[16]) {
  RayPacket16 walking = rays;
  SplatCursor cursors[16];
  std::optional<SplatColours::AlongRay> along[16];
  int remaining = 0;
  for (int lane = 0; lane < 16; ++lane) {
    blends[lane] = SplatBlend{};
    if (!rays.active[lane]) continue;
    along[lane].emplace(colours, rays.ray(lane).direction);
    ++remaining;
  }
  SplatHit hits[16 * kSplatBatch];
  int counts[16];
  uint64_t evaluated = 0;
  while (remaining > 0) {
    accelerator.nextSplats16(walking, cursors, hits, kSplatBatch, counts, &evaluated);
    for (int lane = 0; lane < 16; ++lane) {
      if (!walking.active[lane]) continue;
      const SplatHit* batch = hits + lane * kSplatBatch;
      if (blendBatch(batch, counts[lane], *along[lane], blends[lane])) {
        cursors[lane] = {batch[kSplatBatch - 1].t, batch[kSplatBatch - 1].gaussian, true};
      } else {
        walking.deactivate(lane);
        --remaining;
      }
    }
  }
  // The packet's evaluations, charged to its first lane (the totals are what is reported).
  for (int lane = 0; lane < 16; ++lane)
    if (rays.active[lane]) {
      blends[lane].evaluated = evaluated;
      break;
    }
}

Vec3f overBehind(const SplatBlend& blend, const Vec3f& behind) {
  if (blend.blended == 0 && !blend.opaque) return behind;  // no splat in front
  Vec3f out;
  for (int c = 0; c < 3; ++c) {
    const float seen = blend.opaque ? 0.0f : linearToSrgb(std::max(behind[c], 0.0f));
    out[c] = srgbToLinear(blend.colour[c] + blend.transmittance * seen);
  }
  return out;
}

}  // namespace parallax
