// Test content for Gaussian splats, since no captured scene can be downloaded here
// (docs/splats.md, "Making splat files"): a scene's surfaces turned into flat Gaussians, and a
// capture-like cloud whose sizes, opacities and harmonics are distributed as trained captures'
// are. Both come out in the frame 3DGS files use (COLMAP's: y down, the cameras looking along
// +z), so that loading them as any capture (up "-y") stands them the right way up.
#pragma once

#include <cstdint>
#include <string>

#include "parallax/jobs/reporter.h"
#include "parallax/jobs/scene_request.h"

#include "parallax/scene/gaussians.h"
#include "parallax/scene/scene.h"

namespace parallax::jobs {

struct SurfaceSplatOptions {
  size_t count = 200000;  // Gaussians over all the scene's triangles, by area
  uint64_t seed = 1;
  float opacity = 0.95f;
  // Each Gaussian's deviation across the surface, in units of the spacing sqrt(area / count),
  // and through it, in units of its deviation across.
  float spread = 0.9f;
  float flatness = 0.05f;
};

// Flat Gaussians on every triangle of `scene` (its meshes' world-space surfaces), spread by
// area, coloured by the albedo there (material, texture, vertex colours) lit as the bare-mesh
// scene's key light and ambient light it, without shadows: degree 0, in the file frame.
// Throws InputError (subject "--count") for a scene without triangles.
GaussianCloud surfaceGaussians(const Scene& scene, const SurfaceSplatOptions& options);

struct CaptureLikeOptions {
  size_t count = 1000000;
  uint64_t seed = 1;
};

// A capture-like cloud of `count` Gaussians (degree 3): 80 % on the surfaces of a subject (a
// knot of spheres and a ground disc), 15 % on a distant backdrop (the far half of a shell: a
// forward-facing capture's), 5 % floating between; log-normal sizes over two decades, most of them
// small and flat; opacities bimodal, as training leaves them (a third near 1, many faint);
// view-dependent colour in the harmonics' higher bands. Deterministic from the seed.
GaussianCloud captureLikeGaussians(const CaptureLikeOptions& options);

// The estimated bytes a cloud of `count` Gaussians of `degree` takes in memory (GaussianCloud)
// and in a 3DGS PLY file.
double splatCloudBytes(size_t count, int degree);
double splatPlyFileBytes(size_t count, int degree);

// `parallax splats from-mesh|capture-like` and Python's make_splats (docs/splats.md): the cloud
// made and written as a 3DGS PLY file, OUTPUT (ending .ply, replaced whole if it exists).
struct SplatMakingRequest {
  enum class Source { Surfaces, CaptureLike };
  Source source = Source::CaptureLike;
  SceneRequest scene;  // Surfaces: the scene whose triangles are covered
  size_t count = 0;    // 0: the source's default
  uint64_t seed = 1;
  std::string output;
};
struct SplatMakingResult {
  size_t gaussians = 0;
  int shDegree = 0;
  double fileBytes = 0;
};
// Refuses (RequestError) an output that is not a .ply path this process can write, a count
// over kMaxMadeSplats or whose cloud and file do not fit the memory limit, before any work.
inline constexpr size_t kMaxMadeSplats = 100000000;
SplatMakingResult runSplatMaking(const SplatMakingRequest& request, Reporter& reporter);

}  // namespace parallax::jobs
