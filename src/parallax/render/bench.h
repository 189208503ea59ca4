// The benchmark: our renderer against raw Embree, measured in one run.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/camera/camera.h"
#include "parallax/display/display_model.h"
#include "parallax/render/render_settings.h"
#include "parallax/scene/scene.h"

namespace parallax {

// Rays traced in a time, with the primary rays among them and how many met nothing.
struct RayRate {
  uint64_t rays = 0;
  uint64_t primaryRays = 0, primaryMisses = 0;
  double seconds = 0.0;
  double perSecond() const { return seconds > 0 ? double(rays) / seconds : 0.0; }
  double missFraction() const {
    return primaryRays > 0 ? double(primaryMisses) / double(primaryRays) : 0.0;
  }
};

struct BenchResult {
  RayRate ours;   // the renderer's loop: primary + shadow + secondary rays, generated and shaded
  RayRate limit;  // raw Embree, coherent pinhole rays: primary + one shadow ray per hit
  // Raw Embree on our camera's own rays in our packet order, the limit's way: with our ray
  // generation (sameRays), and Embree's traversal alone (embreeAlone: each tile's rays made
  // beforehand, untimed; its seconds are the workers' seconds inside Embree over the workers).
  RayRate sameRays, embreeAlone;
  // Embree's traversal alone on every ray the renderer traced (camera, shadow and mirror rays,
  // logged tile by tile as the renderer handed them over, traced again on the clock): what
  // `ours` would take if shading, light sampling and packet copies cost nothing.
  RayRate embreeOnOurs;
  // For a display camera: coherent pinhole rays from each of the display's view eyes, each
  // view at its share of the film's columns (a barrier's nine views: a ninth of the columns
  // each), as many rays in all as the limit's. A display's rays are such bundles, so this is
  // the limit at the density its rays sample the scene with (docs/speed.md, "Display rays on
  // large meshes"); empty (no rays) for the pinhole camera.
  RayRate viewsLimit;
  int packetWidth = 16;        // rays per Embree packet query
  int nativePacketWidth = 16;  // the widest the ISA's kernels run natively
  int workers = 1;

  double ratio() const { return rate(ours, limit); }              // ours / coherent limit
  double viewsRatio() const { return rate(ours, viewsLimit); }    // ours / the views' limit
  double sameRaysRatio() const { return rate(ours, sameRays); }   // what shading costs
  double rayOrderRatio() const { return rate(sameRays, limit); }  // what our rays cost
  // The ray order as Embree alone feels it (ray generation excluded).
  double embreeRayOrderRatio() const { return rate(embreeAlone, limit); }
  // Our ray generation's share of the same-rays loop.
  double rayGenerationShare() const {
    return sameRays.seconds > 0 ? 1.0 - embreeAlone.seconds / sameRays.seconds : 0.0;
  }
  // The seconds our camera spends making its rays (the same-rays loop less Embree's part).
  double rayGenerationSeconds() const {
    return std::max(0.0, sameRays.seconds - embreeAlone.seconds);
  }
  // What our loop spends beyond making camera rays and Embree's traversal of all its rays
  // (shading, light sampling, packet copies), over that traversal: the issue's "within a
  // quarter of Embree's own time" is <= 0.25.
  double shadingOverEmbree() const {
    if (embreeOnOurs.seconds <= 0) return 0.0;
    const double shading = ours.seconds - rayGenerationSeconds() - embreeOnOurs.seconds;
    return std::max(0.0, shading) / embreeOnOurs.seconds;
  }
  // Ours against a loop that makes the same camera rays and traces every ray ours traces
  // without shading them: same_rays_ratio for scenes whose rays differ from the limit's
  // (several lights, mirror bounces).
  double tracedRaysRatio() const {
    return ours.seconds > 0 ? (rayGenerationSeconds() + embreeOnOurs.seconds) / ours.seconds : 0.0;
  }

 private:
  static double rate(const RayRate& a, const RayRate& b) {
    return b.perSecond() > 0 ? a.perSecond() / b.perSecond() : 0.0;
  }
};

// Renders through `camera` with `settings` and traces the raw Embree limits at the same rays
// per pixel, alternating `repeats` times and keeping the fastest of each (the machines are
// noisy): the coherent pinhole rays of `limitGrid` (for the display camera, a pinhole at the
// view-zone centre that sees what the display shows), and the camera's own rays, with and
// without their generation. The gap between the limits is what the camera's ray order costs
// Embree; the gap between the same-rays limit and ours is what shading costs.
// `viewGrids`: the views' limit's pinholes (none for the pinhole camera).
BenchResult benchmark(const Scene& scene, const Accelerator& accelerator, const Camera& camera,
                      const PinholeGrid& limitGrid, const RenderSettings& settings, int repeats = 2,
                      const std::vector<PinholeGrid>& viewGrids = {});

// A lenticular panel's two routes to the same picture, timed in one run (wall seconds with the
// same workers, the fastest of `repeats`): the direct per-subpixel render (renderDisplay), the
// device's own quilt (its calibration's layout and size) at the same samples per pixel
// (renderQuilt), and interlacing that quilt onto the panel (interlaceQuiltLenticular). The
// issue's goal: direct <= quilt.
struct QuiltRouteTimes {
  double direct = 0, quilt = 0, interlace = 0;
  uint64_t directRays = 0, quiltRays = 0;  // all rays traced (camera and shadow)
  int views = 0, tileWidth = 0, tileHeight = 0;
  double directOverQuilt() const { return quilt > 0 ? direct / quilt : 0.0; }
  double directOverRoute() const {
    return quilt + interlace > 0 ? direct / (quilt + interlace) : 0.0;
  }
};
// Bytes the quilt route holds at once (the float quilt, its views and the panel), for the
// caller's memory check before it runs.
double quiltRouteBytes(const DisplayModel& display);
// Whether `display` has a device quilt route to time (a lenticular panel).
bool hasQuiltRoute(const DisplayModel& display);
// Throws std::invalid_argument for a display that is not lenticular.
QuiltRouteTimes benchmarkQuiltRoute(const Scene& scene, const Accelerator& accelerator,
                                    const DisplayModel& display, const RenderSettings& settings,
                                    int repeats = 2);

}  // namespace parallax
