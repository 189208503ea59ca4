// Ray queries against a scene: the only module that talks to Embree. One Accelerator owns the
// Embree device, its error callback and the committed scene. All queries are thread-safe.
// The geometry is copied into Embree's own buffers, so the Scene need not outlive it.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "parallax/accel/splat_hits.h"
#include "parallax/core/math.h"
#include "parallax/core/ray.h"
#include "parallax/scene/scene.h"

namespace parallax {

inline constexpr uint32_t kNoHit = 0xffffffffu;

// What a hit refers to in the Scene.
struct SurfaceRef {
  enum class Kind { Mesh, Sphere };
  Kind kind = Kind::Mesh;
  uint32_t index = 0;  // into Scene::meshes or Scene::spheres
};

struct Hit {
  float t = 0.0f;
  uint32_t geometry = kNoHit;  // pass to Accelerator::surface(); kNoHit if the ray escaped
  uint32_t primitive = 0;      // triangle index within the mesh
  float u = 0.0f, v = 0.0f;    // barycentrics of vertices 1 and 2 (triangles)
  // Unnormalised. Triangles: cross(p1 - p0, p2 - p0), whichever side the ray came from.
  // Spheres: hit point minus centre (length = radius), outward even when the ray starts inside.
  Vec3f geometricNormal;

  bool valid() const { return geometry != kNoHit; }
};

struct alignas(64) HitPacket16 {
  float t[16];
  uint32_t geometry[16];
  uint32_t primitive[16];
  float u[16], v[16];
  float ngx[16], ngy[16], ngz[16];

  Hit hit(int lane) const {
    const Vec3f normal{ngx[lane], ngy[lane], ngz[lane]};
    return {t[lane], geometry[lane], primitive[lane], u[lane], v[lane], normal};
  }
};

// How good a BVH to build. High (Embree's spatial splits) traces a little faster and builds
// about three times slower; it pays only when many rays meet each triangle.
enum class BuildQuality { Auto, Medium, High };

struct AcceleratorOptions {
  // Embree's device configuration ("isa=avx2", ...); without one, the environment's
  // PARALLAX_EMBREE_CONFIG, else Embree's defaults (the best ISA).
  std::optional<std::string> embreeConfig;
  // Rays per packet query handed to Embree: 4, 8 or 16 (a 16-ray packet is then traced as
  // 16 / width queries, skipping those whose lanes are all inactive); 0 = 16 on every ISA.
  // Measured (docs/speed.md, "Packet width"): with AVX2 kernels, whose native packet is 8
  // rays, Embree's own handling of 16-ray queries beats two 8-ray queries by 10 to 20 %; with
  // SSE4.2 (native 4) the two tie.
  int packetWidth = 0;
  BuildQuality quality = BuildQuality::Auto;
  // With Auto: the rays the caller expects to trace (0: unknown, which builds High). High is
  // chosen from kHighQualityRaysPerTriangle rays per triangle up.
  double expectedRays = 0.0;
  // A sequence whose vertices move (scene/motion.h): the BVH is built so that refit() can
  // update it in place (Embree's RTC_BUILD_QUALITY_REFIT, a dynamic scene) instead of building
  // it again every frame.
  bool dynamic = false;
};

// Auto's threshold: below it the medium build's saved time exceeds what the high build saves in
// tracing (measured in docs/speed.md, "BVH quality").
inline constexpr double kHighQualityRaysPerTriangle = 5000.0;

// The options of a job that traces about `cameraRays` camera rays, and about as many shadow
// rays: the BVH quality follows them.
inline AcceleratorOptions acceleratorForCameraRays(double cameraRays) {
  AcceleratorOptions options;
  options.expectedRays = 2.0 * cameraRays;
  return options;
}

// The memory Embree holds for a scene (docs/inputs.md, "Memory"): its device (worker threads,
// caches) and, per triangle, its copy of the vertices and indices and the BVH. Measured as the
// resident memory an Accelerator adds over its heap-trimmed process (grids of 0.18 and 0.98 M
// triangles, the 70 k-triangle bunny; medium and high builds alike): 87 to 143 bytes per
// triangle, fewer on larger meshes, on Embree 3.13 and 4.3.
inline constexpr double kEmbreeDeviceBytes = 2.5e6;
inline constexpr double kEmbreeBytesPerTriangle = 95.0;
// And per Gaussian splat: our frame, opacity and reach (56 bytes) and Embree's BVH over their boxes
// (docs/splats.md, "Memory").
inline constexpr double kAcceleratorBytesPerSplat = 56.0 + 64.0;
inline double acceleratorBytes(const Scene& scene) {
  return kEmbreeDeviceBytes + kEmbreeBytesPerTriangle * double(scene.triangleCount()) +
         kAcceleratorBytesPerSplat * double(scene.splatCount());
}

// The raw limit's counts: every ray traced, and the primary rays and how many of them missed.
struct RawTraceCount {
  uint64_t rays = 0;
  uint64_t primaryRays = 0;
  uint64_t primaryMisses = 0;
  RawTraceCount& operator+=(const RawTraceCount& other) {
    rays += other.rays, primaryRays += other.primaryRays, primaryMisses += other.primaryMisses;
    return *this;
  }
};

// Every packet query a thread sends through intersect16 and occluded16 while a log is open on
// it, as the caller handed them over: the benchmark traces them again to time Embree alone on
// exactly the renderer's rays.
struct PacketLog {
  std::vector<RayPacket16> closest, shadow;
};

// Opens `log` on the calling thread for the scope's lifetime (an outer log is restored after).
class ScopedPacketLog {
 public:
  explicit ScopedPacketLog(PacketLog& log);
  ~ScopedPacketLog();
  ScopedPacketLog(const ScopedPacketLog&) = delete;
  ScopedPacketLog& operator=(const ScopedPacketLog&) = delete;

 private:
  PacketLog* outer_;
};

// The Embree library the program runs on, as the loaded library reports it (Embree 3 on
// Debian 12, Embree 4 on Debian 13): for --version, bench and render.json.
struct EmbreeLibrary {
  int major = 0, minor = 0, patch = 0;
  std::string name() const;  // "Embree 4.3.3"
};
// Asks a device once and remembers the answer. Throws std::runtime_error if Embree cannot make
// a device at all.
const EmbreeLibrary& embreeLibrary();

class Accelerator {
 public:
  // Builds the Embree scene from every mesh and sphere: geometry IDs 0..M-1 are the meshes,
  // M..M+S-1 the spheres. Throws std::runtime_error with Embree's message if the device or the
  // build fails, or naming the mesh if one has an index out of range or a ragged index list.
  // `embreeConfig` is Embree's device configuration ("isa=avx2", "isa=sse4.2", ...); without
  // one, the environment's PARALLAX_EMBREE_CONFIG, else Embree's defaults (the best ISA). A
  // configuration Embree refuses is an InputError naming it.
  explicit Accelerator(const Scene& scene,
                       const std::optional<std::string>& embreeConfig = std::nullopt);
  Accelerator(const Scene& scene, const AcceleratorOptions& options);
  ~Accelerator();
  Accelerator(const Accelerator&) = delete;
  Accelerator& operator=(const Accelerator&) = delete;
  // Movable: the device, its error callback's target and the scene stay where they are.
  Accelerator(Accelerator&&) noexcept;

  Hit intersect(const Ray& ray) const;
  bool occluded(const Ray& ray) const;
  // A ray Embree cannot trace (a non-finite or huge origin or direction, a zero direction, a
  // negative tMin or tMin > tMax) misses everything and is not occluded.
  // Packet forms: inactive lanes are not traced, whatever they hold, on every ISA; their hits
  // read as misses (a default Hit).
  void intersect16(const RayPacket16& rays, HitPacket16& hits) const;
  // occludedOut[lane] is true if something lies within (tMin, tMax) of an active lane.
  void occluded16(const RayPacket16& rays, bool occludedOut[16]) const;

  // The rays per Embree packet query (AcceleratorOptions::packetWidth, resolved) and the BVH
  // quality that was built (Medium or High).
  int packetWidth() const;
  // The widest packet the device's kernels run natively: 16 (AVX-512), 8 (AVX, AVX2) or 4.
  int nativePacketWidth() const;
  BuildQuality buildQuality() const;

  // Takes the moved vertices and sphere centres of `scene`, which must have the meshes and
  // spheres the accelerator was built from (the same counts, vertex counts and indices:
  // poseScene's output), and updates the BVH: refitted when built with
  // AcceleratorOptions::dynamic, else rebuilt. Throws std::invalid_argument when the
  // topology differs.
  void refit(const Scene& scene);

  // The Gaussian splats along `ray` within [ray.tMin, ray.tMax) whose alpha reaches
  // kMinSplatAlpha, after `after`, nearest first (by t, then by index): at most `capacity` of
  // them into `out`, their count returned. A full answer may leave more beyond its last; the
  // walk goes on from there (SplatCursor{last.t, last.gaussian, true}). The same hits whatever
  // order Embree visits them in (3DGRT's k-buffer, docs/splats.md). Adds the responses it
  // evaluated (the walk's cost) to `evaluated` when given.
  int nextSplats(const Ray& ray, const SplatCursor& after, SplatHit* out, int capacity,
                 uint64_t* evaluated = nullptr) const;
  // The same for the active lanes of a packet at once, each from its own cursor
  // (`after[lane]`), its hits into out[lane * capacity ...] and their count into counts[lane]
  // (0 for inactive lanes): one packet query, whose traversal Embree shares among the rays and
  // whose responses are evaluated for all of them together. The same hits as nextSplats for
  // each lane.
  void nextSplats16(const RayPacket16& rays, const SplatCursor after[16], SplatHit* out,
                    int capacity, int counts[16], uint64_t* evaluated = nullptr) const;
  // How many Gaussians the splat BVH holds (Scene::splatCount() of the scene it was built from).
  size_t splatCount() const;

  // Throws std::out_of_range for an ID that is not in the scene (including kNoHit).
  SurfaceRef surface(uint32_t geometry) const;

  // The raw Embree limit for benchmarks: for image rows [rowBegin, rowEnd) of `grid`, traces
  // 4x4-pixel packets of coherent pinhole rays with rtcIntersect16 (one packet per sample
  // index), then one shadow ray per hit toward `lightPosition` with rtcOccluded16; no shading.
  // Callers parallelise over rows.
  RawTraceCount traceRawLimit(const PinholeGrid& grid, int rowBegin, int rowEnd,
                              const Vec3f& lightPosition) const;
  // The same limit on rays someone else made: the active lanes of `rays`, then one shadow ray
  // per hit toward `lightPosition`.
  RawTraceCount traceRawPacket(const RayPacket16& rays, const Vec3f& lightPosition) const;
  // Traces a log's packets again, Embree's traversal and nothing else; counts the active lanes
  // (`rays`) and the closest-hit lanes among them (`primaryRays`, `primaryMisses`).
  RawTraceCount replay(const PacketLog& log) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace parallax
