#include "parallax/jobs/splat_making.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/core/output_path.h"
#include "parallax/core/parallel.h"
#include "parallax/core/random.h"
#include "parallax/image/image.h"
#include "parallax/importer/splat_ply.h"
#include "parallax/io/image_file.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/requests.h"
#include "parallax/render/surface.h"

namespace parallax::jobs {

namespace {

constexpr float kShC0 = 0.28209479177387814f;  // Y_0, so that colour = C0 f_dc + 0.5

// From the world (y up, the viewer on +z) to the file frame 3DGS uses: 180 degrees about X.
Vec3f toFileFrame(const Vec3f& v) {
  return {v.x, -v.y, -v.z};
}

// The unit quaternion (w, x, y, z) of the rotation whose columns are the orthonormal, right-
// handed a, b, c (Shepperd's method: the largest of the four squares first, for accuracy).
Quatf quaternionOfColumns(const Vec3f& a, const Vec3f& b, const Vec3f& c) {
  const float m00 = a.x, m10 = a.y, m20 = a.z, m01 = b.x, m11 = b.y, m21 = b.z, m02 = c.x,
              m12 = c.y, m22 = c.z;
  const float trace = m00 + m11 + m22;
  Quatf q;
  if (trace > 0) {
    const float s = 2 * std::sqrt(1 + trace);
    q = {s / 4, (m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s};
  } else if (m00 > m11 && m00 > m22) {
    const float s = 2 * std::sqrt(1 + m00 - m11 - m22);
    q = {(m21 - m12) / s, s / 4, (m01 + m10) / s, (m02 + m20) / s};
  } else if (m11 > m22) {
    const float s = 2 * std::sqrt(1 + m11 - m00 - m22);
    q = {(m02 - m20) / s, (m01 + m10) / s, s / 4, (m12 + m21) / s};
  } else {
    const float s = 2 * std::sqrt(1 + m22 - m00 - m11);
    q = {(m10 - m01) / s, (m02 + m20) / s, (m12 + m21) / s, s / 4};
  }
  return q;
}

// Any unit tangent of the unit normal n, turned by `angle` about it; returns (t, n x t).
void tangents(const Vec3f& n, float angle, Vec3f& t, Vec3f& b) {
  const Vec3f helper = std::abs(n.x) < 0.9f ? Vec3f(1, 0, 0) : Vec3f(0, 1, 0);
  const Vec3f t0 = normalize(cross(helper, n));
  const Vec3f b0 = cross(n, t0);
  t = t0 * std::cos(angle) + b0 * std::sin(angle);
  b = cross(n, t);
}

// One Gaussian appended in the file frame: world centre, world axes (t, b, n) with their
// deviations, opacity and coefficients.
struct CloudWriter {
  GaussianCloud& cloud;
  size_t perGaussian;
  void set(size_t g, const Vec3f& centre, const Vec3f& t, const Vec3f& b, const Vec3f& n,
           const Vec3f& deviations, float opacity, const Vec3f* coefficients) const {
    cloud.centres[g] = toFileFrame(centre);
    cloud.scales[g] = deviations;
    // The file frame's axes: the same rotation by 180 degrees about X, still right-handed.
    cloud.rotations[g] = quaternionOfColumns(toFileFrame(t), toFileFrame(b), toFileFrame(n));
    cloud.opacities[g] = opacity;
    for (size_t k = 0; k < perGaussian; ++k) cloud.sh.set(g * perGaussian + k, coefficients[k]);
  }
};

GaussianCloud sizedCloud(size_t count, int degree) {
  GaussianCloud cloud;
  cloud.shDegree = degree;
  cloud.centres.resize(count);
  cloud.scales.resize(count);
  cloud.rotations.resize(count);
  cloud.opacities.resize(count);
  cloud.sh.resize(count * size_t(shCoefficientCount(degree)));
  return cloud;
}

float normal01(Rng& rng) {  // Box-Muller
  const float u1 = std::max(rng.uniform(), 1e-7f), u2 = rng.uniform();
  return std::sqrt(-2 * std::log(u1)) * std::cos(2 * kPi * u2);
}

struct Triangle {
  uint32_t mesh = 0, index = 0;
  double cumulativeArea = 0;
};

}  // namespace

double splatCloudBytes(size_t count, int degree) {
  // Centre and scale, rotation, opacity, and the coefficients in half floats.
  return double(count) * (2 * sizeof(Vec3f) + sizeof(Quatf) + sizeof(float) +
                          3 * sizeof(uint16_t) * size_t(shCoefficientCount(degree)));
}

double splatPlyFileBytes(size_t count, int degree) {
  return 300.0 + double(count) * 4.0 * (17 + 3 * (shCoefficientCount(degree) - 1));
}

GaussianCloud surfaceGaussians(const Scene& scene, const SurfaceSplatOptions& options) {
  std::vector<Triangle> triangles;
  double area = 0;
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    const TriangleMesh& mesh = scene.meshes[m];
    for (uint32_t i = 0; i < mesh.triangleCount(); ++i) {
      const Vec3f& p0 = mesh.positions[mesh.indices[3 * i]];
      const Vec3f& p1 = mesh.positions[mesh.indices[3 * i + 1]];
      const Vec3f& p2 = mesh.positions[mesh.indices[3 * i + 2]];
      area += 0.5 * double(length(cross(p1 - p0, p2 - p0)));
      triangles.push_back({m, i, area});
    }
  }
  if (!(area > 0)) throw RequestError("scene", "has no triangles to put Gaussians on");
  if (options.count == 0) throw RequestError("count", "must be at least 1");
  GaussianCloud cloud = sizedCloud(options.count, 0);
  const CloudWriter writer{cloud, 1};
  const float spacing = float(std::sqrt(area / double(options.count)));
  const Vec3f toLight = normalize(Vec3f(-0.4f, 1.0f, 0.6f));  // the bare-mesh scene's key light
  parallelFor(int64_t(options.count), 0, 4096, [&](int64_t begin, int64_t end) {
    for (int64_t g = begin; g < end; ++g) {
      Rng rng(options.seed, uint64_t(g));
      // Stratified over the total area: Gaussian g's point lies in the g-th slice.
      const double at = (double(g) + double(rng.uniform())) / double(options.count) * area;
      const auto found = std::lower_bound(
          triangles.begin(), triangles.end(), at,
          [](const Triangle& t, double value) { return t.cumulativeArea < value; });
      const Triangle& tri = found == triangles.end() ? triangles.back() : *found;
      const TriangleMesh& mesh = scene.meshes[tri.mesh];
      const uint32_t i0 = mesh.indices[3 * tri.index], i1 = mesh.indices[3 * tri.index + 1],
                     i2 = mesh.indices[3 * tri.index + 2];
      const float su = std::sqrt(rng.uniform()), v = rng.uniform();
      const float w1 = su * (1 - v), w2 = su * v, w0 = 1 - w1 - w2;
      const Vec3f p = mesh.positions[i0] * w0 + mesh.positions[i1] * w1 + mesh.positions[i2] * w2;
      Vec3f n = normalize(
          cross(mesh.positions[i1] - mesh.positions[i0], mesh.positions[i2] - mesh.positions[i0]));
      if (!mesh.normals.empty()) {
        const Vec3f shading = mesh.normals[i0] * w0 + mesh.normals[i1] * w1 + mesh.normals[i2] * w2;
        if (dot(shading, n) < 0) n = -n;  // the normals say which side is outside
      }
      const Material& material = scene.materials[mesh.material];
      Vec3f albedo = material.diffuse;
      if (material.diffuseTexture >= 0) {
        Vec2f uv{0, 0};
        if (!mesh.uvs.empty())
          uv = {mesh.uvs[i0].x * w0 + mesh.uvs[i1].x * w1 + mesh.uvs[i2].x * w2,
                mesh.uvs[i0].y * w0 + mesh.uvs[i1].y * w1 + mesh.uvs[i2].y * w2};
        albedo =
            albedo * evaluateTexture(scene, scene.textures[size_t(material.diffuseTexture)], p, uv);
      }
      if (!mesh.colors.empty())
        albedo = albedo * (mesh.colors[i0] * w0 + mesh.colors[i1] * w1 + mesh.colors[i2] * w2);
      // The bare-mesh scene's light (scene_file.cpp): key 2.5 / pi cos, ambient 0.15.
      const float lit = 2.5f / kPi * std::max(0.0f, dot(n, toLight)) + 0.15f;
      Vec3f dc;
      for (int c = 0; c < 3; ++c)
        dc[c] = (linearToSrgb(std::min(1.0f, albedo[c] * lit)) - 0.5f) / kShC0;
      Vec3f t, b;
      tangents(n, 2 * kPi * rng.uniform(), t, b);
      const float across = options.spread * spacing;
      writer.set(size_t(g), p, t, b, n, {across, across, across * options.flatness},
                 options.opacity, &dc);
    }
  });
  return cloud;
}

GaussianCloud captureLikeGaussians(const CaptureLikeOptions& options) {
  if (options.count == 0) throw RequestError("count", "must be at least 1");
  constexpr int kDegree = 3;
  constexpr size_t kPerGaussian = size_t(shCoefficientCount(kDegree));
  GaussianCloud cloud = sizedCloud(options.count, kDegree);
  const CloudWriter writer{cloud, kPerGaussian};
  // The subject: seven spheres on a trefoil knot, each its own hue, over a ground disc.
  struct Ball {
    Vec3f centre;
    float radius;
    Vec3f colour;
  };
  std::vector<Ball> balls;
  for (int i = 0; i < 7; ++i) {
    const float s = 2 * kPi * float(i) / 7;
    const Vec3f knot{std::sin(s) + 2 * std::sin(2 * s), std::cos(s) - 2 * std::cos(2 * s),
                     -std::sin(3 * s)};
    const float hue = float(i) / 7;
    balls.push_back(
        {knot * 0.3f + Vec3f(0, 0.2f, 0),
         0.25f + 0.05f * float(i % 3),
         {0.5f + 0.4f * std::cos(2 * kPi * hue), 0.5f + 0.4f * std::cos(2 * kPi * (hue - 1.0f / 3)),
          0.5f + 0.4f * std::cos(2 * kPi * (hue - 2.0f / 3))}});
  }
  const float sizeScale = 0.012f * std::sqrt(1e5f / float(options.count));
  parallelFor(int64_t(options.count), 0, 4096, [&](int64_t begin, int64_t end) {
    for (int64_t g = begin; g < end; ++g) {
      Rng rng(options.seed, uint64_t(g));
      const float kind = rng.uniform();
      Vec3f centre, n, colour;
      // Log-normal, most of them small; as many layers deep whatever the count (a capture's
      // Gaussians shrink where there are more of them): about 24 blended along a ray through
      // the subject, as 3DGS reports for its captures.
      float size = sizeScale * std::exp(0.7f * normal01(rng));
      float flat = 0.05f + 0.25f * rng.uniform();
      if (kind < 0.6f) {  // the spheres
        const Ball& ball = balls[size_t(rng.uniform() * 7) % 7];
        const float z = 2 * rng.uniform() - 1, phi = 2 * kPi * rng.uniform();
        const float r = std::sqrt(std::max(0.0f, 1 - z * z));
        n = {r * std::cos(phi), r * std::sin(phi), z};
        centre = ball.centre + n * ball.radius;
        colour = ball.colour * (0.6f + 0.4f * std::max(0.0f, n.y));
      } else if (kind < 0.8f) {  // the ground disc
        const float r = 2.5f * std::sqrt(rng.uniform()), phi = 2 * kPi * rng.uniform();
        centre = {r * std::cos(phi), -1.0f, r * std::sin(phi)};
        n = {0, 1, 0};
        const bool check = (int(std::floor(centre.x * 2)) + int(std::floor(centre.z * 2))) % 2 != 0;
        colour = check ? Vec3f(0.75f, 0.72f, 0.65f) : Vec3f(0.35f, 0.33f, 0.3f);
      } else if (kind < 0.95f) {  // the backdrop: the far half of a shell, as a capture's
        // cameras all looked that way (a forward-facing capture)
        const float z = -rng.uniform(), phi = 2 * kPi * rng.uniform();
        const float r = std::sqrt(std::max(0.0f, 1 - z * z));
        const Vec3f out{r * std::cos(phi), r * std::sin(phi), z};
        centre = out * 10.0f;
        n = -out;  // facing the middle
        size *= 12;
        colour = Vec3f(0.45f, 0.6f, 0.85f) * (0.75f + 0.25f * out.y);
      } else {  // floaters
        centre = {6 * rng.uniform() - 3, 4 * rng.uniform() - 1.5f, 6 * rng.uniform() - 3};
        n = normalize(Vec3f(normal01(rng), normal01(rng), normal01(rng)) + Vec3f(1e-3f));
        flat = 0.5f + 0.5f * rng.uniform();
        colour = Vec3f(0.5f + 0.2f * normal01(rng));
      }
      // Training leaves opacities bimodal: a third nearly opaque, many faint, the rest between.
      const float pick = rng.uniform();
      const float opacity = kind >= 0.95f  ? 0.01f + 0.2f * rng.uniform()
                            : pick < 0.35f ? 0.9f + 0.099f * rng.uniform()
                            : pick < 0.75f
                                ? std::exp(std::log(0.01f) + std::log(30.0f) * rng.uniform())
                                : 0.3f + 0.6f * rng.uniform();
      Vec3f coefficients[kPerGaussian];
      for (int c = 0; c < 3; ++c)
        coefficients[0][c] =
            (std::clamp(colour[c] + 0.03f * normal01(rng), 0.0f, 1.0f) - 0.5f) / kShC0;
      // View dependence falling off with the band, as trained captures' coefficients do.
      for (size_t k = 1; k < kPerGaussian; ++k) {
        const float band = k < 4 ? 1.0f : k < 9 ? 2.0f : 3.0f;
        for (int c = 0; c < 3; ++c) coefficients[k][c] = 0.06f / band * normal01(rng);
      }
      Vec3f t, b;
      tangents(n, 2 * kPi * rng.uniform(), t, b);
      const Vec3f deviations{size, size * (0.3f + 0.7f * rng.uniform()), size * flat};
      writer.set(size_t(g), centre, t, b, n, deviations, opacity, coefficients);
    }
  });
  return cloud;
}

SplatMakingResult runSplatMaking(const SplatMakingRequest& request, Reporter& reporter) {
  const bool surfaces = request.source == SplatMakingRequest::Source::Surfaces;
  const size_t count = request.count
                           ? request.count
                           : (surfaces ? SurfaceSplatOptions{}.count : CaptureLikeOptions{}.count);
  if (count > kMaxMadeSplats)
    throw RequestError("count", "is at most " + std::to_string(kMaxMadeSplats) + " Gaussians",
                       std::to_string(count));
  const std::string& output = request.output;
  if (output.size() < 4 || output.compare(output.size() - 4, 4, ".ply") != 0)
    throw RequestError("output", "must name a .ply file", output);
  checkOutputFile(output);
  const int degree = surfaces ? 0 : 3;
  // The cloud and its file's bytes at once, before the scene is loaded.
  checkMemoryEstimate(splatCloudBytes(count, degree) + splatPlyFileBytes(count, degree),
                      "--count " + std::to_string(count), "the Gaussians and their file",
                      "make fewer (--count)");
  GaussianCloud cloud;
  if (surfaces) {
    const Scene scene = loadScene(request.scene, reporter);
    reporter.note("covering " + std::to_string(scene.triangleCount()) + " triangles with " +
                  std::to_string(count) + " Gaussians");
    SurfaceSplatOptions options;
    options.count = count;
    options.seed = request.seed;
    cloud = surfaceGaussians(scene, options);
  } else {
    reporter.note("making " + std::to_string(count) + " capture-like Gaussians");
    cloud = captureLikeGaussians({count, request.seed});
  }
  const std::string bytes = meshio::splatPlyBytes(cloud);
  writeFileAtomically(output, bytes);
  reporter.result("wrote " + output + " (" + std::to_string(cloud.size()) +
                  " Gaussians, spherical harmonics of degree " + std::to_string(cloud.shDegree) +
                  ")");
  return {cloud.size(), cloud.shDegree, double(bytes.size())};
}

}  // namespace parallax::jobs
