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
#include <vector>

#include "parallax/accel/embree_internal.h"
#include "parallax/core/parallel.h"

namespace parallax {

namespace {

// Whether hit (ta, ga) comes before (tb, gb) along the ray.
inline bool before(float ta, uint32_t ga, float tb, uint32_t gb) {
  return ta < tb || (ta == tb && ga < gb);
}

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
  const double inverse[3][3] = {{c00 / det, (w[0][2] * w[2][1] - w[0][1] * w[2][2]) / det,
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

// A packet's query: the same for sixteen rays, each with its own interval, cursor and buffer.
struct SplatQuery16 {
#if PARALLAX_EMBREE_MAJOR == 4
  RTCRayQueryContext context;
#else
  RTCIntersectContext context;
#endif
  const SplatStore* store = nullptr;
  const RayPacket16* rays = nullptr;
  float tMin[16] = {}, tMax[16] = {};
  const SplatCursor* after = nullptr;
  SplatHit* hits = nullptr;  // capacity a lane
  int capacity = 0;
  int* count = nullptr;
  uint64_t evaluated = 0;
};

// Offers one Gaussian to every valid ray of the packet Embree hands over. The responses are
// computed for all lanes in one loop (vectorised); the few that are seen are then offered to
// their lane's buffer one by one. Embree may hand over the packet whole or in parts: a ray's
// lane is found from its id, which fillRays set to the lane.
PARALLAX_LANE_KERNEL void splatIntersect16(const RTCIntersectFunctionNArguments* args) {
  auto& query = *reinterpret_cast<SplatQuery16*>(args->context);
  const uint32_t gaussian = args->primID;
  const SplatStore& store = *query.store;
  const GaussianFrame& f = store.frames[gaussian];
  const float reach = store.reachSquared[gaussian];
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  const RayPacket16& packet = *query.rays;
  const unsigned n = args->N;
  alignas(64) float t[16], q[16];
  alignas(64) int lanes[16];
  for (unsigned i = 0; i < n && i < 16; ++i) lanes[i] = int(RTCRayN_id(rays, n, i)) & 15;
  const unsigned width = n < 16 ? n : 16;
  PARALLAX_SIMD
  for (unsigned i = 0; i < width; ++i) {
    const int lane = lanes[i];
    const float ox = packet.ox[lane] - f.centre.x, oy = packet.oy[lane] - f.centre.y,
                oz = packet.oz[lane] - f.centre.z;
    const float dx = packet.dx[lane], dy = packet.dy[lane], dz = packet.dz[lane];
    const float l0 = f.whiten[0].x * ox + f.whiten[0].y * oy + f.whiten[0].z * oz;
    const float l1 = f.whiten[1].x * ox + f.whiten[1].y * oy + f.whiten[1].z * oz;
    const float l2 = f.whiten[2].x * ox + f.whiten[2].y * oy + f.whiten[2].z * oz;
    const float w0 = f.whiten[0].x * dx + f.whiten[0].y * dy + f.whiten[0].z * dz;
    const float w1 = f.whiten[1].x * dx + f.whiten[1].y * dy + f.whiten[1].z * dz;
    const float w2 = f.whiten[2].x * dx + f.whiten[2].y * dy + f.whiten[2].z * dz;
    const float along = -(l0 * w0 + l1 * w1 + l2 * w2) / (w0 * w0 + w1 * w1 + w2 * w2);
    const float c0 = l0 + w0 * along, c1 = l1 + w1 * along, c2 = l2 + w2 * along;
    t[i] = along;
    q[i] = c0 * c0 + c1 * c1 + c2 * c2;
  }
  const int last = query.capacity - 1;
  for (unsigned i = 0; i < width; ++i) {
    if (!args->valid[i]) continue;
    ++query.evaluated;
    const int lane = lanes[i];
    const float ti = t[i];
    if (!(ti >= query.tMin[lane]) || !(ti < query.tMax[lane]) || !(q[i] <= reach)) continue;
    const SplatCursor& after = query.after[lane];
    if (after.started && !before(after.t, after.gaussian, ti, gaussian)) continue;
    SplatHit* hits = query.hits + size_t(lane) * size_t(query.capacity);
    int& count = query.count[lane];
    if (count == query.capacity && !before(ti, gaussian, hits[last].t, hits[last].gaussian))
      continue;
    const float alpha = RayResponse{ti, q[i]}.alpha(store.opacities[gaussian]);
    if (!(alpha >= kMinSplatAlpha)) continue;
    int at = count < query.capacity ? count++ : last;
    for (; at > 0 && before(ti, gaussian, hits[at - 1].t, hits[at - 1].gaussian); --at)
      hits[at] = hits[at - 1];
    hits[at] = {ti, gaussian, alpha};
    if (count == query.capacity) RTCRayN_tfar(rays, n, i) = hits[last].t;
  }
}

// The splat scene is only ever asked for closest hits; an occlusion query finds nothing.
void splatOccluded(const RTCOccludedFunctionNArguments*) {}

}  // namespace

namespace {

// Every Gaussian's frame in the world, opacity and reach, in scene order, on every core.
void placeSplats(const Scene& scene, SplatStore& store) {
  size_t first = 0;
  for (const SplatSet& set : scene.splats) {
    parallelFor(int64_t(set.cloud.size()), 0, 16384, [&](int64_t begin, int64_t end) {
      for (int64_t g = begin; g < end; ++g) {
        const size_t at = first + size_t(g);
        store.frames[at] = gaussianFrame(set.cloud, size_t(g), set.worldFromFile);
        store.opacities[at] = set.cloud.opacities[size_t(g)];
        const float reach = boundingRadius(set.cloud.opacities[size_t(g)]);
        // A little beyond the bound, so that rounding leaves the exact test to alpha itself.
        store.reachSquared[at] = reach * reach * 1.0001f + 1e-6f;
      }
    });
    first += set.cloud.size();
  }
}

}  // namespace

void rebuildSplatStore(const Scene& scene, SplatStore& store) {
  placeSplats(scene, store);
  RTCGeometry geometry = rtcGetGeometry(store.scene, 0);
  rtcCommitGeometry(geometry);
  rtcCommitScene(store.scene);
}

void buildSplatStore(RTCDevice device, const Scene& scene, SplatStore& store) {
  const size_t count = scene.splatCount();
  if (count == 0) return;
  if (count >= size_t(std::numeric_limits<uint32_t>::max()))
    throw std::runtime_error("Embree: too many Gaussian splats (" + std::to_string(count) + ")");
  store.frames.resize(count);
  store.opacities.resize(count);
  store.reachSquared.resize(count);
  placeSplats(scene, store);
  store.scene = rtcNewScene(device);
  if (!store.scene) return;  // the caller reads the device's error
  rtcSetSceneFlags(store.scene, RTC_SCENE_FLAG_COMPACT);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  if (!geometry) return;
  rtcSetGeometryUserPrimitiveCount(geometry, unsigned(count));
  rtcSetGeometryUserData(geometry, &store);
  rtcSetGeometryBoundsFunction(geometry, splatBounds, nullptr);
  rtcSetGeometryIntersectFunction(geometry, splatIntersect16);
  rtcSetGeometryOccludedFunction(geometry, splatOccluded);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(store.scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(store.scene);
}

void walkSplats16(const SplatStore& store, const RayPacket16& rays, const SplatCursor after[16],
                  SplatHit* out, int capacity, int counts[16], uint64_t* evaluated) {
  for (int lane = 0; lane < 16; ++lane) counts[lane] = 0;
  if (!store.scene || capacity <= 0) return;
  SplatQuery16 query;
  query.store = &store;
  query.rays = &rays;
  query.after = after;
  query.hits = out;
  query.capacity = capacity;
  query.count = counts;
  alignas(64) RTCRayHit16 rayHit;
  fillRays(rays, rayHit.ray);
  alignas(64) int valid[16];
  for (int lane = 0; lane < 16; ++lane) {
    query.tMin[lane] =
        std::max(rays.tMin[lane], after[lane].started ? after[lane].t : rays.tMin[lane]);
    query.tMax[lane] = rays.tMax[lane];
    rayHit.ray.tnear[lane] = query.tMin[lane];
    rayHit.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
    valid[lane] = rays.active[lane] ? -1 : 0;
  }
  if (guardPacket(rayHit.ray, valid) == 0) return;
#if PARALLAX_EMBREE_MAJOR == 4
  rtcInitRayQueryContext(&query.context);
  RTCIntersectArguments arguments;
  rtcInitIntersectArguments(&arguments);
  arguments.context = &query.context;
  arguments.intersect = nullptr;
  rtcIntersect16(valid, store.scene, &rayHit, &arguments);
#else
  rtcInitIntersectContext(&query.context);
  rtcIntersect16(valid, store.scene, &query.context, &rayHit);
#endif
  if (evaluated) *evaluated += query.evaluated;
}

}  // namespace parallax
