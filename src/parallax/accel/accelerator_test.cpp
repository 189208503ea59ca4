// Accelerator against independent truths: the ray-sphere quadratic, the slab method for boxes,
// ray-plane intersection for quads and a brute-force Moller-Trumbore intersector, all in double
// precision; then the packet and occlusion paths against the single-ray closest-hit path.
#include "parallax/accel/accelerator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/core/random.h"

// The header this build compiled against: the truth the library's own report is checked with.
#if PARALLAX_EMBREE_MAJOR == 4
#include <embree4/rtcore_config.h>
#else
#include <embree3/rtcore_config.h>
#endif

namespace parallax {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Double-precision vectors for the reference intersectors.
struct D3 {
  double x = 0, y = 0, z = 0;
  D3() = default;
  D3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
  explicit D3(const Vec3f& v) : x(v.x), y(v.y), z(v.z) {}
  double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};
D3 operator+(const D3& a, const D3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
D3 operator-(const D3& a, const D3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
D3 operator*(const D3& a, double s) {
  return {a.x * s, a.y * s, a.z * s};
}
double dot(const D3& a, const D3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
D3 cross(const D3& a, const D3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double norm(const D3& a) {
  return std::sqrt(dot(a, a));
}
D3 unit(const D3& a) {
  return a * (1.0 / norm(a));
}

float uniform(Rng& rng, float lo, float hi) {
  return lo + (hi - lo) * rng.uniform();
}
Vec3f uniformBox(Rng& rng, float lo, float hi) {
  return {uniform(rng, lo, hi), uniform(rng, lo, hi), uniform(rng, lo, hi)};
}
// A direction that is neither unit length nor axis aligned.
Vec3f randomDirection(Rng& rng) {
  Vec3f d;
  do d = uniformBox(rng, -1.0f, 1.0f);
  while (dot(d, d) < 0.01f || dot(d, d) > 1.0f);
  return d * uniform(rng, 0.3f, 3.0f);
}

void expectNormalAlong(const Vec3f& ng, const D3& expected) {
  ASSERT_GT(length(ng), 0.0f);
  EXPECT_GT(dot(unit(D3(ng)), unit(expected)), 1.0 - 1e-5)
      << "Ng (" << ng.x << ", " << ng.y << ", " << ng.z << ")";
}

// ---- Spheres: |o + t d - c|^2 = r^2, the nearer root inside [tMin, tMax] ----

struct SphereTruth {
  double t = kInf;
  int sphere = -1;
  bool ambiguous = false;  // tangent ray, or two spheres at nearly the same distance
};

SphereTruth sphereTruth(const std::vector<Sphere>& spheres, const Ray& ray) {
  SphereTruth truth;
  const D3 o(ray.origin), d(ray.direction);
  std::vector<double> ts;
  for (size_t i = 0; i < spheres.size(); ++i) {
    const D3 oc = o - D3(spheres[i].center);
    const double r = spheres[i].radius;
    const double a = dot(d, d), halfB = dot(oc, d), c = dot(oc, oc) - r * r;
    // Distance from the centre to the ray's line, relative to r: 1 means tangent.
    const double lineDistance = norm(cross(oc, d)) / std::sqrt(a);
    if (std::abs(lineDistance / r - 1.0) < 1e-4) truth.ambiguous = true;
    const double disc = halfB * halfB - a * c;
    if (disc < 0) continue;
    for (double t : {(-halfB - std::sqrt(disc)) / a, (-halfB + std::sqrt(disc)) / a}) {
      if (t < ray.tMin || t > ray.tMax) continue;
      ts.push_back(t);
      if (t < truth.t) truth.t = t, truth.sphere = int(i);
      break;
    }
  }
  std::sort(ts.begin(), ts.end());
  if (ts.size() > 1 && ts[1] - ts[0] < 1e-4 * ts[0]) truth.ambiguous = true;
  return truth;
}

TEST(AcceleratorSpheres, MatchAnalyticNearestHitAndOutwardNormal) {
  Rng rng(11);
  Scene scene;
  addQuad(scene, "far wall", {-50, -50, -40}, {100, 0, 0}, {0, 100, 0}, 0);  // offsets geomIDs
  for (int i = 0; i < 12; ++i)
    scene.spheres.push_back({"s", 0, uniformBox(rng, -3, 3), uniform(rng, 0.2f, 1.0f)});
  const Accelerator accel(scene);

  int hits = 0, inside = 0, skipped = 0;
  for (int i = 0; i < 5000; ++i) {
    Ray ray;
    if (i % 5 == 0) {  // start at a centre: the hit is the far root, on the way out
      ray.origin = scene.spheres[size_t(i / 5) % scene.spheres.size()].center;
    } else {
      ray.origin = normalize(randomDirection(rng)) * 10.0f;
    }
    ray.direction = (uniformBox(rng, -3, 3) - ray.origin) * uniform(rng, 0.5f, 2.0f);
    const SphereTruth truth = sphereTruth(scene.spheres, ray);
    if (truth.ambiguous) {
      ++skipped;
      continue;
    }
    // Rays that miss every sphere escape or end on the wall far behind them.
    const Hit hit = accel.intersect(ray);
    if (truth.sphere < 0) {
      if (hit.valid()) {
        EXPECT_EQ(accel.surface(hit.geometry).kind, SurfaceRef::Kind::Mesh);
      }
      continue;
    }
    ASSERT_TRUE(hit.valid()) << "ray " << i;
    ++hits;
    inside += i % 5 == 0;
    const SurfaceRef ref = accel.surface(hit.geometry);
    ASSERT_EQ(ref.kind, SurfaceRef::Kind::Sphere) << "ray " << i;
    ASSERT_EQ(ref.index, uint32_t(truth.sphere)) << "ray " << i;
    EXPECT_EQ(hit.geometry, scene.meshes.size() + uint32_t(truth.sphere));
    EXPECT_NEAR(hit.t, truth.t, 1e-4 * truth.t) << "ray " << i;
    const Sphere& s = scene.spheres[size_t(truth.sphere)];
    const D3 p = D3(ray.origin) + D3(ray.direction) * truth.t;
    expectNormalAlong(hit.geometricNormal, p - D3(s.center));  // outward, also from inside
    EXPECT_NEAR(length(hit.geometricNormal), s.radius, 1e-3 * s.radius);
  }
  EXPECT_GT(hits, 1500);
  EXPECT_GT(inside, 500);
  EXPECT_LT(skipped, 50);
}

// ---- An axis-aligned box from addBox against the slab method ----

TEST(AcceleratorBox, MatchesSlabMethod) {
  const Vec3f lo{-1.0f, -0.5f, -2.0f}, hi{1.5f, 0.7f, 0.3f};
  Scene scene;
  addBox(scene, "box", lo, hi, 0);
  const Accelerator accel(scene);
  Rng rng(12);
  int hits = 0, fromInside = 0, skipped = 0;
  for (int i = 0; i < 5000; ++i) {
    // Aim at points around the box: about half the rays hit it.
    const Vec3f origin = uniformBox(rng, -4, 4);
    const Vec3f target{uniform(rng, lo.x - 0.5f, hi.x + 0.5f),
                       uniform(rng, lo.y - 0.5f, hi.y + 0.5f),
                       uniform(rng, lo.z - 0.5f, hi.z + 0.5f)};
    const Ray ray{origin, (target - origin) * uniform(rng, 0.5f, 2.0f)};
    const D3 o(ray.origin), d(ray.direction);
    double tEnter = -kInf, tExit = kInf;
    int enterAxis = 0, exitAxis = 0;
    for (int a = 0; a < 3; ++a) {
      const double t0 = (lo[a] - o[a]) / d[a], t1 = (hi[a] - o[a]) / d[a];
      if (std::min(t0, t1) > tEnter) tEnter = std::min(t0, t1), enterAxis = a;
      if (std::max(t0, t1) < tExit) tExit = std::max(t0, t1), exitAxis = a;
    }
    const bool truthHit = tEnter <= tExit && tExit > 0;
    const bool entering = tEnter > 0;
    const double t = entering ? tEnter : tExit;
    const int axis = entering ? enterAxis : exitAxis;
    // Skip rays that pass within 1e-4 of an edge: the slab and the triangles may disagree.
    const D3 p = o + d * t;
    bool nearEdge = std::abs(tEnter - tExit) < 1e-4 * std::abs(t);
    for (int a = 0; a < 3 && truthHit; ++a)
      if (a != axis && std::min(std::abs(p[a] - lo[a]), std::abs(p[a] - hi[a])) < 1e-4)
        nearEdge = true;
    if (nearEdge) {
      ++skipped;
      continue;
    }
    const Hit hit = accel.intersect(ray);
    ASSERT_EQ(hit.valid(), truthHit) << "ray " << i;
    if (!truthHit) continue;
    ++hits;
    fromInside += !entering;
    EXPECT_NEAR(hit.t, t, 1e-4 * t) << "ray " << i;
    // addBox faces outward: entering rays meet a face against them, leaving rays along them.
    D3 outward{0, 0, 0};
    const double sign = d[axis] > 0 ? 1.0 : -1.0;
    (axis == 0 ? outward.x : axis == 1 ? outward.y : outward.z) = entering ? -sign : sign;
    expectNormalAlong(hit.geometricNormal, outward);
  }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(fromInside, 50);
  EXPECT_LT(skipped, 50);
}

// ---- Parallelograms from addQuad against ray-plane intersection ----

TEST(AcceleratorQuad, MatchesPlaneIntersection) {
  Rng rng(13);
  for (int q = 0; q < 5; ++q) {
    const Vec3f corner = uniformBox(rng, -1, 1);
    const Vec3f edgeU = randomDirection(rng), edgeV = randomDirection(rng);
    Scene scene;
    addQuad(scene, "quad", corner, edgeU, edgeV, 0);
    const Accelerator accel(scene);
    const D3 c(corner), u(edgeU), v(edgeV), n = cross(u, v);
    // Gram matrix of the edges, to solve p - c = s u + w v in the plane.
    const double uu = dot(u, u), uv = dot(u, v), vv = dot(v, v), det = uu * vv - uv * uv;
    int hits = 0;
    for (int i = 0; i < 1000; ++i) {
      // Aim at a point in the plane around the quad, so that about half the rays hit it.
      const Vec3f origin = uniformBox(rng, -5, 5);
      const Vec3f target =
          corner + edgeU * uniform(rng, -0.3f, 1.3f) + edgeV * uniform(rng, -0.3f, 1.3f);
      const Ray aimed{origin, target - origin};
      const D3 o(aimed.origin), d(aimed.direction);
      const double denom = dot(d, n);
      if (std::abs(denom) < 1e-3 * norm(d) * norm(n)) continue;  // grazing
      const double t = dot(c - o, n) / denom;
      const D3 rel = o + d * t - c;
      const double pu = dot(rel, u), pv = dot(rel, v);
      const double s = (vv * pu - uv * pv) / det, w = (uu * pv - uv * pu) / det;
      const double margin = std::min({s, w, 1 - s, 1 - w});
      if (std::abs(margin) < 1e-4 || std::abs(s - w) < 1e-4) continue;
      const bool truthHit = t > 0 && margin > 0;
      const Hit hit = accel.intersect(aimed);
      ASSERT_EQ(hit.valid(), truthHit) << "quad " << q << " ray " << i;
      if (!truthHit) continue;
      ++hits;
      EXPECT_EQ(hit.geometry, 0u);
      EXPECT_NEAR(hit.t, t, 1e-4 * t);
      // Triangle 0 is (corner, +U, +U+V): the half with s >= w.
      EXPECT_EQ(hit.primitive, s >= w ? 0u : 1u);
      expectNormalAlong(hit.geometricNormal, n);  // the front side, whichever side the ray is on
    }
    EXPECT_GT(hits, 200);
  }
}

// ---- Triangle soups against brute-force Moller-Trumbore (Moller & Trumbore 1997) ----

struct SoupTriangle {
  D3 p0, p1, p2;
  uint32_t mesh, primitive;
};

struct SoupTruth {
  double t = kInf, secondT = kInf;  // nearest and second-nearest hit
  int triangle = -1;
  double b1 = 0, b2 = 0;
  bool ambiguous = false;  // passes within 1e-6 (barycentric) of an edge of some triangle
};

SoupTruth bruteForce(const std::vector<SoupTriangle>& soup, const Ray& ray) {
  SoupTruth truth;
  const D3 o(ray.origin), d(ray.direction);
  for (size_t i = 0; i < soup.size(); ++i) {
    const D3 e1 = soup[i].p1 - soup[i].p0, e2 = soup[i].p2 - soup[i].p0;
    const D3 pvec = cross(d, e2);
    const double det = dot(e1, pvec);
    if (std::abs(det) < 1e-12 * norm(d) * norm(e1) * norm(e2)) continue;
    const D3 tvec = o - soup[i].p0;
    const double b1 = dot(tvec, pvec) / det;
    const D3 qvec = cross(tvec, e1);
    const double b2 = dot(d, qvec) / det;
    const double t = dot(e2, qvec) / det;
    if (t < ray.tMin - 1e-5 * std::abs(t) || t > ray.tMax + 1e-5 * std::abs(t)) continue;
    const double margin = std::min({b1, b2, 1 - b1 - b2});
    if (std::abs(margin) < 1e-6) truth.ambiguous = true;
    if (std::abs(t - ray.tMin) < 1e-5 * std::abs(t) || std::abs(t - ray.tMax) < 1e-5 * t)
      truth.ambiguous = true;
    if (margin < 0) continue;
    if (t < truth.t) {
      truth.secondT = truth.t;
      truth.t = t, truth.triangle = int(i), truth.b1 = b1, truth.b2 = b2;
    } else {
      truth.secondT = std::min(truth.secondT, t);
    }
  }
  return truth;
}

// Small random triangles in [-1.2, 1.2]^3 spread over three meshes whose vertex arrays are
// shuffled, so that the index buffers matter.
Scene randomSoup(Rng& rng, int triangleCount, std::vector<SoupTriangle>& soup) {
  Scene scene;
  const int perMesh = (triangleCount + 2) / 3;
  for (int first = 0; first < triangleCount; first += perMesh) {
    const int count = std::min(perMesh, triangleCount - first);
    TriangleMesh mesh;
    mesh.name = "soup";
    std::vector<uint32_t> slot(size_t(3 * count));
    for (size_t i = 0; i < slot.size(); ++i) slot[i] = uint32_t(i);
    for (size_t i = slot.size() - 1; i > 0; --i) std::swap(slot[i], slot[rng.next() % (i + 1)]);
    mesh.positions.resize(slot.size());
    for (int k = 0; k < count; ++k) {
      const Vec3f center = uniformBox(rng, -1, 1);
      Vec3f p[3];
      for (int j = 0; j < 3; ++j) {
        p[j] = center + uniformBox(rng, -0.2f, 0.2f);
        const uint32_t s = slot[size_t(3 * k + j)];
        mesh.positions[s] = p[j];
        mesh.indices.push_back(s);
      }
      soup.push_back({D3(p[0]), D3(p[1]), D3(p[2]), uint32_t(scene.meshes.size()), uint32_t(k)});
    }
    scene.meshes.push_back(std::move(mesh));
  }
  return scene;
}

Ray randomSoupRay(Rng& rng) {
  Ray ray{uniformBox(rng, -2, 2), randomDirection(rng)};
  // Half the rays aim into the cloud, so that most of them hit something.
  if (rng.next() % 2) ray.direction = (uniformBox(rng, -1, 1) - ray.origin) * uniform(rng, 0.5f, 2);
  const uint32_t kind = rng.next() % 4;
  if (kind == 1) ray.tMin = uniform(rng, 0.0f, 1.0f);
  if (kind == 2) ray.tMax = uniform(rng, 0.1f, 2.0f);
  return ray;
}

// scene/scene.h's one-ray firstHitDistance (the focus of a file camera's shot) against
// Embree: the same nearest distance on a soup of triangles and spheres, and no hit where
// Embree finds none.
TEST(AcceleratorTriangles, SceneFirstHitDistanceIsTheClosestHit) {
  Rng rng(21);
  std::vector<SoupTriangle> soup;
  Scene scene = randomSoup(rng, 600, soup);
  for (int i = 0; i < 6; ++i)
    scene.spheres.push_back({"s", 0, uniformBox(rng, -1, 1), uniform(rng, 0.05f, 0.3f)});
  const Accelerator accel(scene);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    Ray ray = randomSoupRay(rng);
    ray.direction = normalize(ray.direction);
    ray.tMin = 0;
    ray.tMax = std::numeric_limits<float>::infinity();
    const Hit hit = accel.intersect(ray);
    const std::optional<float> first = firstHitDistance(scene, ray.origin, ray.direction);
    ASSERT_EQ(first.has_value(), hit.valid()) << "ray " << i;
    if (!first) continue;
    ++hits;
    EXPECT_NEAR(*first, hit.t, 1e-4f * hit.t + 1e-6f) << "ray " << i;
  }
  EXPECT_GT(hits, 500);
}

TEST(AcceleratorTriangles, MatchBruteForceOnRandomSoup) {
  Rng rng(14);
  std::vector<SoupTriangle> soup;
  const Scene scene = randomSoup(rng, 2000, soup);
  const Accelerator accel(scene);
  int hits = 0, skipped = 0, ties = 0;
  for (int i = 0; i < 5000; ++i) {
    const Ray ray = randomSoupRay(rng);
    const SoupTruth truth = bruteForce(soup, ray);
    if (truth.ambiguous) {
      ++skipped;
      continue;
    }
    const Hit hit = accel.intersect(ray);
    ASSERT_EQ(hit.valid(), truth.triangle >= 0) << "ray " << i;
    EXPECT_EQ(accel.occluded(ray), hit.valid()) << "ray " << i;
    if (!hit.valid()) continue;
    ++hits;
    EXPECT_NEAR(hit.t, truth.t, 1e-4 * truth.t) << "ray " << i;
    const bool tie = truth.secondT - truth.t < 1e-4 * truth.t;
    ties += tie;
    const SoupTriangle& expected = soup[size_t(truth.triangle)];
    if (!tie) {
      ASSERT_EQ(accel.surface(hit.geometry).kind, SurfaceRef::Kind::Mesh);
      ASSERT_EQ(hit.geometry, expected.mesh) << "ray " << i;
      ASSERT_EQ(hit.primitive, expected.primitive) << "ray " << i;
      EXPECT_NEAR(hit.u, truth.b1, 1e-4);
      EXPECT_NEAR(hit.v, truth.b2, 1e-4);
      // The documented normal: cross(p1 - p0, p2 - p0), unnormalised.
      const D3 ng = cross(expected.p1 - expected.p0, expected.p2 - expected.p0);
      EXPECT_LT(norm(D3(hit.geometricNormal) - ng), 1e-4 * norm(ng)) << "ray " << i;
      // Shadow segments: open just short of the hit, closed just past it.
      Ray shadow = ray;
      shadow.tMax = hit.t * (1 - 1e-3f);
      if (truth.t * (1 - 1e-3) > ray.tMin) {
        EXPECT_FALSE(accel.occluded(shadow)) << "ray " << i;
      }
      shadow.tMax = hit.t * (1 + 1e-3f);
      EXPECT_TRUE(accel.occluded(shadow)) << "ray " << i;
    }
  }
  EXPECT_GT(hits, 1500);
  EXPECT_LT(skipped, 50);
  EXPECT_LT(ties, 20);
}

// ---- Packets against single rays ----

// Inactive lanes hold whatever a caller left there: stale rays, NaN, infinities, empty
// intervals. Embree 3 without native 16-wide kernels (AVX2, SSE) ignores the valid mask, so
// each packet test runs on every kernel width this CPU can run: Embree's best, AVX2 (8 wide)
// and SSE4.2 (4 wide); each must give the single-ray answers lane by lane.
void scribble(RayPacket16& rays, int lane, uint32_t kind) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  switch (kind % 5) {
    case 0:
      rays.ox[lane] = nan;
      break;
    case 1:
      rays.dx[lane] = rays.dy[lane] = rays.dz[lane] = 0.0f;
      break;
    case 2:
      rays.oy[lane] = kInf, rays.dz[lane] = -kInf;
      break;
    case 3:
      rays.tMin[lane] = -1.0f, rays.tMax[lane] = nan;
      break;
    default:
      break;  // a stale but well-formed ray: still must not be traced
  }
}

class AcceleratorIsa : public ::testing::TestWithParam<const char*> {};

std::string kernelName(const ::testing::TestParamInfo<const char*>& param) {
  const std::string config = param.param;
  if (config.empty()) return "best";
  return config == "isa=sse4.2" ? "sse42" : config.substr(4);
}

INSTANTIATE_TEST_SUITE_P(Kernels, AcceleratorIsa, ::testing::Values("", "isa=avx2", "isa=sse4.2"),
                         kernelName);

// Every packet width (the ISA's own, and 4, 8 and 16 forced: a 16-ray packet split into 4 or
// 2 Embree queries) against single rays, lane by lane.
class AcceleratorPacketWidth : public ::testing::TestWithParam<std::tuple<const char*, int>> {};

INSTANTIATE_TEST_SUITE_P(Kernels, AcceleratorPacketWidth,
                         ::testing::Combine(::testing::Values("", "isa=avx2", "isa=sse4.2"),
                                            ::testing::Values(0, 4, 8, 16)),
                         [](const ::testing::TestParamInfo<std::tuple<const char*, int>>& param) {
                           const std::string config = std::get<0>(param.param);
                           const std::string isa = config.empty()           ? "best"
                                                   : config == "isa=sse4.2" ? "sse42"
                                                                            : config.substr(4);
                           return isa + "_width" + std::to_string(std::get<1>(param.param));
                         });

TEST_P(AcceleratorPacketWidth, PacketsAgreeWithSingleRaysLaneByLane) {
  Rng rng(15);
  std::vector<SoupTriangle> soup;
  Scene scene = randomSoup(rng, 500, soup);
  for (int i = 0; i < 6; ++i)
    scene.spheres.push_back({"s", 0, uniformBox(rng, -1.5f, 1.5f), uniform(rng, 0.1f, 0.4f)});
  AcceleratorOptions options;
  options.embreeConfig = std::string(std::get<0>(GetParam()));
  options.packetWidth = std::get<1>(GetParam());
  const Accelerator accel(scene, options);
  EXPECT_EQ(accel.packetWidth(), options.packetWidth != 0 ? options.packetWidth : 16);
  const int native = accel.nativePacketWidth();
  EXPECT_TRUE(native == 4 || native == 8 || native == 16) << native;
  // Kernels forced narrower report their own width (on a CPU that has them).
  if (std::string(std::get<0>(GetParam())) == "isa=sse4.2") {
    EXPECT_EQ(native, 4);
  }
  const int width = accel.packetWidth();
  EXPECT_TRUE(width == 4 || width == 8 || width == 16) << width;
  int activeLanes = 0, hitLanes = 0, occludedLanes = 0;
  for (int p = 0; p < 400; ++p) {
    RayPacket16 rays;
    for (int lane = 0; lane < 16; ++lane) {
      rays.set(lane, randomSoupRay(rng));
      if (rng.next() % 4 == 0) {
        rays.deactivate(lane);
        scribble(rays, lane, uint32_t(rng.next()));  // must be ignored
      }
    }
    HitPacket16 hits;
    bool occludedOut[16];
    accel.intersect16(rays, hits);
    accel.occluded16(rays, occludedOut);
    for (int lane = 0; lane < 16; ++lane) {
      if (!rays.active[lane]) {
        EXPECT_FALSE(hits.hit(lane).valid());
        EXPECT_FALSE(occludedOut[lane]);
        continue;
      }
      ++activeLanes;
      const Ray ray = rays.ray(lane);
      const Hit single = accel.intersect(ray), packet = hits.hit(lane);
      ASSERT_EQ(packet.valid(), single.valid()) << "packet " << p << " lane " << lane;
      EXPECT_EQ(occludedOut[lane], accel.occluded(ray)) << "packet " << p << " lane " << lane;
      occludedLanes += occludedOut[lane];
      if (!single.valid()) continue;
      ++hitLanes;
      EXPECT_EQ(packet.geometry, single.geometry);
      EXPECT_EQ(packet.primitive, single.primitive);
      EXPECT_NEAR(packet.t, single.t, 1e-5f * single.t);
      EXPECT_NEAR(packet.u, single.u, 1e-4f);
      EXPECT_NEAR(packet.v, single.v, 1e-4f);
      EXPECT_LT(length(packet.geometricNormal - single.geometricNormal),
                1e-4f * length(single.geometricNormal));
    }
  }
  EXPECT_GT(activeLanes, 4000);
  EXPECT_GT(hitLanes, 1000);
  EXPECT_EQ(occludedLanes, hitLanes);
}

// Active lanes Embree cannot trace (NaN, huge or zero directions, tMin > tMax, tMin < 0) read
// as misses and are never occluded, in packets and single rays alike, on every kernel width;
// their neighbours are traced as usual.
TEST_P(AcceleratorIsa, UntraceableActiveLanesMiss) {
  Scene scene;
  scene.spheres.push_back({"s", 0, {0, 0, 0}, 1.0f});
  const Accelerator accel(scene, std::string(GetParam()));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const Ray good{{0, 0, 5}, {0, 0, -1}};
  std::vector<Ray> bad(8, good);
  bad[0].origin.x = nan;
  bad[1].direction = {0, 0, 0};
  bad[2].direction.z = -kInf;
  bad[3].origin.z = 1e30f;
  bad[4].tMin = 3.0f, bad[4].tMax = 2.0f;
  bad[5].tMin = -1.0f;
  bad[6].tMax = nan;
  bad[7].direction.y = 1e19f;
  RayPacket16 rays;
  for (int lane = 0; lane < 16; ++lane) rays.set(lane, lane % 2 ? bad[size_t(lane / 2)] : good);
  HitPacket16 hits;
  bool occludedOut[16];
  accel.intersect16(rays, hits);
  accel.occluded16(rays, occludedOut);
  for (int lane = 0; lane < 16; ++lane) {
    const bool traceable = lane % 2 == 0;
    EXPECT_EQ(hits.hit(lane).valid(), traceable) << "lane " << lane;
    EXPECT_EQ(occludedOut[lane], traceable) << "lane " << lane;
    EXPECT_EQ(accel.intersect(rays.ray(lane)).valid(), traceable) << "lane " << lane;
    EXPECT_EQ(accel.occluded(rays.ray(lane)), traceable) << "lane " << lane;
    if (traceable) {
      EXPECT_NEAR(hits.t[lane], 4.0f, 1e-5f);
    }
  }
}

// The Embree that runs (its device's answer) is the one the build compiled against.
TEST(AcceleratorLibrary, ReportsTheEmbreeTheBuildCompiledAgainst) {
  const EmbreeLibrary& library = embreeLibrary();
  EXPECT_EQ(library.major, PARALLAX_EMBREE_MAJOR);
  EXPECT_EQ(library.major, RTC_VERSION_MAJOR);
  EXPECT_EQ(library.minor, RTC_VERSION_MINOR);
  EXPECT_EQ(library.patch, RTC_VERSION_PATCH);
  EXPECT_EQ(library.name(), std::string("Embree ") + RTC_VERSION_STRING);
  EXPECT_EQ(&embreeLibrary(), &library);  // asked once
}

TEST(AcceleratorConfig, RefusedConfigurationIsAnInputErrorNamingIt) {
  const Scene scene;
  for (const std::string config : {"isa=nonsense", "threads=abc", "isa=", "isa=avx512skx"}) {
    try {
      const Accelerator accel(scene, config);
      ADD_FAILURE() << "accepted " << config;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("Embree"), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(Accelerator(scene, std::string("isa=sse4.2,verbose=0")));
}

// ---- Geometry IDs, empty scenes and bad meshes ----

TEST(AcceleratorSurface, MapsGeometryIdsBackToMeshesAndSpheres) {
  Scene scene;
  addQuad(scene, "a", {-10, -1, -1}, {0, 2, 0}, {0, 0, 2}, 0);  // the plane x = -10
  scene.meshes.push_back({});                                   // an empty mesh keeps its ID
  addBox(scene, "b", {9, -1, -1}, {11, 1, 1}, 0);
  // Three unit spheres at distances 10, 20 and 30 in different directions.
  scene.spheres.push_back({"s", 0, {0, 10, 0}, 1});
  scene.spheres.push_back({"s", 0, {0, -20, 0}, 1});
  scene.spheres.push_back({"s", 0, {0, 0, -30}, 1});
  const Accelerator accel(scene);

  const auto aimAt = [&](const Vec3f& target) {
    return accel.intersect({{0, 0, 0}, target, 0.0f, kInf});
  };
  Hit hit = aimAt({-1, 0, 0});
  ASSERT_TRUE(hit.valid());
  EXPECT_EQ(accel.surface(hit.geometry).kind, SurfaceRef::Kind::Mesh);
  EXPECT_EQ(accel.surface(hit.geometry).index, 0u);
  EXPECT_NEAR(hit.t, 10.0f, 1e-5f);
  hit = aimAt({1, 0, 0});
  ASSERT_TRUE(hit.valid());
  EXPECT_EQ(accel.surface(hit.geometry).kind, SurfaceRef::Kind::Mesh);
  EXPECT_EQ(accel.surface(hit.geometry).index, 2u);
  EXPECT_NEAR(hit.t, 9.0f, 1e-5f);
  for (uint32_t i = 0; i < 3; ++i) {
    hit = aimAt(scene.spheres[i].center);
    ASSERT_TRUE(hit.valid());
    EXPECT_EQ(accel.surface(hit.geometry).kind, SurfaceRef::Kind::Sphere);
    EXPECT_EQ(accel.surface(hit.geometry).index, i);
    EXPECT_NEAR(hit.t, 1.0f - 1.0f / (10.0f * float(i + 1)), 1e-5f);  // aimed at the centre
  }
  EXPECT_FALSE(aimAt({0, 0, 1}).valid());
  EXPECT_EQ(accel.surface(1).kind, SurfaceRef::Kind::Mesh);
  EXPECT_THROW(accel.surface(6), std::out_of_range);
  EXPECT_THROW(accel.surface(kNoHit), std::out_of_range);
}

TEST(AcceleratorEmpty, EverythingMisses) {
  const Scene scene;
  const Accelerator accel(scene);
  Rng rng(16);
  RayPacket16 rays;
  for (int lane = 0; lane < 16; ++lane) rays.set(lane, {uniformBox(rng, -1, 1), {0, 0, 1}});
  for (int lane = 0; lane < 16; ++lane) {
    EXPECT_FALSE(accel.intersect(rays.ray(lane)).valid());
    EXPECT_FALSE(accel.occluded(rays.ray(lane)));
  }
  HitPacket16 hits;
  bool occludedOut[16];
  accel.intersect16(rays, hits);
  accel.occluded16(rays, occludedOut);
  for (int lane = 0; lane < 16; ++lane) {
    EXPECT_FALSE(hits.hit(lane).valid());
    EXPECT_FALSE(occludedOut[lane]);
  }
  // Primary rays only: nothing is hit, so no shadow rays.
  const PinholeGrid grid{{0, 0, 0}, {-1, 1, -1}, {0.1f, 0, 0}, {0, -0.1f, 0}, 10, 7, 4};
  const RawTraceCount count = accel.traceRawLimit(grid, 0, 7, {0, 5, 0});
  EXPECT_EQ(count.rays, 10u * 7u * 4u);
  EXPECT_EQ(count.primaryMisses, count.primaryRays);
  EXPECT_THROW(accel.surface(0), std::out_of_range);
}

TEST(AcceleratorErrors, RejectsMalformedMeshes) {
  Scene outOfRange;
  addQuad(outOfRange, "q", {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
  outOfRange.meshes[0].indices[4] = 4;
  EXPECT_THROW(Accelerator{outOfRange}, std::runtime_error);
  Scene ragged;
  addQuad(ragged, "q", {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
  ragged.meshes[0].indices.pop_back();
  EXPECT_THROW(Accelerator{ragged}, std::runtime_error);
}

// ---- The raw-limit benchmark loop ----

// Rays the documented PinholeGrid formula produces for rows [rowBegin, rowEnd), counted with
// the single-ray path: every primary ray, plus one shadow ray per primary hit.
RawTraceCount expectedRawRays(const Accelerator& accel, const PinholeGrid& grid, int rowBegin,
                              int rowEnd) {
  int n = 1;
  while ((n + 1) * (n + 1) <= grid.samplesPerPixel) ++n;
  RawTraceCount count;
  for (int y = std::max(rowBegin, 0); y < std::min(rowEnd, grid.height); ++y)
    for (int x = 0; x < grid.width; ++x)
      for (int sy = 0; sy < n; ++sy)
        for (int sx = 0; sx < n; ++sx) {
          const float jx = (float(sx) + 0.5f) / float(n), jy = (float(sy) + 0.5f) / float(n);
          const Vec3f target =
              grid.pixel00 + (float(x) + jx) * grid.pixelDx + (float(y) + jy) * grid.pixelDy;
          const bool hit = accel.intersect({grid.eye, target - grid.eye}).valid();
          count.rays += 1 + hit;
          count.primaryRays += 1;
          count.primaryMisses += !hit;
        }
  return count;
}

void expectSameCount(const RawTraceCount& traced, const RawTraceCount& expected,
                     const std::string& what) {
  EXPECT_EQ(traced.rays, expected.rays) << what;
  EXPECT_EQ(traced.primaryRays, expected.primaryRays) << what;
  EXPECT_EQ(traced.primaryMisses, expected.primaryMisses) << what;
}

TEST_P(AcceleratorIsa, RawLimitCountsPrimaryRaysAndOneShadowRayPerHit) {
  Scene scene;
  addQuad(scene, "floor", {-5, -1, 5}, {10, 0, 0}, {0, 0, -10}, 0);
  addBox(scene, "box", {-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}, 0);
  scene.spheres.push_back({"ball", 0, {1.2f, 0.0f, 0.3f}, 0.6f});
  const Accelerator accel(scene, std::string(GetParam()));
  // 37 x 23 pixels: partial 4x4 blocks on the right and at the bottom.
  const PinholeGrid grid{{0, 1, 6}, {-1.5f, 1.4f, 4}, {3.0f / 37, 0, 0}, {0, -2.0f / 23, 0}, 37, 23,
                         5};
  for (const auto& [begin, end] : {std::pair{0, 23}, {5, 19}, {20, 40}, {-3, 2}}) {
    expectSameCount(accel.traceRawLimit(grid, begin, end, {-2, 4, 3}),
                    expectedRawRays(accel, grid, begin, end),
                    "rows " + std::to_string(begin) + ".." + std::to_string(end));
  }
  const RawTraceCount all = expectedRawRays(accel, grid, 0, 23);
  EXPECT_GT(all.rays, uint64_t(37 * 23 * 4 * 3 / 2)) << "most rays hit";
  EXPECT_GT(all.primaryMisses, 0u) << "some miss";
  PinholeGrid nine = grid;
  nine.samplesPerPixel = 9;
  expectSameCount(accel.traceRawLimit(nine, 3, 11, {-2, 4, 3}), expectedRawRays(accel, nine, 3, 11),
                  "9 spp");
  EXPECT_EQ(accel.traceRawLimit(grid, 10, 10, {-2, 4, 3}).rays, 0u);
}

// A packet log holds every packet query made on its thread while open, as handed over, and
// closes back to the log outside it; replaying it counts the same lanes and finds the same
// misses as the queries did.
TEST(AcceleratorPacketLog, RecordsEachQueryAndReplaysThem) {
  Scene scene;
  addBox(scene, "box", {-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}, 0);
  const Accelerator accel(scene);
  RayPacket16 rays{};
  int misses = 0;
  for (int lane = 0; lane < 16; ++lane) {
    // Lanes 0..9 aim at the box from +z, 10..13 pass beside it, 14 and 15 are inactive.
    const float x = lane < 10 ? -0.4f + 0.08f * float(lane) : 2.0f + float(lane);
    rays.set(lane, {{x, 0.1f, 5.0f}, {0, 0, -1}});
    misses += lane >= 10 && lane < 14;
  }
  rays.deactivate(14), rays.deactivate(15);
  PacketLog outer, inner;
  HitPacket16 hits;
  bool occluded[16];
  {
    const ScopedPacketLog openOuter(outer);
    accel.intersect16(rays, hits);
    {
      const ScopedPacketLog openInner(inner);
      accel.occluded16(rays, occluded);
      accel.occluded16(rays, occluded);
    }
    accel.intersect16(rays, hits);
  }
  accel.intersect16(rays, hits);  // no log open: recorded nowhere
  ASSERT_EQ(outer.closest.size(), 2u);
  EXPECT_EQ(outer.shadow.size(), 0u);
  EXPECT_EQ(inner.closest.size(), 0u);
  ASSERT_EQ(inner.shadow.size(), 2u);
  for (int lane = 0; lane < 16; ++lane) {
    EXPECT_EQ(outer.closest[1].ox[lane], rays.ox[lane]);
    EXPECT_EQ(inner.shadow[0].active[lane], rays.active[lane]);
  }
  const RawTraceCount closest = accel.replay(outer);
  EXPECT_EQ(closest.rays, 2u * 14u);
  EXPECT_EQ(closest.primaryRays, 2u * 14u);
  EXPECT_EQ(closest.primaryMisses, 2u * uint64_t(misses));
  int found = 0;
  for (int lane = 0; lane < 14; ++lane) found += hits.geometry[lane] == kNoHit;
  EXPECT_EQ(found, misses);
  const RawTraceCount shadow = accel.replay(inner);
  EXPECT_EQ(shadow.rays, 2u * 14u);
  EXPECT_EQ(shadow.primaryRays, 0u);
}

// Auto builds High only when enough rays meet each triangle; both qualities find the same
// first hits.
TEST(AcceleratorQuality, ChosenByRaysPerTriangleAndInvisibleInTheHits) {
  Rng rng(23);
  std::vector<SoupTriangle> soup;
  const Scene scene = randomSoup(rng, 400, soup);
  const double triangles = double(scene.triangleCount());
  const auto built = [&](BuildQuality quality, double rays) {
    AcceleratorOptions options;
    options.quality = quality;
    options.expectedRays = rays;
    return Accelerator(scene, options).buildQuality();
  };
  EXPECT_EQ(built(BuildQuality::Auto, 0.0), BuildQuality::High);  // unknown: the safe default
  EXPECT_EQ(built(BuildQuality::Auto, kHighQualityRaysPerTriangle * triangles), BuildQuality::High);
  EXPECT_EQ(built(BuildQuality::Auto, 0.5 * kHighQualityRaysPerTriangle * triangles),
            BuildQuality::Medium);
  EXPECT_EQ(built(BuildQuality::Medium, 1e12), BuildQuality::Medium);
  EXPECT_EQ(built(BuildQuality::High, 1.0), BuildQuality::High);

  AcceleratorOptions medium, high;
  medium.quality = BuildQuality::Medium;
  high.quality = BuildQuality::High;
  const Accelerator a(scene, medium), b(scene, high);
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    const Ray ray = randomSoupRay(rng);
    const Hit x = a.intersect(ray), y = b.intersect(ray);
    ASSERT_EQ(x.valid(), y.valid()) << i;
    if (!x.valid()) continue;
    ++hits;
    EXPECT_EQ(x.primitive, y.primitive) << i;
    EXPECT_FLOAT_EQ(x.t, y.t) << i;
  }
  EXPECT_GT(hits, 500);
}

TEST(AcceleratorOptionsCheck, RefusesAnUnknownPacketWidth) {
  Scene scene;
  addQuad(scene, "q", {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
  AcceleratorOptions options;
  options.packetWidth = 12;
  EXPECT_THROW(Accelerator(scene, options), InputError);
}

TEST(AcceleratorThreads, ConcurrentQueriesMatchSerialOnes) {
  Rng rng(17);
  std::vector<SoupTriangle> soup;
  const Scene scene = randomSoup(rng, 300, soup);
  const Accelerator accel(scene);
  std::vector<Ray> rays;
  for (int i = 0; i < 2000; ++i) rays.push_back(randomSoupRay(rng));
  std::vector<float> serial;
  for (const Ray& ray : rays) serial.push_back(accel.intersect(ray).t);
  std::vector<float> results[2];
  std::vector<std::thread> threads;
  for (auto& out : results)
    threads.emplace_back([&] {
      for (const Ray& ray : rays) out.push_back(accel.intersect(ray).t);
    });
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(results[0], serial);
  EXPECT_EQ(results[1], serial);
}

}  // namespace
}  // namespace parallax

namespace parallax {
namespace {

// A refitted BVH answers like one built from scratch on the moved geometry (a second code
// path): every vertex of a random soup and a sphere's centre move, then rays are compared.
class AcceleratorRefit : public ::testing::TestWithParam<bool> {};

TEST_P(AcceleratorRefit, AnswersLikeAFreshBuildOfTheMovedScene) {
  const bool dynamic = GetParam();
  Rng rng(21);
  std::vector<SoupTriangle> soup;
  Scene scene = randomSoup(rng, 1500, soup);
  scene.spheres.push_back({"ball", 0, Vec3f(0.2f, -0.1f, 0.3f), 0.35f});
  AcceleratorOptions options;
  options.dynamic = dynamic;
  Accelerator refitted(scene, options);
  for (int frame = 0; frame < 3; ++frame) {
    for (TriangleMesh& mesh : scene.meshes)
      for (Vec3f& p : mesh.positions) p = p + uniformBox(rng, -0.3f, 0.3f);
    scene.spheres[0].center = uniformBox(rng, -0.8f, 0.8f);
    refitted.refit(scene);
    const Accelerator fresh(scene);
    int hits = 0;
    for (int i = 0; i < 3000; ++i) {
      const Ray ray = randomSoupRay(rng);
      const Hit a = refitted.intersect(ray), b = fresh.intersect(ray);
      ASSERT_EQ(a.valid(), b.valid()) << "frame " << frame << " ray " << i;
      ASSERT_EQ(refitted.occluded(ray), fresh.occluded(ray)) << "frame " << frame << " ray " << i;
      if (!a.valid()) continue;
      ++hits;
      EXPECT_NEAR(a.t, b.t, 1e-5f * (1.0f + b.t)) << "frame " << frame << " ray " << i;
      if (a.t != b.t) continue;  // two surfaces at one distance: either may be reported
      EXPECT_EQ(a.geometry, b.geometry);
      EXPECT_EQ(a.primitive, b.primitive);
    }
    EXPECT_GT(hits, 1000);
  }
}

INSTANTIATE_TEST_SUITE_P(BothBuilds, AcceleratorRefit, ::testing::Bool(),
                         [](const auto& param) { return param.param ? "Dynamic" : "Static"; });

TEST(AcceleratorRefitErrors, RefusesAnotherTopology) {
  Rng rng(3);
  std::vector<SoupTriangle> soup;
  Scene scene = randomSoup(rng, 30, soup);
  AcceleratorOptions options;
  options.dynamic = true;
  Accelerator accel(scene, options);
  Scene fewer = scene;
  fewer.meshes[0].positions.pop_back();
  EXPECT_THROW(accel.refit(fewer), std::invalid_argument);
  Scene more = scene;
  more.spheres.push_back({"ball", 0, Vec3f(0.0f), 1.0f});
  EXPECT_THROW(accel.refit(more), std::invalid_argument);
  EXPECT_NO_THROW(accel.refit(scene));
}

}  // namespace
}  // namespace parallax
