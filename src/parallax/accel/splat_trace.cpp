// Gaussian splats in Embree (docs/splats.md, "Tracing"): 3DGRT's approach on a CPU. Every
// Gaussian is one primitive of a user geometry, bounded by the box of its ellipsoid at alpha
// kMinSplatAlpha (boundingRadius); a query walks the BVH once and keeps, in a buffer of the
// caller's size, the nearest Gaussians by the depth where their response peaks (the k-buffer).
// Once the buffer is full the ray's far end is pulled in to its last entry, so Embree skips
// every box that lies wholly beyond it: a box holds the point where its Gaussian peaks whenever
// that Gaussian is seen at all (its alpha there reaches kMinSplatAlpha only inside the
// ellipsoid), so nothing the buffer would keep is skipped. The buffer's contents are the
// nearest k by (t, index) whatever order Embree visits the leaves in: deterministic.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "parallax/accel/embree_backend.h"

namespace parallax {

namespace {

// Whether hit (ta, ga) comes before (tb, gb) along the ray.
inline bool before(float ta, uint32_t ga, float tb, uint32_t gb) {
  return ta < tb || (ta == tb && ga < gb);
}

// What one query carries into Embree's callbacks. Embree hands the callbacks the address of
// the context it was given, which is this struct's first member (Embree's documented way to
// pass per-query data: RTCIntersectContext in Embree 3, RTCRayQueryContext in Embree 4).
struct SplatQuery {
#if PARALLAX_EMBREE_MAJOR == 4
  RTCRayQueryContext context;
#else
  RTCIntersectContext context;
#endif
  const SplatStore* store = nullptr;
  Vec3f origin, direction;  // the ray's, kept here rather than read back from Embree's
  SplatCursor after;
  float tMin = 0.0f, tMax = 0.0f;  // [tMin, tMax): the caller's interval
  SplatHit* hits = nullptr;
  int capacity = 0;
  int count = 0;
  uint64_t evaluated = 0;
};

// The box of Gaussian g's ellipsoid |W (x - c)| <= r: x = c + W^-1 u with |u| <= r reaches
// r |row a of W^-1| along world axis a. Padded a little, so that rounding in Embree's box test
// never drops a Gaussian whose peak lies on the box's face.
void splatBounds(const RTCBoundsFunctionArguments* args) {
  const auto& store = *static_cast<const SplatStore*>(args->geometryUserPtr);
  const GaussianFrame& frame = store.frames[args->primID];
  const float radius = boundingRadius(store.opacities[args->primID]);
  RTCBounds& box = *args->bounds_o;
  if (!(radius > 0.0f)) {  // never reaches kMinSplatAlpha: an empty box, which Embree drops
    box.lower_x = box.lower_y = box.lower_z = 1.0f;
    box.upper_x = box.upper_y = box.upper_z = 0.0f;
    return;
  }
  double w[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) w[r][c] = frame.whiten[r][c];
  // The inverse by cofactors: inverse[a][b] = cofactor(b, a) / det.
  const double c00 = w[1][1] * w[2][2] - w[1][2] * w[2][1];
  const double c01 = w[1][2] * w[2][0] - w[1][0] * w[2][2];
  const double c02 = w[1][0] * w[2][1] - w[1][1] * w[2][0];
  const double det = w[0][0] * c00 + w[0][1] * c01 + w[0][2] * c02;
  const double inverse[3][3] = {
      {c00 / det, (w[0][2] * w[2][1] - w[0][1] * w[2][2]) / det,
       (w[0][1] * w[1][2] - w[0][2] * w[1][1]) / det},
      {c01 / det, (w[0][0] * w[2][2] - w[0][2] * w[2][0]) / det,
       (w[0][2] * w[1][0] - w[0][0] * w[1][2]) / det},
      {c02 / det, (w[0][1] * w[2][0] - w[0][0] * w[2][1]) / det,
       (w[0][0] * w[1][1] - w[0][1] * w[1][0]) / det}};
  float half[3];
  for (int a = 0; a < 3; ++a) {
    const double extent = std::sqrt(inverse[a][0] * inverse[a][0] + inverse[a][1] * inverse[a][1] +
                                    inverse[a][2] * inverse[a][2]);
    const double pad = 1e-5 * extent + 1e-6 * (1.0 + std::abs(double(frame.centre[a])));
    half[a] = float(double(radius) * extent + pad);
  }
  box.lower_x = frame.centre.x - half[0], box.upper_x = frame.centre.x + half[0];
  box.lower_y = frame.centre.y - half[1], box.upper_y = frame.centre.y + half[1];
  box.lower_z = frame.centre.z - half[2], box.upper_z = frame.centre.z + half[2];
}

// Offers Gaussian primID to the query's buffer; never reports a hit to Embree, only pulls the
// ray's far end in once the buffer is full.
void splatIntersect(const RTCIntersectFunctionNArguments* args) {
  // Queries are single rays (rtcIntersect1): N is 1, and the ray is the query's own.
  if (!args->valid[0]) return;
  auto& query = *reinterpret_cast<SplatQuery*>(args->context);
  const uint32_t gaussian = args->primID;
  const SplatStore& store = *query.store;
  {
    const RayResponse response =
        gaussianRayResponse(store.frames[gaussian], query.origin, query.direction);
    ++query.evaluated;
    const float t = response.t;
    if (!(t >= query.tMin) || !(t < query.tMax)) return;
    if (!(response.distanceSquared <= store.reachSquared[gaussian])) return;
    if (query.after.started && !before(query.after.t, query.after.gaussian, t, gaussian)) return;
    const int last = query.capacity - 1;
    if (query.count == query.capacity &&
        !before(t, gaussian, query.hits[last].t, query.hits[last].gaussian))
      return;
    const float alpha = response.alpha(store.opacities[gaussian]);
    if (!(alpha >= kMinSplatAlpha)) return;
    int at = query.count < query.capacity ? query.count++ : last;
    for (; at > 0 && before(t, gaussian, query.hits[at - 1].t, query.hits[at - 1].gaussian); --at)
      query.hits[at] = query.hits[at - 1];
    query.hits[at] = {t, gaussian, alpha};
    if (query.count == query.capacity)
      RTCRayN_tfar(RTCRayHitN_RayN(args->rayhit, args->N), args->N, 0) = query.hits[last].t;
  }
}

// The splat scene is only ever asked for closest hits; an occlusion query finds nothing.
void splatOccluded(const RTCOccludedFunctionNArguments*) {}

}  // namespace

void buildSplatStore(RTCDevice device, const Scene& scene, SplatStore& store) {
  const size_t count = scene.splatCount();
  if (count == 0) return;
  if (count >= size_t(std::numeric_limits<uint32_t>::max()))
    throw std::runtime_error("Embree: too many Gaussian splats (" + std::to_string(count) + ")");
  store.frames.resize(count);
  store.opacities.resize(count);
  store.reachSquared.resize(count);
  size_t at = 0;
  for (const SplatSet& set : scene.splats)
    for (size_t g = 0; g < set.cloud.size(); ++g, ++at) {
      store.frames[at] = gaussianFrame(set.cloud, g, set.worldFromFile);
      store.opacities[at] = set.cloud.opacities[g];
      const float reach = boundingRadius(set.cloud.opacities[g]);
      // A little beyond the bound, so that rounding leaves the exact test to alpha itself.
      store.reachSquared[at] = reach * reach * 1.0001f + 1e-6f;
    }
  store.scene = rtcNewScene(device);
  if (!store.scene) return;  // the caller reads the device's error
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  if (!geometry) return;
  rtcSetGeometryUserPrimitiveCount(geometry, unsigned(count));
  rtcSetGeometryUserData(geometry, &store);
  rtcSetGeometryBoundsFunction(geometry, splatBounds, nullptr);
  rtcSetGeometryIntersectFunction(geometry, splatIntersect);
  rtcSetGeometryOccludedFunction(geometry, splatOccluded);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(store.scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(store.scene);
}

int Accelerator::nextSplats(const Ray& ray, const SplatCursor& after, SplatHit* out,
                            int capacity, uint64_t* evaluated) const {
  const SplatStore& store = impl_->splats;
  if (!store.scene || capacity <= 0) return 0;
  SplatQuery query;
  query.store = &store;
  query.origin = ray.origin;
  query.direction = ray.direction;
  query.after = after;
  query.tMin = std::max(ray.tMin, after.started ? after.t : ray.tMin);
  query.tMax = ray.tMax;
  query.hits = out;
  query.capacity = capacity;
  Ray bounded = ray;
  bounded.tMin = query.tMin;
  if (!traceable(bounded)) return 0;
  RTCRayHit rayHit;
  fillRay(bounded, rayHit.ray);
  rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
#if PARALLAX_EMBREE_MAJOR == 4
  rtcInitRayQueryContext(&query.context);
  RTCIntersectArguments arguments;
  rtcInitIntersectArguments(&arguments);
  arguments.context = &query.context;
  rtcIntersect1(store.scene, &rayHit, &arguments);
#else
  rtcInitIntersectContext(&query.context);
  rtcIntersect1(store.scene, &query.context, &rayHit);
#endif
  if (evaluated) *evaluated += query.evaluated;
  return query.count;
}

size_t Accelerator::splatCount() const {
  return impl_->splats.frames.size();
}

}  // namespace parallax
