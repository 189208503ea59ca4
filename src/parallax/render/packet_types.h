// Structure-of-arrays data for one packet of sixteen rays, laid out so that per-lane loops
// compile to SIMD instructions (16 floats = one AVX-512 register).
#pragma once

#include <cstdint>

#include "parallax/core/math.h"

namespace parallax {

struct alignas(64) Color16 {
  float r[16], g[16], b[16];

  void fill(float v) {
    for (int i = 0; i < 16; ++i) r[i] = g[i] = b[i] = v;
  }
  Vec3f at(int lane) const { return {r[lane], g[lane], b[lane]}; }
  void set(int lane, const Vec3f& c) { r[lane] = c.x, g[lane] = c.y, b[lane] = c.z; }
};

// The shading inputs of sixteen hits. Lanes with `shade` = 0 get no direct light.
struct alignas(64) SurfacePacket16 {
  float px[16], py[16], pz[16];  // hit position
  float gx[16], gy[16], gz[16];  // unit geometric normal, on the side the ray came from
  float nx[16], ny[16], nz[16];  // unit shading normal, same side
  Color16 diffuse;               // albedo times (1 - mirror)
  Color16 mirror;
  int32_t hit[16];    // the ray hit something
  int32_t shade[16];  // diffuse reflectance is non-zero
};

// Sixteen light samples: the unoccluded irradiance each delivers, and its shadow segment from
// the shading point (toLight is unnormalised, the light point at t = 1).
struct alignas(64) LightPacket16 {
  float tx[16], ty[16], tz[16];
  float tMax[16];
  Color16 irradiance;
  int32_t valid[16];
};

}  // namespace parallax
