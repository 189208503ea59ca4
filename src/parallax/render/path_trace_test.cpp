// Path tracing (RenderSettings::bounces, docs/path-tracing.md) against analytic truth: furnaces
// (closed enclosures of uniform emission and albedo), a diffuse sphere inside an emitting
// sphere (the two-sphere energy balance), the white furnace under a uniform background, and a
// second code path (a scalar recursive path tracer written here, one ray at a time) on a
// Cornell-like box.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "parallax/core/random.h"
#include "parallax/image/metrics.h"
#include "parallax/render/light_sampler.h"
#include "parallax/render/render.h"
#include "parallax/render/surface.h"

namespace parallax {
namespace {

// A closed UV sphere as a triangle mesh. `inward`: the triangles' front faces (the side of
// cross(p1 - p0, p2 - p0)) look at the centre, so it emits into its interior.
void addSphereMesh(Scene& scene, const Vec3f& center, float radius, uint32_t material, bool inward,
                   int stacks = 48, int slices = 96) {
  TriangleMesh mesh;
  mesh.name = "sphere";
  mesh.material = material;
  // One vertex per (stack, slice), the seam's shared (j = slices is j = 0): the mesh is closed
  // exactly, with no crack for a ray to slip through.
  for (int i = 0; i <= stacks; ++i) {
    const float theta = kPi * float(i) / float(stacks);
    for (int j = 0; j < slices; ++j) {
      const float phi = 2.0f * kPi * float(j) / float(slices);
      const Vec3f d{std::sin(theta) * std::cos(phi), std::cos(theta),
                    std::sin(theta) * std::sin(phi)};
      mesh.positions.push_back(center + d * radius);
    }
  }
  const auto at = [slices](int i, int j) { return uint32_t(i * slices + j % slices); };
  const auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
    // Degenerate triangles at the poles are skipped (zero area: no hit, no light sample).
    const Vec3f n =
        cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
    if (!(length(n) > 0.0f)) return;
    const bool pointsIn = dot(n, center - mesh.positions[a]) > 0.0f;
    if (pointsIn == inward)
      mesh.indices.insert(mesh.indices.end(), {a, b, c});
    else
      mesh.indices.insert(mesh.indices.end(), {a, c, b});
  };
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      add(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      add(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  scene.meshes.push_back(std::move(mesh));
}

// Registers mesh `mesh` as an emissive mesh light (as io's loader does for emissive meshes).
void addMeshLight(Scene& scene, int mesh) {
  Light light;
  light.kind = Light::Kind::Mesh;
  light.mesh = mesh;
  light.intensity = scene.materials[scene.meshes[size_t(mesh)].material].emission;
  scene.lights.push_back(light);
}

// Mean and standard error of the mean of an image's (or a region's) green channel, pixels
// taken as independent estimates.
struct Estimate {
  double mean = 0, error = 0;
};
Estimate greenStats(const Image& image) {
  double sum = 0, squares = 0;
  const auto& pixels = image.pixels();
  for (const Vec3f& p : pixels) sum += p.y, squares += double(p.y) * p.y;
  const double n = double(pixels.size());
  const double mean = sum / n;
  const double variance = std::max(0.0, squares / n - mean * mean);
  return {mean, std::sqrt(variance / (n - 1))};
}

Image renderWith(const Scene& scene, const Camera& camera, int bounces, int spp,
                 RenderStats* stats = nullptr, int threads = 0) {
  const Accelerator accel(scene);
  RenderSettings settings;
  settings.samplesPerPixel = spp;
  settings.bounces = bounces;
  settings.threads = threads;
  return render(scene, accel, camera, settings, stats);
}

// Le * sum_{k=0..n} rho^k.
double geometricSum(double le, double rho, int n) {
  double sum = 0, term = le;
  for (int k = 0; k <= n; ++k) sum += term, term *= rho;
  return sum;
}

// (a) The furnace. Inside a closed enclosure whose walls all emit Le and reflect with albedo
// rho, light reflected k times has radiance Le rho^k everywhere (uniform radiance L over a
// whole hemisphere reflects rho L), whatever the enclosure's shape.
// - Walls that are a mesh light: the camera sees Le (emission at depth 0), next-event
//   estimation at each of the 1 + N vertices adds one more reflection, and the emission that
//   bounce rays hit is not counted again: L = Le sum_{k=0..N+1} rho^k.
// - Walls that emit but are no light (nothing samples them): only hits count the emission,
//   the camera's and each of the N bounces': L = Le sum_{k=0..N} rho^k.
// Both tell double counting (one too many terms) from missing light (one too few).
TEST(PathTrace, FurnaceGivesTheGeometricSeriesOfTheAlbedo) {
  const float le = 1.0f, rho = 0.5f;
  for (const bool sampled : {true, false}) {
    Scene scene;
    Material wall;
    wall.diffuse = Vec3f(rho);
    wall.emission = Vec3f(le);
    scene.materials.push_back(wall);
    addSphereMesh(scene, {0, 0, 0}, 2.0f, 0, /*inward=*/true, 24, 48);
    if (sampled) addMeshLight(scene, 0);
    scene.ambient = Vec3f(0.0f);
    const PinholeCamera camera({0.3f, -0.2f, 0.5f}, {1, 0.4f, -1}, {0, 1, 0}, 90.0f, 24, 24);
    for (const int n : {0, 1, 2, 5}) {
      RenderStats stats;
      const Estimate e = greenStats(renderWith(scene, camera, n, 16, &stats));
      const double expected = geometricSum(le, rho, sampled ? n + 1 : n);
      EXPECT_NEAR(e.mean, expected, 4.0 * e.error + 2e-3 * expected)
          << (sampled ? "mesh light" : "unsampled emitter") << ", bounces " << n;
      // A closed room: every bounce ray hits, so each vertex but the last sends one.
      EXPECT_EQ(stats.bounceRays, stats.cameraRays * uint64_t(n)) << "bounces " << n;
    }
  }
}

// The furnace with walls that are partly mirrors: diffuse reflectance rho_d = albedo x
// (1 - mirror), mirror reflectance rho_m, emission Le, no light sampling. Uniform radiance is
// reflected as rho_d L by the diffuse part and rho_m L by the mirror part, so light that took a
// diffuse and b mirror reflections (in any of C(a + b, a) orders) has radiance Le rho_d^a
// rho_m^b. The renderer follows up to N diffuse bounces and Scene::maxDepth = M mirror
// reflections, splitting before the first diffuse bounce and choosing one of the two after it
// (weighted by the inverse probability), so its expectation is
//   L = Le sum_{a=0..N} sum_{b=0..M} C(a + b, a) rho_d^a rho_m^b.
// A wrong choice weight (or a lost or doubled branch) moves it.
TEST(PathTrace, FurnaceWithMirrorWallsCountsEveryOrderOfReflections) {
  const float le = 1.0f, albedo = 0.6f, mirror = 0.3f;
  const double rhoD = double(albedo) * (1.0 - mirror), rhoM = mirror;
  Scene scene;
  Material wall;
  wall.diffuse = Vec3f(albedo);
  wall.mirror = Vec3f(mirror);
  wall.emission = Vec3f(le);
  scene.materials.push_back(wall);
  addSphereMesh(scene, {0, 0, 0}, 2.0f, 0, /*inward=*/true, 24, 48);
  scene.ambient = Vec3f(0.0f);
  scene.maxDepth = 3;
  const PinholeCamera camera({0.3f, -0.2f, 0.5f}, {1, 0.4f, -1}, {0, 1, 0}, 90.0f, 24, 24);
  for (const int n : {0, 1, 3}) {
    double expected = 0;
    for (int a = 0; a <= n; ++a)
      for (int b = 0; b <= scene.maxDepth; ++b) {
        double orders = 1;  // C(a + b, a)
        for (int k = 1; k <= b; ++k) orders = orders * (a + k) / k;
        expected += le * orders * std::pow(rhoD, a) * std::pow(rhoM, b);
      }
    const Estimate e = greenStats(renderWith(scene, camera, n, 16));
    EXPECT_NEAR(e.mean, expected, 4.0 * e.error + 2e-3 * expected) << "bounces " << n;
  }
}

// (b) A diffuse sphere (radius r, albedo rho1, no emission) inside a concentric sphere
// (radius R) that emits Le and reflects with albedo rho2. By symmetry each sphere's radiance
// is uniform: Li on the inner one, Lo on the outer one's inside. The view factors: the inner
// sphere sees only the outer one (F_io = 1); a point of the outer one sees the inner sphere
// over F_oi = (r/R)^2 of its cosine-weighted hemisphere and itself over F_oo = 1 - (r/R)^2.
// Energy balance (light reflected at most m times: Li_m, Lo_m):
//   Li_0 = 0, Lo_0 = Le;  Li_{m+1} = rho1 Lo_m;  Lo_{m+1} = Le + rho2 (F_oi Li_m + F_oo Lo_m).
// The renderer with N bounces reflects light up to N + 1 times (next-event estimation at each
// of its 1 + N vertices), so a camera ray on the inner sphere sees Li_{N+1}. For m -> infinity
// the fixed point is
//   Lo = Le / (1 - rho2 (1 - F_oi (1 - rho1))),   Li = rho1 Lo.
// With rho2 = 0 this is Li = rho1 Le at any N (direct light already gives it all).
double innerRadiance(double le, double rho1, double rho2, double f, int reflections) {
  double li = 0, lo = le;
  for (int m = 0; m < reflections; ++m) {
    const double nextLi = rho1 * lo;
    lo = le + rho2 * (f * li + (1 - f) * lo);
    li = nextLi;
  }
  return li;
}

TEST(PathTrace, DiffuseSphereInsideEmittingSphereMatchesTheEnergyBalance) {
  const float r = 1.0f, bigR = 3.0f, le = 1.0f, rho1 = 0.8f;
  const double f = double(r / bigR) * double(r / bigR);
  // The camera between the spheres, 2.4 from the centre: the inner sphere spans 24.6 degrees
  // around the view axis, so a 30-degree field sees only the inner sphere.
  const PinholeCamera camera({0, 0, 2.4f}, {0, 0, 0}, {0, 1, 0}, 30.0f, 16, 16);
  for (const float rho2 : {0.0f, 0.6f}) {
    Scene scene;
    Material inner, outer;
    inner.diffuse = Vec3f(rho1);
    outer.diffuse = Vec3f(rho2);
    outer.emission = Vec3f(le);
    scene.materials = {inner, outer};
    addSphereMesh(scene, {0, 0, 0}, bigR, 1, /*inward=*/true);
    addMeshLight(scene, 0);
    scene.spheres.push_back({"inner", 0, {0, 0, 0}, r});
    scene.ambient = Vec3f(0.0f);
    for (const int n : {0, 1, 2, 40}) {
      if (rho2 == 0.0f && n == 2) continue;
      const Estimate e = greenStats(renderWith(scene, camera, n, 64));
      const double expected = innerRadiance(le, rho1, rho2, f, n + 1);
      // 1 % for the tessellated outer sphere (its facets sit up to 0.1 % inside R, and its
      // view factors shift with them) on top of the Monte-Carlo error.
      EXPECT_NEAR(e.mean, expected, 4.0 * e.error + 0.01 * expected)
          << "rho2 " << rho2 << ", bounces " << n;
      if (rho2 == 0.0f) {
        EXPECT_NEAR(expected, rho1 * le, 1e-9);
      }
    }
    if (rho2 > 0.0f) {
      // At 40 bounces the series has converged to the closed form (the remainder is below
      // 0.6^40), so the render above was compared with it too.
      const double closed = rho1 * le / (1 - rho2 * (1 - f * (1 - rho1)));
      EXPECT_NEAR(innerRadiance(le, rho1, rho2, f, 41), closed, 1e-6 * closed);
    }
  }
}

// (c) The white furnace: a convex object of albedo 1 under a uniform background B, no lights,
// no ambient. Each diffuse bounce from a convex surface escapes (it cannot meet the object
// again), and the bounce's weight is albedo 1 (cosine sampling cancels BRDF x cosine), so every
// camera ray returns exactly B for any N >= 1: nothing absorbed, nothing created. With N = 0
// the object reflects only the ambient term (direct light only, as before path tracing).
// One object per scene: two convex objects together are not convex (one's bounces meet the
// other).
void expectWhiteFurnace(bool sphere) {
  const Vec3f background{0.3f, 0.5f, 0.7f};
  Scene scene;
  Material white;
  white.diffuse = Vec3f(1.0f);
  scene.materials.push_back(white);
  if (sphere)
    scene.spheres.push_back({"ball", 0, {-0.3f, 0, 0}, 0.6f});
  else
    addBox(scene, "box", {-0.5f, -0.4f, -0.4f}, {0.5f, 0.4f, 0.4f}, 0);  // convex, outward
  scene.background = background;
  scene.ambient = Vec3f(0.0f);
  const PinholeCamera camera({0.2f, 0.8f, 3.0f}, {0.2f, 0, 0}, {0, 1, 0}, 40.0f, 32, 24);
  const Accelerator accel(scene);
  for (const int n : {1, 3}) {
    const Image img = renderWith(scene, camera, n, 4);
    for (const Vec3f& p : img.pixels()) {
      EXPECT_NEAR(p.x, background.x, 1e-5f);
      EXPECT_NEAR(p.y, background.y, 1e-5f);
      EXPECT_NEAR(p.z, background.z, 1e-5f);
    }
  }
  // Which pixels' centres see an object; pixels on a silhouette (a neighbour differs) are left
  // out of the exact comparisons below, where the renderer's packet rays and the single rays
  // here may round differently.
  const int w = camera.width(), h = camera.height();
  std::vector<int> object(size_t(w * h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      object[size_t(y * w + x)] = accel.intersect(camera.generateRay({x + 0.5f, y + 0.5f})).valid();
  const auto interior = [&](int x, int y) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = std::clamp(x + dx, 0, w - 1), ny = std::clamp(y + dy, 0, h - 1);
        if (object[size_t(ny * w + nx)] != object[size_t(y * w + x)]) return false;
      }
    return true;
  };
  // N = 0: the objects are black (no light, no ambient) where the camera sees them.
  const Image direct = renderWith(scene, camera, 0, 1);
  int objectPixels = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!interior(x, y)) continue;
      const bool seen = object[size_t(y * w + x)] != 0;
      objectPixels += seen;
      EXPECT_EQ(direct.at(x, y).y, seen ? 0.0f : background.y);
    }
  EXPECT_GT(objectPixels, 50);
  // Ambient A stands in for the light beyond the last diffuse bounce: with N = 0 the object
  // reflects albedo x A = A; with N >= 1 the bounces escape to B and no ambient is added.
  scene.ambient = Vec3f(0.25f);
  const Image ambient0 = renderWith(scene, camera, 0, 1);
  const Image ambient2 = renderWith(scene, camera, 2, 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      EXPECT_NEAR(ambient2.at(x, y).y, background.y, 1e-5f);
      if (interior(x, y)) {
        EXPECT_EQ(ambient0.at(x, y).y, object[size_t(y * w + x)] ? 0.25f : background.y);
      }
    }
}

TEST(PathTrace, WhiteFurnaceReturnsTheBackgroundExactly) {
  expectWhiteFurnace(true);
  expectWhiteFurnace(false);
}

// A Cornell-like box, built here: a unit room open toward +z (the camera), white floor,
// ceiling and back wall, red left and green right wall, a quad light under the ceiling facing
// down (its visible quad is a mesh, as the scene loader makes it), a white block and a block
// that is partly a mirror. Mesh 0 is the light's quad.
struct CornellBox {
  Scene scene;
  uint32_t floorMesh = 0, ceilingMesh = 0;
};

CornellBox cornellBox(float ambient, float background) {
  CornellBox box;
  Scene& s = box.scene;
  Material white, red, green, lamp, glossy;
  white.diffuse = Vec3f(0.75f);
  red.diffuse = {0.65f, 0.06f, 0.05f};
  green.diffuse = {0.12f, 0.48f, 0.1f};
  lamp.diffuse = Vec3f(0.0f);
  lamp.emission = {17.0f, 12.0f, 4.0f};
  glossy.diffuse = Vec3f(0.7f);
  glossy.mirror = Vec3f(0.3f);
  s.materials = {white, red, green, lamp, glossy};
  Light light;
  light.kind = Light::Kind::Quad;
  light.corner = {0.4f, 0.999f, -0.6f};
  light.edgeU = {0.2f, 0, 0};
  light.edgeV = {0, 0, 0.2f};  // cross(edgeU, edgeV) = -y: emits downward
  light.intensity = lamp.emission;
  addQuad(s, "lamp", light.corner, light.edgeU, light.edgeV, 3);
  light.mesh = 0;
  s.lights.push_back(light);
  // Walls facing into the room (front face = side of cross(edgeU, edgeV)).
  box.floorMesh = uint32_t(s.meshes.size());
  addQuad(s, "floor", {0, 0, 0}, {0, 0, -1}, {1, 0, 0}, 0);  // +y
  box.ceilingMesh = uint32_t(s.meshes.size());
  addQuad(s, "ceiling", {0, 1, 0}, {1, 0, 0}, {0, 0, -1}, 0);  // -y
  addQuad(s, "back", {0, 0, -1}, {1, 0, 0}, {0, 1, 0}, 0);     // +z
  addQuad(s, "left", {0, 0, 0}, {0, 1, 0}, {0, 0, -1}, 1);     // +x
  addQuad(s, "right", {1, 0, 0}, {0, 0, -1}, {0, 1, 0}, 2);    // -x
  addBox(s, "short block", {0.55f, 0.0f, -0.45f}, {0.8f, 0.3f, -0.2f}, 0);
  addBox(s, "tall block", {0.2f, 0.0f, -0.8f}, {0.45f, 0.6f, -0.55f}, 4);
  s.ambient = Vec3f(ambient);
  s.background = Vec3f(background);
  return box;
}

PinholeCamera cornellCamera(int size) {
  return PinholeCamera({0.5f, 0.5f, 1.4f}, {0.5f, 0.5f, 0.0f}, {0, 1, 0}, 42.0f, size, size);
}

// (d) A second code path: the same estimator (docs/path-tracing.md, eq. 1-4) written as a plain
// recursive function of one ray, on Accelerator::intersect/occluded, SurfaceShader::evaluate
// and LightSampler::sample, with its own random numbers.
class ScalarPathTracer {
 public:
  ScalarPathTracer(const Scene& scene, const Accelerator& accel, int bounces, uint32_t lightMesh)
      : scene_(scene),
        accel_(accel),
        shader_(scene, accel),
        lights_(scene),
        bounces_(bounces),
        lightGeometry_(lightMesh) {}

  Vec3f radiance(const Ray& ray, int mirrorDepth, int diffuseDepth, bool afterDiffuse,
                 Rng& rng) const {
    const Hit hit = accel_.intersect(ray);
    if (!hit.valid()) return scene_.background;
    const SurfacePoint sp = shader_.evaluate(ray, hit);
    // Emission, unless a diffuse bounce hit the light that next-event estimation samples.
    Vec3f l = afterDiffuse && hit.geometry == lightGeometry_ ? Vec3f(0.0f) : sp.emission;
    if (diffuseDepth == bounces_) l = l + sp.diffuse * scene_.ambient;
    // Next-event estimation: L_d = (rho / pi) E, E = irradiance / pdf from the light sampler.
    if (maxComponent(sp.diffuse) > 0.0f) {
      for (size_t i = 0; i < lights_.lightCount(); ++i) {
        const int samples = lights_.samplesFor(i);
        for (int s = 0; s < samples; ++s) {
          const float u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
          const LightSample ls = lights_.sample(i, sp.position, sp.shadingNormal, u1, u2, u3);
          if (!ls.valid || !(dot(ls.toLight, sp.geometricNormal) > 0.0f)) continue;
          const Vec3f origin = offsetAlong(sp.position, sp.geometricNormal);
          const Ray shadow{origin, sp.position + ls.toLight - origin, 0.0f, ls.tMax};
          if (accel_.occluded(shadow)) continue;
          l = l + sp.diffuse * ls.irradiance * (1.0f / (kPi * float(samples)));
        }
      }
    }
    // Continuation: both before the first diffuse bounce, one (chosen by reflectance) after.
    const float m = mirrorDepth < scene_.maxDepth ? maxComponent(sp.mirror) : 0.0f;
    const float d = diffuseDepth < bounces_ ? maxComponent(sp.diffuse) : 0.0f;
    float wm = m > 0.0f ? 1.0f : 0.0f, wd = d > 0.0f ? 1.0f : 0.0f;
    const float choice = rng.uniform();
    if (diffuseDepth > 0 && m > 0.0f && d > 0.0f) {
      const float pm = m / (m + d);
      wm = choice < pm ? 1.0f / pm : 0.0f;
      wd = choice < pm ? 0.0f : 1.0f / (1.0f - pm);
    }
    if (wm > 0.0f) {
      const Vec3f dir = normalize(ray.direction);
      const Vec3f n = sp.shadingNormal;
      const Ray mirror{offsetAlong(sp.position, sp.geometricNormal),
                       dir - n * (2.0f * dot(dir, n))};
      l = l + sp.mirror * wm * radiance(mirror, mirrorDepth + 1, diffuseDepth, false, rng);
    }
    if (wd > 0.0f) {
      // Cosine-weighted about the shading normal, by rejection from the unit disc lifted to the
      // hemisphere (a different construction from the renderer's).
      float x, y;
      do {
        x = 2.0f * rng.uniform() - 1.0f;
        y = 2.0f * rng.uniform() - 1.0f;
      } while (x * x + y * y >= 1.0f);
      const Vec3f n = sp.shadingNormal;
      const Vec3f helper = std::abs(n.x) > 0.5f ? Vec3f(0, 1, 0) : Vec3f(1, 0, 0);
      const Vec3f t = normalize(cross(helper, n)), b = cross(n, t);
      const Vec3f dir = t * x + b * y + n * std::sqrt(std::max(0.0f, 1.0f - x * x - y * y));
      if (dot(dir, sp.geometricNormal) > 0.0f) {
        const Ray bounce{offsetAlong(sp.position, sp.geometricNormal), dir};
        l = l + sp.diffuse * wd * radiance(bounce, mirrorDepth, diffuseDepth + 1, true, rng);
      }
    }
    return l;
  }

 private:
  const Scene& scene_;
  const Accelerator& accel_;
  const SurfaceShader shader_;
  const LightSampler lights_;
  int bounces_;
  uint32_t lightGeometry_;
};

TEST(PathTrace, PacketRendererAgreesWithAScalarPathTracer) {
  const CornellBox box = cornellBox(0.03f, 0.1f);
  const Scene& scene = box.scene;
  const Accelerator accel(scene);
  const int size = 48, spp = 64, bounces = 3, regions = 3, side = size / regions;
  const PinholeCamera camera = cornellCamera(size);
  RenderSettings settings;
  settings.samplesPerPixel = spp;
  settings.bounces = bounces;
  const Image packets = render(scene, accel, camera, settings);

  const ScalarPathTracer scalar(scene, accel, bounces, /*lightMesh=*/0);
  // Per region: the packet image's mean, the scalar mean, and the scalar samples' variance.
  std::vector<Vec3f> packetSum(regions * regions, Vec3f(0.0f)), scalarSum = packetSum,
                                                                scalarSquares = packetSum;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const int region = (y / side) * regions + x / side;
      packetSum[size_t(region)] = packetSum[size_t(region)] + packets.at(x, y);
      Rng rng(uint64_t(y) * 1000 + uint64_t(x), 12345);
      for (int s = 0; s < spp; ++s) {
        const Ray ray = camera.generateRay({x + rng.uniform(), y + rng.uniform()});
        const Vec3f l = scalar.radiance(ray, 0, 0, false, rng);
        scalarSum[size_t(region)] = scalarSum[size_t(region)] + l;
        scalarSquares[size_t(region)] = scalarSquares[size_t(region)] + l * l;
      }
    }
  const double pixels = double(side * side), samples = pixels * spp;
  for (int region = 0; region < regions * regions; ++region)
    for (int c = 0; c < 3; ++c) {
      const double packetMean = packetSum[size_t(region)][c] / pixels;
      const double scalarMean = scalarSum[size_t(region)][c] / samples;
      const double variance =
          std::max(0.0, scalarSquares[size_t(region)][c] / samples - scalarMean * scalarMean);
      // The scalar estimate's standard error; the packet render's (stratified, so no larger)
      // is taken to be the same.
      const double error = std::sqrt(2.0 * variance / samples);
      EXPECT_NEAR(packetMean, scalarMean, 4.0 * error + 0.005 * scalarMean)
          << "region " << region << ", channel " << c;
    }
}

// Pixels that see only mesh `mesh` (the centre rays of the pixel and its eight neighbours all
// meet it first: no antialiased edge of the lamp or a wall), and whose centre's hit lies in an
// x range.
std::vector<std::pair<int, int>> pixelsOn(const Accelerator& accel, const Camera& camera,
                                          uint32_t mesh, float xMin = -1e9f, float xMax = 1e9f) {
  const auto meets = [&](int x, int y, float* hitX) {
    const Ray ray = camera.generateRay({x + 0.5f, y + 0.5f});
    const Hit hit = accel.intersect(ray);
    if (hitX && hit.valid()) *hitX = ray.at(hit.t).x;
    return hit.valid() && hit.geometry == mesh;
  };
  std::vector<std::pair<int, int>> out;
  for (int y = 1; y + 1 < camera.height(); ++y)
    for (int x = 1; x + 1 < camera.width(); ++x) {
      float px = 0;
      bool all = meets(x, y, &px);
      for (int dy = -1; dy <= 1 && all; ++dy)
        for (int dx = -1; dx <= 1 && all; ++dx) all = meets(x + dx, y + dy, nullptr);
      if (all && px >= xMin && px <= xMax) out.emplace_back(x, y);
    }
  return out;
}

Vec3f meanOver(const Image& image, const std::vector<std::pair<int, int>>& pixels) {
  Vec3f sum(0.0f);
  for (const auto& [x, y] : pixels) sum = sum + image.at(x, y);
  return sum * (1.0f / float(pixels.size()));
}

// The Cornell box: with direct light only its ceiling is black (the lamp faces away from it)
// and its floor is lit white; with bounces the ceiling is lit and the floor beside the red wall
// turns red, beside the green wall green (colour bleeding).
TEST(PathTrace, CornellBoxGetsALitCeilingAndColourBleeding) {
  const CornellBox box = cornellBox(0.0f, 0.0f);
  const Accelerator accel(box.scene);
  const PinholeCamera camera = cornellCamera(48);
  const Image direct = renderWith(box.scene, camera, 0, 16);
  const Image bounced = renderWith(box.scene, camera, 3, 16);
  const auto ceiling = pixelsOn(accel, camera, box.ceilingMesh);
  const auto nearRed = pixelsOn(accel, camera, box.floorMesh, 0.0f, 0.12f);
  const auto nearGreen = pixelsOn(accel, camera, box.floorMesh, 0.88f, 1.0f);
  ASSERT_GT(ceiling.size(), 50u);
  // Enough floor pixels for a mean (about a dozen at this size; which pixels pass the edge test
  // varies a little between builds, e.g. with and without -march=native).
  ASSERT_GE(nearRed.size(), 5u);
  ASSERT_GE(nearGreen.size(), 5u);
  EXPECT_EQ(maxComponent(meanOver(direct, ceiling)), 0.0f);
  EXPECT_GT(luminance(meanOver(bounced, ceiling)), 0.01f);
  // The lamp's own colour tints everything alike; the walls' tint shows as the red/green
  // balance moving against the direct picture's.
  const Vec3f redDirect = meanOver(direct, nearRed), redBounced = meanOver(bounced, nearRed);
  const Vec3f greenDirect = meanOver(direct, nearGreen),
              greenBounced = meanOver(bounced, nearGreen);
  EXPECT_GT(redBounced.x / redBounced.y, 1.1f * redDirect.x / redDirect.y);
  EXPECT_GT(greenBounced.y / greenBounced.x, 1.1f * greenDirect.y / greenDirect.x);
}

// Determinism: the same picture for 1 and 2 threads with bounces; bounces unset and 0 give the
// same picture and counts (the direct renderer); the new rays are counted.
TEST(PathTrace, DeterministicAndCounted) {
  const CornellBox box = cornellBox(0.02f, 0.05f);
  const PinholeCamera camera = cornellCamera(40);
  RenderStats one, two;
  const Image a = renderWith(box.scene, camera, 3, 4, &one, 1);
  const Image b = renderWith(box.scene, camera, 3, 4, &two, 2);
  EXPECT_EQ(a.pixels(), b.pixels());
  EXPECT_EQ(one.bounceRays, two.bounceRays);
  EXPECT_GT(one.bounceRays, one.cameraRays);  // a closed room but for its front: most go on
  EXPECT_LE(one.bounceRays, 3 * one.cameraRays);
  EXPECT_LE(one.bounceRays, one.secondaryRays);
  EXPECT_EQ(one.totalRays(), one.cameraRays + one.shadowRays + one.secondaryRays);

  const Scene scene = defaultScene();
  const Accelerator accel(scene);
  const CameraSpec& c = *scene.camera;
  const PinholeCamera view(c.eye, c.lookAt, c.up, c.fovDegrees, 61, 37);
  RenderSettings unset, zero;
  unset.samplesPerPixel = zero.samplesPerPixel = 4;
  zero.bounces = 0;
  RenderStats unsetStats, zeroStats;
  const Image u = render(scene, accel, view, unset, &unsetStats);
  const Image z = render(scene, accel, view, zero, &zeroStats);
  EXPECT_EQ(u.pixels(), z.pixels());
  EXPECT_EQ(unsetStats.totalRays(), zeroStats.totalRays());
  EXPECT_EQ(zeroStats.bounceRays, 0u);
}

}  // namespace
}  // namespace parallax
