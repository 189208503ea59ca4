// The Embree back end of Accelerator: scene construction, single-ray and 16-ray queries, and
// the raw-rate benchmark loop. This is the only file in parallax that includes Embree; it
// builds against Embree 3 (Debian 12) and Embree 4 (Debian 13 and later), whichever CMake
// found (PARALLAX_EMBREE_MAJOR); the two differ only in how a query is handed its flags
// (EmbreeQuery below).
#include "parallax/accel/accelerator.h"

#include "parallax/core/lane_kernel.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "parallax/accel/embree_internal.h"
#include "parallax/core/error.h"

namespace parallax {

namespace {

const char* errorName(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
    default:
      return "unknown error";
  }
}

}  // namespace

// Embree device configuration: defaults (all cores through Embree's TBB tasking, best ISA),
// unless PARALLAX_EMBREE_CONFIG holds one (Embree's own syntax, e.g. "isa=avx2" or
// "isa=sse4.2"), so that tests and benchmarks can run the kernels a narrower CPU would.
constexpr const char* kEmbreeConfigVariable = "PARALLAX_EMBREE_CONFIG";

// Embree quietly falls back to other kernels for an ISA name it does not know ("isa=avx-2",
// "isa=avx512skx": SSE2), so a test meant for some kernels would pass on others; the names it
// knows are checked here. Embree 3.13 and 4.3 take the same ones (each tried with verbose=1,
// which prints the kernels chosen; docs/install.md "Both Debian releases").
void checkIsaName(const std::string& config, const char* source) {
  static const char* const known[] = {"sse",    "sse2", "sse3", "ssse3", "sse4.1",
                                      "sse4.2", "avx",  "avxi", "avx2",  "avx512"};
  for (size_t at = config.find("isa"); at != std::string::npos; at = config.find("isa", at + 1)) {
    if (at > 0 && config[at - 1] != ',' && config[at - 1] != ' ') continue;  // e.g. max_isa
    size_t value = config.find_first_not_of(" =", at + 3);
    if (value == std::string::npos || config.compare(at + 3, 1, "=") != 0) continue;
    const std::string name = config.substr(value, config.find_first_of(", ", value) - value);
    if (std::find_if(std::begin(known), std::end(known),
                     [&](const char* k) { return name == k; }) == std::end(known))
      throw InputError(source, "",
                       "unknown Embree ISA '" + name + "'; use sse2, sse4.2, avx, avx2 or avx512");
  }
}

// Every ray query goes through one of these: the only place where Embree 3 and Embree 4 trace
// differently. Embree 3 hands every query an RTCIntersectContext whose flags say whether the
// rays are coherent; Embree 4 dropped the context from the call and takes
// RTCIntersectArguments (closest hits) and RTCOccludedArguments (any hit) instead, with the
// same flag as RTC_RAY_QUERY_FLAG_COHERENT. Neither has filter functions here. The geometry
// mask default also differs (Embree 3: all bits; Embree 4: 1), which changes nothing: every
// ray carries mask 0xffffffff, which meets either. (The splat walk, splat_trace.cpp, hands its
// user geometry a context of its own, the same way in both.)
class EmbreeQuery {
 public:
  enum class Rays { Incoherent, Coherent };
  explicit EmbreeQuery(Rays rays) {
#if PARALLAX_EMBREE_MAJOR == 4
    rtcInitIntersectArguments(&intersectArguments_);
    rtcInitOccludedArguments(&occludedArguments_);
    if (rays == Rays::Coherent)
      intersectArguments_.flags = occludedArguments_.flags = RTC_RAY_QUERY_FLAG_COHERENT;
#else
    rtcInitIntersectContext(&context_);
    if (rays == Rays::Coherent) context_.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
#endif
  }

#if PARALLAX_EMBREE_MAJOR == 4
  void intersect(RTCScene scene, RTCRayHit& rayHit) {
    rtcIntersect1(scene, &rayHit, &intersectArguments_);  // the arguments come last
  }
  void occluded(RTCScene scene, RTCRay& ray) {
    rtcOccluded1(scene, &ray, &occludedArguments_);  // tfar = -infinity when occluded
  }
  // A packet query, `query` being rtcIntersect4/8/16 or rtcOccluded4/8/16.
  template <class Packet, class Arguments>
  void packet(void (*query)(const int*, RTCScene, Packet*, Arguments*), const int* valid,
              RTCScene scene, Packet& rays) {
    if constexpr (std::is_same_v<Arguments, RTCIntersectArguments>)
      query(valid, scene, &rays, &intersectArguments_);
    else
      query(valid, scene, &rays, &occludedArguments_);
  }
#else
  void intersect(RTCScene scene, RTCRayHit& rayHit) {
    rtcIntersect1(scene, &context_, &rayHit);  // the context comes before the rays
  }
  void occluded(RTCScene scene, RTCRay& ray) {
    rtcOccluded1(scene, &context_, &ray);  // tfar = -infinity when occluded
  }
  template <class Packet>
  void packet(void (*query)(const int*, RTCScene, RTCIntersectContext*, Packet*), const int* valid,
              RTCScene scene, Packet& rays) {
    query(valid, scene, &context_, &rays);
  }
#endif

 private:
#if PARALLAX_EMBREE_MAJOR == 4
  RTCIntersectArguments intersectArguments_;
  RTCOccludedArguments occludedArguments_;
#else
  RTCIntersectContext context_;
#endif
};

struct Accelerator::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  uint32_t meshCount = 0;
  uint32_t sphereCount = 0;
  int packetWidth = 16, nativePacketWidth = 16;
  BuildQuality quality = BuildQuality::High;
  bool dynamic = false;
  // What refit() must find again: each mesh's vertex and index counts.
  std::vector<std::pair<size_t, size_t>> meshSizes;
  std::mutex errorMutex;
  std::string firstError;  // first message Embree reported through the error callback
  SplatStore splats;

  ~Impl();
  void throwIfError(const char* stage);

  // Embree calls this from whichever thread hit the error; keep the first message.
  static void recordError(void* userPtr, RTCError code, const char* message);
};

namespace {

void checkMesh(const TriangleMesh& mesh, size_t meshIndex) {
  const std::string where = "mesh " + std::to_string(meshIndex) + " '" + mesh.name + "': ";
  if (mesh.indices.size() % 3 != 0)
    throw std::runtime_error(where + "index count is not a multiple of 3");
  if (mesh.positions.size() > std::numeric_limits<uint32_t>::max())
    throw std::runtime_error(where + "too many vertices for 32-bit indices");
  // Embree does not check indices; an out-of-range one would read outside the vertex buffer.
  for (uint32_t index : mesh.indices)
    if (index >= mesh.positions.size())
      throw std::runtime_error(where + "vertex index " + std::to_string(index) + " out of range");
}

// Copies the mesh into Embree-owned buffers. rtcSetNewGeometryBuffer pads vertex buffers so
// that the last float3 can be read with a 16-byte load (Embree 3 API, rtcSetNewGeometryBuffer).
RTCGeometry newTriangleGeometry(RTCDevice device, const TriangleMesh& mesh) {
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (!geometry) return nullptr;
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                               RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                               mesh.positions.size()));
  auto* indices = static_cast<uint32_t*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(uint32_t), mesh.triangleCount()));
  if (vertices)
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      vertices[3 * i + 0] = mesh.positions[i].x;
      vertices[3 * i + 1] = mesh.positions[i].y;
      vertices[3 * i + 2] = mesh.positions[i].z;
    }
  if (indices && !mesh.indices.empty())
    std::memcpy(indices, mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t));
  return geometry;
}

// One sphere as a single RTC_GEOMETRY_TYPE_SPHERE_POINT primitive (x, y, z, radius).
RTCGeometry newSphereGeometry(RTCDevice device, const Sphere& sphere) {
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
  if (!geometry) return nullptr;
  auto* point = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
  if (point) {
    point[0] = sphere.center.x, point[1] = sphere.center.y, point[2] = sphere.center.z;
    point[3] = sphere.radius;
  }
  return geometry;
}

// A 16-ray packet traced as 16 / N queries of N rays (N = 4 or 8), each skipped when all its
// lanes are inactive: the packet width Embree runs natively on AVX2 (8) or SSE (4). `RayN`
// is RTCRay4/8 or RTCRayHit4/8; `copyIn` and `copyOut` move one lane between the two layouts.
template <int N, class PacketN, class CopyIn, class Trace, class CopyOut>
void traceInParts(const int valid[16], const CopyIn& copyIn, const Trace& trace,
                  const CopyOut& copyOut) {
  for (int base = 0; base < 16; base += N) {
    bool any = false;
    for (int i = 0; i < N; ++i) any |= valid[base + i] != 0;
    if (!any) continue;
    alignas(64) PacketN part;
    for (int i = 0; i < N; ++i) copyIn(part, i, base + i);
    trace(valid + base, part);
    for (int i = 0; i < N; ++i) copyOut(part, i, base + i);
  }
}

template <class RayN, class Ray16>
void copyRayLane(RayN& to, int t, const Ray16& from, int f) {
  to.org_x[t] = from.org_x[f], to.org_y[t] = from.org_y[f], to.org_z[t] = from.org_z[f];
  to.dir_x[t] = from.dir_x[f], to.dir_y[t] = from.dir_y[f], to.dir_z[t] = from.dir_z[f];
  to.tnear[t] = from.tnear[f], to.tfar[t] = from.tfar[f], to.time[t] = from.time[f];
  to.mask[t] = from.mask[f], to.id[t] = from.id[f], to.flags[t] = from.flags[f];
}

template <class HitN, class Hit16>
void copyHitLane(HitN& to, int t, const Hit16& from, int f) {
  to.Ng_x[t] = from.Ng_x[f], to.Ng_y[t] = from.Ng_y[f], to.Ng_z[t] = from.Ng_z[f];
  to.u[t] = from.u[f], to.v[t] = from.v[f];
  to.primID[t] = from.primID[f], to.geomID[t] = from.geomID[f];
  to.instID[0][t] = from.instID[0][f];
}

template <int N, class RayHitN, class Intersect>
void intersectInParts(const int valid[16], RTCRayHit16& rayHit, const Intersect& intersect) {
  traceInParts<N, RayHitN>(
      valid,
      [&](RayHitN& part, int i, int lane) {
        copyRayLane(part.ray, i, rayHit.ray, lane);
        copyHitLane(part.hit, i, rayHit.hit, lane);
      },
      intersect,
      [&](const RayHitN& part, int i, int lane) {
        rayHit.ray.tfar[lane] = part.ray.tfar[i];
        copyHitLane(rayHit.hit, lane, part.hit, i);
      });
}

template <int N, class RayN, class Occluded>
void occludedInParts(const int valid[16], RTCRay16& ray, const Occluded& occluded) {
  traceInParts<N, RayN>(
      valid, [&](RayN& part, int i, int lane) { copyRayLane(part, i, ray, lane); }, occluded,
      [&](const RayN& part, int i, int lane) { ray.tfar[lane] = part.tfar[i]; });
}

// rtcIntersect16 at the accelerator's packet width.
void intersectPacket(int width, const int valid[16], RTCScene scene, EmbreeQuery& query,
                     RTCRayHit16& rayHit) {
  if (width == 8)
    return intersectInParts<8, RTCRayHit8>(valid, rayHit, [&](const int* v, RTCRayHit8& part) {
      query.packet(rtcIntersect8, v, scene, part);
    });
  if (width == 4)
    return intersectInParts<4, RTCRayHit4>(valid, rayHit, [&](const int* v, RTCRayHit4& part) {
      query.packet(rtcIntersect4, v, scene, part);
    });
  query.packet(rtcIntersect16, valid, scene, rayHit);
}

// rtcOccluded16 at the accelerator's packet width.
void occludedPacket(int width, const int valid[16], RTCScene scene, EmbreeQuery& query,
                    RTCRay16& ray) {
  if (width == 8)
    return occludedInParts<8, RTCRay8>(valid, ray, [&](const int* v, RTCRay8& part) {
      query.packet(rtcOccluded8, v, scene, part);
    });
  if (width == 4)
    return occludedInParts<4, RTCRay4>(valid, ray, [&](const int* v, RTCRay4& part) {
      query.packet(rtcOccluded4, v, scene, part);
    });
  query.packet(rtcOccluded16, valid, scene, ray);
}

// The widest packet the device's kernels run natively.
int widestNativePacket(RTCDevice device) {
  if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) return 16;
  if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) return 8;
  return 4;
}

}  // namespace

std::string EmbreeLibrary::name() const {
  return "Embree " + std::to_string(major) + "." + std::to_string(minor) + "." +
         std::to_string(patch);
}

const EmbreeLibrary& embreeLibrary() {
  static const EmbreeLibrary library = [] {
    RTCDevice device = rtcNewDevice("threads=1");
    if (!device)
      throw std::runtime_error(std::string("Embree: cannot create device: ") +
                               errorName(rtcGetDeviceError(nullptr)));
    EmbreeLibrary found;
    found.major = int(rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION_MAJOR));
    found.minor = int(rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION_MINOR));
    found.patch = int(rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION_PATCH));
    rtcReleaseDevice(device);
    return found;
  }();
  return library;
}

void Accelerator::Impl::recordError(void* userPtr, RTCError code, const char* message) {
  auto& impl = *static_cast<Impl*>(userPtr);
  std::lock_guard lock(impl.errorMutex);
  if (impl.firstError.empty())
    impl.firstError = std::string(errorName(code)) + ": " + (message ? message : "");
}

Accelerator::Impl::~Impl() {
  if (splats.scene) rtcReleaseScene(splats.scene);
  if (scene) rtcReleaseScene(scene);
  if (device) rtcReleaseDevice(device);
}

void Accelerator::Impl::throwIfError(const char* stage) {
  std::string message;
  {
    std::lock_guard lock(errorMutex);
    message = firstError;
  }
  const RTCError code = rtcGetDeviceError(device);
  if (message.empty() && code != RTC_ERROR_NONE) message = errorName(code);
  if (!message.empty()) throw std::runtime_error(std::string("Embree ") + stage + ": " + message);
}

Accelerator::Accelerator(const Scene& scene, const std::optional<std::string>& embreeConfig)
    : Accelerator(scene, AcceleratorOptions{embreeConfig}) {}

Accelerator::Accelerator(const Scene& scene, const AcceleratorOptions& options)
    : impl_(std::make_unique<Impl>()) {
  const std::optional<std::string>& embreeConfig = options.embreeConfig;
  if (options.packetWidth != 0 && options.packetWidth != 4 && options.packetWidth != 8 &&
      options.packetWidth != 16)
    throw InputError("packet width", "", "4, 8 or 16 rays, or 0 for the ISA's own");
  for (size_t i = 0; i < scene.meshes.size(); ++i) checkMesh(scene.meshes[i], i);
  if (scene.meshes.size() + scene.spheres.size() >= RTC_INVALID_GEOMETRY_ID)
    throw std::runtime_error("Embree: too many geometries");

  Impl& impl = *impl_;
  const char* environment = std::getenv(kEmbreeConfigVariable);
  const std::string config = embreeConfig ? *embreeConfig : environment ? environment : "";
  checkIsaName(config, embreeConfig ? "Embree configuration" : kEmbreeConfigVariable);
  impl.device = rtcNewDevice(config.c_str());
  if (!impl.device) {
    const std::string reason = errorName(rtcGetDeviceError(nullptr));
    if (config.empty()) throw std::runtime_error("Embree: cannot create device: " + reason);
    throw InputError(embreeConfig ? "Embree configuration" : kEmbreeConfigVariable, "",
                     "Embree refuses '" + config + "' (" + reason +
                         "); use e.g. isa=avx2 or isa=sse4.2, or leave it unset");
  }
  rtcSetDeviceErrorFunction(impl.device, Impl::recordError, &impl);
  impl.meshCount = uint32_t(scene.meshes.size());
  impl.sphereCount = uint32_t(scene.spheres.size());
  impl.nativePacketWidth = widestNativePacket(impl.device);
  impl.packetWidth = options.packetWidth ? options.packetWidth : 16;
  impl.quality = options.quality;
  if (impl.quality == BuildQuality::Auto)
    impl.quality =
        options.expectedRays <= 0.0 ||
                options.expectedRays >= kHighQualityRaysPerTriangle * double(scene.triangleCount())
            ? BuildQuality::High
            : BuildQuality::Medium;
  const RTCBuildQuality quality =
      impl.quality == BuildQuality::High ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM;

  impl.scene = rtcNewScene(impl.device);
  impl.throwIfError("scene creation");
  // Static scenes are built once and traced many times: the quality follows how many.
  // A moving one is refitted per frame (Embree 3 and 4: RTC_SCENE_FLAG_DYNAMIC with geometries
  // of RTC_BUILD_QUALITY_REFIT keep their BVH's topology and update its bounds).
  impl.dynamic = options.dynamic;
  rtcSetSceneFlags(impl.scene, impl.dynamic ? RTC_SCENE_FLAG_DYNAMIC : RTC_SCENE_FLAG_NONE);
  rtcSetSceneBuildQuality(impl.scene, impl.dynamic ? RTC_BUILD_QUALITY_LOW : quality);

  auto attach = [&](RTCGeometry geometry, uint32_t geomID) {
    if (!geometry) {
      impl.throwIfError("geometry creation");
      throw std::runtime_error("Embree: cannot create a geometry");
    }
    rtcSetGeometryBuildQuality(geometry, impl.dynamic ? RTC_BUILD_QUALITY_REFIT : quality);
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(impl.scene, geometry, geomID);
    rtcReleaseGeometry(geometry);  // the scene holds its own reference
    impl.throwIfError("geometry setup");
  };
  for (uint32_t i = 0; i < impl.meshCount; ++i) {
    attach(newTriangleGeometry(impl.device, scene.meshes[i]), i);
    impl.meshSizes.emplace_back(scene.meshes[i].positions.size(), scene.meshes[i].indices.size());
  }
  for (uint32_t i = 0; i < impl.sphereCount; ++i)
    attach(newSphereGeometry(impl.device, scene.spheres[i]), impl.meshCount + i);

  rtcCommitScene(impl.scene);
  impl.throwIfError("scene build");
  buildSplatStore(impl.device, scene, impl.splats);
  impl.throwIfError("splat build");
}

void Accelerator::refit(const Scene& scene) {
  Impl& impl = *impl_;
  if (scene.meshes.size() != impl.meshCount || scene.spheres.size() != impl.sphereCount)
    throw std::invalid_argument("refit: the scene has other meshes or spheres than the BVH");
  for (uint32_t i = 0; i < impl.meshCount; ++i) {
    const TriangleMesh& mesh = scene.meshes[i];
    if (mesh.positions.size() != impl.meshSizes[i].first ||
        mesh.indices.size() != impl.meshSizes[i].second)
      throw std::invalid_argument("refit: mesh " + std::to_string(i) + " '" + mesh.name +
                                  "' changed its vertex or index count");
    RTCGeometry geometry = rtcGetGeometry(impl.scene, i);
    auto* vertices =
        static_cast<float*>(rtcGetGeometryBufferData(geometry, RTC_BUFFER_TYPE_VERTEX, 0));
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      vertices[3 * v + 0] = mesh.positions[v].x;
      vertices[3 * v + 1] = mesh.positions[v].y;
      vertices[3 * v + 2] = mesh.positions[v].z;
    }
    rtcUpdateGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(geometry);
  }
  for (uint32_t i = 0; i < impl.sphereCount; ++i) {
    const Sphere& sphere = scene.spheres[i];
    RTCGeometry geometry = rtcGetGeometry(impl.scene, impl.meshCount + i);
    auto* point =
        static_cast<float*>(rtcGetGeometryBufferData(geometry, RTC_BUFFER_TYPE_VERTEX, 0));
    point[0] = sphere.center.x, point[1] = sphere.center.y, point[2] = sphere.center.z;
    point[3] = sphere.radius;
    rtcUpdateGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(geometry);
  }
  rtcCommitScene(impl.scene);
  impl.throwIfError("refit");
  // Splat sets move by their placement (a turntable): their frames again, their boxes rebuilt.
  if (scene.splatCount() != impl.splats.frames.size())
    throw std::invalid_argument("refit: the scene has other splats than the BVH");
  if (impl.splats.scene) {
    rebuildSplatStore(scene, impl.splats);
    impl.throwIfError("splat refit");
  }
}

Accelerator::~Accelerator() = default;
Accelerator::Accelerator(Accelerator&&) noexcept = default;

int Accelerator::nextSplats(const Ray& ray, const SplatCursor& after, SplatHit* out, int capacity,
                            uint64_t* evaluated) const {
  // One lane of a packet: the single-ray walk and the packet's are then one code path.
  RayPacket16 packet{};
  for (int lane = 0; lane < 16; ++lane) packet.deactivate(lane);
  packet.set(0, ray);
  SplatCursor cursors[16];
  cursors[0] = after;
  std::vector<SplatHit> hits(size_t(std::max(capacity, 0)) * 16);
  int counts[16];
  walkSplats16(impl_->splats, packet, cursors, hits.data(), capacity, counts, evaluated);
  std::copy_n(hits.begin(), counts[0], out);
  return counts[0];
}

void Accelerator::nextSplats16(const RayPacket16& rays, const SplatCursor after[16], SplatHit* out,
                               int capacity, int counts[16], uint64_t* evaluated) const {
  walkSplats16(impl_->splats, rays, after, out, capacity, counts, evaluated);
}

size_t Accelerator::splatCount() const {
  return impl_->splats.frames.size();
}

int Accelerator::packetWidth() const {
  return impl_->packetWidth;
}
int Accelerator::nativePacketWidth() const {
  return impl_->nativePacketWidth;
}
BuildQuality Accelerator::buildQuality() const {
  return impl_->quality;
}

Hit Accelerator::intersect(const Ray& ray) const {
  if (!traceable(ray)) return Hit{};
  RTCRayHit rayHit;
  fillRay(ray, rayHit.ray);
  rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  EmbreeQuery(EmbreeQuery::Rays::Incoherent).intersect(impl_->scene, rayHit);
  if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return Hit{};
  const RTCHit& h = rayHit.hit;
  return {rayHit.ray.tfar, h.geomID, h.primID, h.u, h.v, {h.Ng_x, h.Ng_y, h.Ng_z}};
}

bool Accelerator::occluded(const Ray& ray) const {
  if (!traceable(ray)) return false;
  RTCRay shadow;
  fillRay(ray, shadow);
  EmbreeQuery(EmbreeQuery::Rays::Incoherent).occluded(impl_->scene, shadow);
  // Embree marks an occluded ray by setting tfar to -infinity.
  return shadow.tfar == -std::numeric_limits<float>::infinity();
}

namespace {

// The calling thread's open PacketLog, if any.
thread_local PacketLog* openPacketLog = nullptr;

}  // namespace

ScopedPacketLog::ScopedPacketLog(PacketLog& log) : outer_(openPacketLog) {
  openPacketLog = &log;
}

ScopedPacketLog::~ScopedPacketLog() {
  openPacketLog = outer_;
}

PARALLAX_LANE_KERNEL void Accelerator::intersect16(const RayPacket16& rays,
                                                   HitPacket16& hits) const {
  if (openPacketLog) openPacketLog->closest.push_back(rays);
  EmbreeQuery query(EmbreeQuery::Rays::Coherent);
  alignas(64) RTCRayHit16 rayHit;
  fillRays(rays, rayHit.ray);
  for (int lane = 0; lane < 16; ++lane) {
    rayHit.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
  }
  alignas(64) int valid[16];
  std::memcpy(valid, rays.active, sizeof(valid));
  if (guardPacket(rayHit.ray, valid) > 0)
    intersectPacket(impl_->packetWidth, valid, impl_->scene, query, rayHit);
  const RTCHit16& h = rayHit.hit;
  for (int lane = 0; lane < 16; ++lane) {
    const bool hit = valid[lane] != 0 && h.geomID[lane] != RTC_INVALID_GEOMETRY_ID;
    // Misses and inactive lanes look exactly like a default Hit, as intersect() returns.
    hits.t[lane] = hit ? rayHit.ray.tfar[lane] : 0.0f;
    hits.geometry[lane] = hit ? h.geomID[lane] : kNoHit;
    hits.primitive[lane] = hit ? h.primID[lane] : 0;
    hits.u[lane] = hit ? h.u[lane] : 0.0f;
    hits.v[lane] = hit ? h.v[lane] : 0.0f;
    hits.ngx[lane] = hit ? h.Ng_x[lane] : 0.0f;
    hits.ngy[lane] = hit ? h.Ng_y[lane] : 0.0f;
    hits.ngz[lane] = hit ? h.Ng_z[lane] : 0.0f;
  }
}

PARALLAX_LANE_KERNEL void Accelerator::occluded16(const RayPacket16& rays,
                                                  bool occludedOut[16]) const {
  if (openPacketLog) openPacketLog->shadow.push_back(rays);
  EmbreeQuery query(EmbreeQuery::Rays::Coherent);
  alignas(64) RTCRay16 shadow;
  fillRays(rays, shadow);
  alignas(64) int valid[16];
  std::memcpy(valid, rays.active, sizeof(valid));
  if (guardPacket(shadow, valid) > 0)
    occludedPacket(impl_->packetWidth, valid, impl_->scene, query, shadow);
  for (int lane = 0; lane < 16; ++lane)
    occludedOut[lane] =
        valid[lane] != 0 && shadow.tfar[lane] == -std::numeric_limits<float>::infinity();
}

SurfaceRef Accelerator::surface(uint32_t geometry) const {
  if (geometry < impl_->meshCount) return {SurfaceRef::Kind::Mesh, geometry};
  if (geometry - impl_->meshCount < impl_->sphereCount)
    return {SurfaceRef::Kind::Sphere, geometry - impl_->meshCount};
  throw std::out_of_range("Accelerator::surface: no geometry " + std::to_string(geometry));
}

namespace {

// Side of the stratified sub-pixel grid: spp rounded down to a square, at least 1.
int strataPerAxis(int samplesPerPixel) {
  int n = 1;
  while ((n + 1) * (n + 1) <= samplesPerPixel) ++n;
  return n;
}

// Shadow rays run from the hit point (t = 0) to the light (t = 1); trimming both ends keeps
// them from re-hitting the surface they start on or a surface the light sits on.
constexpr float kShadowEpsilon = 1e-4f;

}  // namespace

namespace {

// The limit's shading stand-in: one shadow ray from every hit of `primary` toward the light.
// Returns the number of shadow rays traced.
PARALLAX_LANE_KERNEL uint32_t traceRawShadows(int width, RTCScene scene, EmbreeQuery& query,
                                              RTCRayHit16& primary, const int primaryValid[16],
                                              const Vec3f& lightPosition) {
  alignas(64) RTCRay16 shadow;
  alignas(64) int shadowValid[16];
  uint32_t shadowCount = 0;
  for (int lane = 0; lane < 16; ++lane) {
    const bool hit = primaryValid[lane] != 0 && primary.hit.geomID[lane] != RTC_INVALID_GEOMETRY_ID;
    shadowValid[lane] = hit ? -1 : 0;
    shadowCount += hit;
    const float t = hit ? primary.ray.tfar[lane] : 0.0f;
    const Vec3f origin{primary.ray.org_x[lane] + t * primary.ray.dir_x[lane],
                       primary.ray.org_y[lane] + t * primary.ray.dir_y[lane],
                       primary.ray.org_z[lane] + t * primary.ray.dir_z[lane]};
    const Vec3f toLight = lightPosition - origin;  // unnormalised: the light is at t = 1
    shadow.org_x[lane] = origin.x, shadow.org_y[lane] = origin.y;
    shadow.org_z[lane] = origin.z;
    shadow.dir_x[lane] = toLight.x, shadow.dir_y[lane] = toLight.y;
    shadow.dir_z[lane] = toLight.z;
    shadow.tnear[lane] = kShadowEpsilon;
    shadow.tfar[lane] = 1.0f - kShadowEpsilon;
    shadow.time[lane] = 0.0f;
    shadow.mask[lane] = 0xffffffffu;
    shadow.id[lane] = unsigned(lane);
    shadow.flags[lane] = 0;
  }
  shadowCount = uint32_t(guardPacket(shadow, shadowValid));
  if (shadowCount == 0) return 0;
  occludedPacket(width, shadowValid, scene, query, shadow);
  // The occlusion results are otherwise unused; a volatile store keeps them observable.
  uint32_t occluded = 0;
  for (int lane = 0; lane < 16; ++lane) occluded += shadowValid[lane] != 0 && shadow.tfar[lane] < 0;
  volatile uint32_t sink = occluded;
  (void)sink;
  return shadowCount;
}

// The primary rays of a traced packet and how many of them missed.
PARALLAX_LANE_KERNEL void countPrimaries(const RTCRayHit16& primary, const int valid[16],
                                         RawTraceCount& count) {
  for (int lane = 0; lane < 16; ++lane) {
    count.primaryRays += valid[lane] != 0;
    count.primaryMisses += valid[lane] != 0 && primary.hit.geomID[lane] == RTC_INVALID_GEOMETRY_ID;
  }
}

}  // namespace

PARALLAX_LANE_KERNEL RawTraceCount Accelerator::traceRawLimit(const PinholeGrid& grid, int rowBegin,
                                                              int rowEnd,
                                                              const Vec3f& lightPosition) const {
  rowBegin = std::max(rowBegin, 0);
  rowEnd = std::min(rowEnd, grid.height);
  if (rowBegin >= rowEnd || grid.width <= 0) return {};
  const int n = strataPerAxis(grid.samplesPerPixel);

  EmbreeQuery query(EmbreeQuery::Rays::Coherent);  // a 4x4 pixel block shares one eye
  alignas(64) RTCRayHit16 primary;
  alignas(64) int primaryValid[16];
  RawTraceCount count;

  for (int y0 = rowBegin; y0 < rowEnd; y0 += 4)
    for (int x0 = 0; x0 < grid.width; x0 += 4)
      for (int sample = 0; sample < n * n; ++sample) {
        const float jx = (float(sample % n) + 0.5f) / float(n);
        const float jy = (float(sample / n) + 0.5f) / float(n);
        for (int lane = 0; lane < 16; ++lane) {
          const int x = x0 + lane % 4, y = y0 + lane / 4;
          primaryValid[lane] = (x < grid.width && y < rowEnd) ? -1 : 0;
          const Vec3f target =
              grid.pixel00 + (float(x) + jx) * grid.pixelDx + (float(y) + jy) * grid.pixelDy;
          const Vec3f direction = target - grid.eye;
          primary.ray.org_x[lane] = grid.eye.x, primary.ray.org_y[lane] = grid.eye.y;
          primary.ray.org_z[lane] = grid.eye.z;
          primary.ray.dir_x[lane] = direction.x, primary.ray.dir_y[lane] = direction.y;
          primary.ray.dir_z[lane] = direction.z;
          primary.ray.tnear[lane] = 0.0f;
          primary.ray.tfar[lane] = std::numeric_limits<float>::infinity();
          primary.ray.time[lane] = 0.0f;
          primary.ray.mask[lane] = 0xffffffffu;
          primary.ray.id[lane] = unsigned(lane);
          primary.ray.flags[lane] = 0;
          primary.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
          primary.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
        }
        count.rays += uint64_t(guardPacket(primary.ray, primaryValid));
        intersectPacket(impl_->packetWidth, primaryValid, impl_->scene, query, primary);
        countPrimaries(primary, primaryValid, count);
        count.rays += traceRawShadows(impl_->packetWidth, impl_->scene, query, primary,
                                      primaryValid, lightPosition);
      }
  return count;
}

PARALLAX_LANE_KERNEL RawTraceCount Accelerator::traceRawPacket(const RayPacket16& rays,
                                                               const Vec3f& lightPosition) const {
  EmbreeQuery query(EmbreeQuery::Rays::Coherent);
  alignas(64) RTCRayHit16 primary;
  fillRays(rays, primary.ray);
  for (int lane = 0; lane < 16; ++lane) {
    primary.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
    primary.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
  }
  alignas(64) int valid[16];
  std::memcpy(valid, rays.active, sizeof(valid));
  RawTraceCount count;
  count.rays = uint64_t(guardPacket(primary.ray, valid));
  intersectPacket(impl_->packetWidth, valid, impl_->scene, query, primary);
  countPrimaries(primary, valid, count);
  count.rays +=
      traceRawShadows(impl_->packetWidth, impl_->scene, query, primary, valid, lightPosition);
  return count;
}

RawTraceCount Accelerator::replay(const PacketLog& log) const {
  EmbreeQuery query(EmbreeQuery::Rays::Coherent);
  RawTraceCount count;
  alignas(64) int valid[16];
  for (const RayPacket16& rays : log.closest) {
    alignas(64) RTCRayHit16 rayHit;
    fillRays(rays, rayHit.ray);
    for (int lane = 0; lane < 16; ++lane) {
      rayHit.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
      rayHit.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
    }
    std::memcpy(valid, rays.active, sizeof(valid));
    for (int lane = 0; lane < 16; ++lane) count.rays += valid[lane] != 0;
    if (guardPacket(rayHit.ray, valid) > 0)
      intersectPacket(impl_->packetWidth, valid, impl_->scene, query, rayHit);
    countPrimaries(rayHit, valid, count);
  }
  for (const RayPacket16& rays : log.shadow) {
    alignas(64) RTCRay16 shadow;
    fillRays(rays, shadow);
    std::memcpy(valid, rays.active, sizeof(valid));
    for (int lane = 0; lane < 16; ++lane) count.rays += valid[lane] != 0;
    if (guardPacket(shadow, valid) > 0)
      occludedPacket(impl_->packetWidth, valid, impl_->scene, query, shadow);
  }
  return count;
}

}  // namespace parallax
