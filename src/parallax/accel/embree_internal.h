// Internal to accel: the Embree back end's shared pieces, for the two files that talk to Embree
// (accelerator.cpp: meshes and spheres, the device; splat_trace.cpp: Gaussian splats). Nothing
// outside this module includes it.
#pragma once

#if PARALLAX_EMBREE_MAJOR == 4
#include <embree4/rtcore.h>
#elif PARALLAX_EMBREE_MAJOR == 3
#include <embree3/rtcore.h>
#else
#error "PARALLAX_EMBREE_MAJOR must be 3 or 4 (src/parallax/accel/CMakeLists.txt)"
#endif

#include <cmath>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "parallax/accel/splat_hits.h"
#include "parallax/core/lane_kernel.h"
#include "parallax/core/ray.h"
#include "parallax/scene/gaussians.h"
#include "parallax/scene/scene.h"

namespace parallax {

inline void fillRay(const Ray& ray, RTCRay& out) {
  out.org_x = ray.origin.x, out.org_y = ray.origin.y, out.org_z = ray.origin.z;
  out.dir_x = ray.direction.x, out.dir_y = ray.direction.y, out.dir_z = ray.direction.z;
  out.tnear = ray.tMin, out.tfar = ray.tMax;
  out.time = 0.0f;
  out.mask = 0xffffffffu;
  out.id = 0;
  out.flags = 0;
}

// The one seam between our rays and Embree's packet kernels. Embree 3 checks every ray it
// traces (Debian's build asserts `ray.valid()`: finite origin and direction below FLT_LARGE,
// tnear and tfar not NaN), and on CPUs without native 16-wide kernels (AVX2, SSE) it serves
// rtcIntersect16 / rtcOccluded16 through a fallback that ignores the valid mask and traces
// every lane whose tnear <= tfar. So every lane that is not to be traced gets a harmless ray
// that no kernel traces (origin 0, direction +z, tnear 1 > tfar 0), and an active lane whose
// ray Embree would reject (non-finite or huge numbers, an empty or negative interval) is
// turned off and reads as a miss: it cannot hit anything meaningful. The same guard serves
// Embree 4, whose packet and untraceable-lane tests pass the same way on every ISA.
constexpr float kLargestCoordinate = 1e18f;  // below Embree's FLT_LARGE (1.844e18)

inline bool traceable(float ox, float oy, float oz, float dx, float dy, float dz, float tMin,
                      float tMax) {
  auto small = [](float value) { return std::abs(value) <= kLargestCoordinate; };  // NaN: false
  // Bitwise & and |: every test is cheap, and without short-circuit branches the lane loops
  // that call this vectorise.
  return small(ox) & small(oy) & small(oz) & small(dx) & small(dy) & small(dz) &
         ((dx != 0.0f) | (dy != 0.0f) | (dz != 0.0f)) & (tMin >= 0.0f) & (tMin <= tMax);
}

inline bool traceable(const Ray& ray) {
  return traceable(ray.origin.x, ray.origin.y, ray.origin.z, ray.direction.x, ray.direction.y,
                   ray.direction.z, ray.tMin, ray.tMax);
}

inline void disableLane(RTCRay16& ray, int lane) {
  ray.org_x[lane] = 0.0f, ray.org_y[lane] = 0.0f, ray.org_z[lane] = 0.0f;
  ray.dir_x[lane] = 0.0f, ray.dir_y[lane] = 0.0f, ray.dir_z[lane] = 1.0f;
  ray.tnear[lane] = 1.0f, ray.tfar[lane] = 0.0f;
}

// Makes `ray` safe for rtcIntersect16 / rtcOccluded16 under any ISA: clears `valid` for lanes
// Embree cannot trace and disarms every lane `valid` leaves out. Returns the active count.
PARALLAX_LANE_KERNEL static int guardPacket(RTCRay16& ray, int valid[16]) {
  // The test lane by lane without branches (it vectorises), then the rare disarming.
  int count = 0;
  for (int lane = 0; lane < 16; ++lane) {
    const bool trace = (valid[lane] != 0) &
                       traceable(ray.org_x[lane], ray.org_y[lane], ray.org_z[lane], ray.dir_x[lane],
                                 ray.dir_y[lane], ray.dir_z[lane], ray.tnear[lane], ray.tfar[lane]);
    valid[lane] = trace ? -1 : 0;
    count += int(trace);
  }
  if (count < 16)
    for (int lane = 0; lane < 16; ++lane)
      if (valid[lane] == 0) disableLane(ray, lane);
  return count;
}

PARALLAX_LANE_KERNEL static void fillRays(const RayPacket16& rays, RTCRay16& out) {
  for (int lane = 0; lane < 16; ++lane) {
    out.org_x[lane] = rays.ox[lane], out.org_y[lane] = rays.oy[lane];
    out.org_z[lane] = rays.oz[lane];
    out.dir_x[lane] = rays.dx[lane], out.dir_y[lane] = rays.dy[lane];
    out.dir_z[lane] = rays.dz[lane];
    out.tnear[lane] = rays.tMin[lane], out.tfar[lane] = rays.tMax[lane];
    out.time[lane] = 0.0f;
    out.mask[lane] = 0xffffffffu;
    out.id[lane] = unsigned(lane);
    out.flags[lane] = 0;
  }
}

// The splats' own Embree scene (splat_trace.cpp): one user geometry whose primitives are the
// Gaussians of every set in scene order, each bounded by its ellipsoid at alpha kMinSplatAlpha.
struct SplatStore {
  RTCScene scene = nullptr;
  std::vector<GaussianFrame> frames;  // world space
  std::vector<float> opacities;
  // boundingRadius(opacity)^2: a ray farther than this (squared Mahalanobis distance) from the
  // centre sees alpha below kMinSplatAlpha, so no exponential is needed to reject it.
  std::vector<float> reachSquared;
};
// Builds the store for every splat set of `scene` on `device` (nothing when it has none).
void buildSplatStore(RTCDevice device, const Scene& scene, SplatStore& store);
// The same Gaussians placed anew (the sets' worldFromFile changed): frames and BVH again.
void rebuildSplatStore(const Scene& scene, SplatStore& store);
// Accelerator::nextSplats16 on the store (nothing when it holds no scene).
void walkSplats16(const SplatStore& store, const RayPacket16& rays, const SplatCursor after[16],
                  SplatHit* out, int capacity, int counts[16], uint64_t* evaluated);

}  // namespace parallax
