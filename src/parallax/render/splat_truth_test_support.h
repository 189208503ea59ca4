// Two independent truths the splat renderer is tested against (docs/splats.md, "Truth"):
// - bruteForceSplatPixel: every Gaussian's response along the pixel's ray evaluated, the ones
//   seen sorted by depth and blended, with no BVH and no k-buffer;
// - rasteriseSplats: the reference 3DGS rasteriser's algorithm (Kerbl et al. 2023, its CUDA
//   forward pass), written here from the paper: each Gaussian projected to a 2-D Gaussian by the
//   local affine approximation of the perspective (EWA splatting, Zwicker et al. 2002) with the
//   0.3 px^2 low-pass, sorted by its centre's depth, cut at 3 deviations, its colour evaluated
//   once along the line from the eye to its centre, and alpha-blended front to back.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "parallax/image/image.h"
#include "parallax/scene/gaussians.h"

namespace parallax::splat_truth {

// The rotation matrix of a quaternion (w, x, y, z), unnormalised, in rows: written here again,
// not shared with the renderer.
inline void rotation(const Quatf& q, double r[3][3]) {
  const double n =
      std::sqrt(double(q.w) * q.w + double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z);
  const double w = q.w / n, x = q.x / n, y = q.y / n, z = q.z / n;
  const double rows[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                             {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                             {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[i][j] = rows[i][j];
}

// Sigma = R S^2 R^T of Gaussian g (a set placed by the identity).
inline void covariance(const GaussianCloud& cloud, size_t g, double sigma[3][3]) {
  double r[3][3];
  rotation(cloud.rotations[g], r);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      sigma[i][j] = 0;
      for (int k = 0; k < 3; ++k) {
        const double s = cloud.scales[g][k];
        sigma[i][j] += r[i][k] * s * s * r[j][k];
      }
    }
}

// The display-value colour of Gaussian g along the unit direction d (3DGS's basis constants).
inline Vec3f colourAlong(const GaussianCloud& cloud, size_t g, const Vec3f& d) {
  const size_t count = size_t(shCoefficientCount(cloud.shDegree));
  const auto c = [&](size_t k) { return cloud.sh[g * count + k]; };
  const double x = d.x, y = d.y, z = d.z;
  double basis[16] = {0.28209479177387814};
  if (cloud.shDegree >= 1) {
    basis[1] = -0.4886025119029199 * y, basis[2] = 0.4886025119029199 * z;
    basis[3] = -0.4886025119029199 * x;
  }
  if (cloud.shDegree >= 2) {
    basis[4] = 1.0925484305920792 * x * y, basis[5] = -1.0925484305920792 * y * z;
    basis[6] = 0.31539156525252005 * (2 * z * z - x * x - y * y);
    basis[7] = -1.0925484305920792 * x * z, basis[8] = 0.5462742152960396 * (x * x - y * y);
  }
  if (cloud.shDegree >= 3) {
    basis[9] = -0.5900435899266435 * y * (3 * x * x - y * y);
    basis[10] = 2.890611442640554 * x * y * z;
    basis[11] = -0.4570457994644658 * y * (4 * z * z - x * x - y * y);
    basis[12] = 0.3731763325901154 * z * (2 * z * z - 3 * x * x - 3 * y * y);
    basis[13] = -0.4570457994644658 * x * (4 * z * z - x * x - y * y);
    basis[14] = 1.445305721320277 * z * (x * x - y * y);
    basis[15] = -0.5900435899266435 * x * (x * x - 3 * y * y);
  }
  Vec3f out;
  for (int ch = 0; ch < 3; ++ch) {
    double v = 0.5;
    for (size_t k = 0; k < count; ++k) v += double(c(k)[ch]) * basis[k];
    out[ch] = float(std::max(v, 0.0));
  }
  return out;
}

// Front-to-back blending of (alpha, colour) in order, 3DGS's way, over `background` (display
// values): returns the display value.
struct Blender {
  Vec3f colour{0.0f};
  double transmittance = 1;
  bool done = false;
  void add(double alpha, const Vec3f& c) {
    if (done || alpha < 1.0 / 255.0) return;
    alpha = std::min(alpha, 0.99);
    const double next = transmittance * (1 - alpha);
    if (next < 1e-4) {
      done = true;
      return;
    }
    colour += c * float(alpha * transmittance);
    transmittance = next;
  }
  Vec3f over(const Vec3f& background) const {
    return colour + background * float(done ? 0.0 : transmittance);
  }
};

// Brute force along one ray (world = file frame: the scene's sets placed by the identity):
// returns the display value over `background` (display values).
inline Vec3f bruteForceSplatPixel(const GaussianCloud& cloud, const Vec3f& origin,
                                  const Vec3f& direction, const Vec3f& background) {
  struct Seen {
    double t, alpha;
    size_t g;
  };
  std::vector<Seen> seen;
  for (size_t g = 0; g < cloud.size(); ++g) {
    double sigma[3][3];
    covariance(cloud, g, sigma);
    // Sigma^-1 by cofactors; the response along the ray peaks where the quadratic form
    // q(t) = (o + t d - mu)^T Sigma^-1 (o + t d - mu) is least.
    const double a = sigma[0][0], b = sigma[0][1], c = sigma[0][2], d = sigma[1][1],
                 e = sigma[1][2], f = sigma[2][2];
    const double det = a * (d * f - e * e) - b * (b * f - c * e) + c * (b * e - c * d);
    const double inv[3][3] = {
        {(d * f - e * e) / det, (c * e - b * f) / det, (b * e - c * d) / det},
        {(c * e - b * f) / det, (a * f - c * c) / det, (b * c - a * e) / det},
        {(b * e - c * d) / det, (b * c - a * e) / det, (a * d - b * b) / det}};
    const double o[3] = {double(origin.x) - cloud.centres[g].x,
                         double(origin.y) - cloud.centres[g].y,
                         double(origin.z) - cloud.centres[g].z};
    const double dir[3] = {direction.x, direction.y, direction.z};
    double dd = 0, od = 0, oo = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        dd += dir[i] * inv[i][j] * dir[j];
        od += o[i] * inv[i][j] * dir[j];
        oo += o[i] * inv[i][j] * o[j];
      }
    const double t = -od / dd;
    const double q = std::max(0.0, oo - od * od / dd);
    const double alpha = std::min(0.99, double(cloud.opacities[g]) * std::exp(-0.5 * q));
    if (t >= 0 && alpha >= 1.0 / 255.0) seen.push_back({t, alpha, g});
  }
  std::sort(seen.begin(), seen.end(),
            [](const Seen& x, const Seen& y) { return x.t < y.t || (x.t == y.t && x.g < y.g); });
  Blender blend;
  const Vec3f unit = normalize(direction);
  for (const Seen& s : seen) blend.add(s.alpha, colourAlong(cloud, s.g, unit));
  return blend.over(background);
}

// A pinhole view for the rasteriser: the same as PinholeCamera's (square pixels, vertical field
// of view, pixel centres at half-integers).
struct View {
  Vec3f eye, lookAt, up;
  float fovDegrees = 40;
  int width = 0, height = 0;
};

// The 3DGS rasteriser's picture of `cloud` over `background` (display values), in linear
// values. `lowPass`: the variance in px^2 added to every projected Gaussian (3DGS: 0.3; 0 leaves
// the projection alone, to tell its other approximations from the filter).
inline Image rasteriseSplats(const GaussianCloud& cloud, const View& view, const Vec3f& background,
                             double lowPass = 0.3) {
  const Vec3f forward = normalize(view.lookAt - view.eye);
  const Vec3f right = normalize(cross(forward, view.up));
  const Vec3f down = cross(forward, right);  // image y grows downwards
  const double tanHalf = std::tan(double(view.fovDegrees) * kPi / 360.0);
  const double focal = view.height / (2 * tanHalf);
  const double tanHalfX = tanHalf * view.width / view.height;
  struct Splat {
    double depth, x, y, conic[3], opacity;
    int radius;
    Vec3f colour;
  };
  std::vector<Splat> splats;
  for (size_t g = 0; g < cloud.size(); ++g) {
    const Vec3f p = cloud.centres[g] - view.eye;
    const double cx = dot(p, right), cy = dot(p, down), cz = dot(p, forward);
    if (cz <= 0.2) continue;  // 3DGS's near cull
    // The Jacobian of the projection at the centre, its x/z and y/z clamped to 1.3 times the
    // view's extent as 3DGS clamps them.
    const double lx = 1.3 * tanHalfX, ly = 1.3 * tanHalf;
    const double tx = std::clamp(cx / cz, -lx, lx) * cz, ty = std::clamp(cy / cz, -ly, ly) * cz;
    const double j[2][3] = {{focal / cz, 0, -focal * tx / (cz * cz)},
                            {0, focal / cz, -focal * ty / (cz * cz)}};
    const double w[3][3] = {
        {right.x, right.y, right.z}, {down.x, down.y, down.z}, {forward.x, forward.y, forward.z}};
    double sigma[3][3];
    covariance(cloud, g, sigma);
    double t[2][3] = {};  // T = J W
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 3; ++b)
        for (int k = 0; k < 3; ++k) t[a][b] += j[a][k] * w[k][b];
    double cov[2][2] = {};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) cov[a][b] += t[a][k] * sigma[k][l] * t[b][l];
    cov[0][0] += lowPass, cov[1][1] += lowPass;  // the low-pass filter
    const double det = cov[0][0] * cov[1][1] - cov[0][1] * cov[0][1];
    if (det == 0) continue;
    const double mid = 0.5 * (cov[0][0] + cov[1][1]);
    const double lambda = mid + std::sqrt(std::max(0.1, mid * mid - det));
    Splat s;
    s.radius = int(std::ceil(3 * std::sqrt(lambda)));
    s.conic[0] = cov[1][1] / det, s.conic[1] = -cov[0][1] / det, s.conic[2] = cov[0][0] / det;
    s.x = focal * cx / cz + view.width / 2.0;
    s.y = focal * cy / cz + view.height / 2.0;
    s.depth = cz;
    s.opacity = cloud.opacities[g];
    s.colour = colourAlong(cloud, g, normalize(p));
    splats.push_back(s);
  }
  std::stable_sort(splats.begin(), splats.end(),
                   [](const Splat& a, const Splat& b) { return a.depth < b.depth; });
  Image image(view.width, view.height);
  for (int py = 0; py < view.height; ++py)
    for (int px = 0; px < view.width; ++px) {
      Blender blend;
      const double x = px + 0.5, y = py + 0.5;
      for (const Splat& s : splats) {
        if (blend.done) break;
        if (std::abs(x - s.x) > s.radius || std::abs(y - s.y) > s.radius) continue;
        const double dx = s.x - x, dy = s.y - y;
        const double power =
            -0.5 * (s.conic[0] * dx * dx + s.conic[2] * dy * dy) - s.conic[1] * dx * dy;
        if (power > 0) continue;
        blend.add(s.opacity * std::exp(power), s.colour);
      }
      const Vec3f v = blend.over(background);
      image.at(px, py) = {srgbToLinear(v.x), srgbToLinear(v.y), srgbToLinear(v.z)};
    }
  return image;
}

}  // namespace parallax::splat_truth
